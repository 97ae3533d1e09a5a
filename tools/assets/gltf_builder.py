"""Small, dependency-free glTF 2.0 writer shared by the asset generators.

Why our own writer: the generators must run with the standard library only
(no numpy, no pygltflib) and must be byte-for-byte reproducible, so every
number that reaches the JSON goes through `num()` (fixed rounding, no -0.0)
and every float that reaches the binary buffer is packed little-endian float32.

Layout rules this writer guarantees (glTF 2.0 spec, section 3.6 / 5.11):
  * one buffer; one bufferView per accessor, tightly packed (no byteStride);
  * every bufferView starts on a 4-byte boundary, so every accessor is aligned
    to its component size;
  * vertex attributes use target 34962 (ARRAY_BUFFER), indices 34963;
  * POSITION accessors carry min/max equal to the float32 values stored;
  * empty top-level arrays are omitted (the schema demands minItems 1).
"""
import json
import math
import os
import struct

FLOAT, USHORT, UINT = 5126, 5123, 5125
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
_NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


class Lcg:
    """Numerical Recipes LCG: a fixed-seed sequence in [0, 1) that cannot change with the
    Python version (the generators' randomness)."""

    def __init__(self, seed):
        self.s = seed & 0xFFFFFFFF

    def next(self):
        self.s = (1664525 * self.s + 1013904223) & 0xFFFFFFFF
        return self.s / 4294967296.0


def num(x, digits=6):
    """Round for JSON so output does not depend on float noise; never -0.0."""
    r = round(float(x), digits)
    return r + 0.0 if r != 0 else 0.0


def nums(v, digits=6):
    return [num(x, digits) for x in v]


def f32(x):
    """The value a float32 store of x will hold (as a Python float)."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


# ---------------------------------------------------------------- vector math
def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def scale(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def quat_axis_angle(axis, angle):
    """glTF quaternion [x, y, z, w] for a rotation of `angle` radians about `axis`."""
    ax = normalize(axis)
    s = math.sin(angle / 2)
    return [ax[0] * s, ax[1] * s, ax[2] * s, math.cos(angle / 2)]


def quat_from_basis(x, y, z):
    """Quaternion of the rotation whose columns are the unit vectors x, y, z."""
    m00, m11, m22 = x[0], y[1], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(y[2] - z[1]) / s, (z[0] - x[2]) / s, (x[1] - y[0]) / s, 0.25 * s]
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = [0.25 * s, (y[0] + x[1]) / s, (z[0] + x[2]) / s, (y[2] - z[1]) / s]
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = [(y[0] + x[1]) / s, 0.25 * s, (z[1] + y[2]) / s, (z[0] - x[2]) / s]
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = [(z[0] + x[2]) / s, (z[1] + y[2]) / s, 0.25 * s, (x[1] - y[0]) / s]
    if q[3] < 0:  # canonical sign so output is stable
        q = [-c for c in q]
    return q


def quat_look(eye, target, up=(0.0, 1.0, 0.0)):
    """Rotation that points a node's local -Z from `eye` toward `target`.

    Cameras (glTF) and EXT_lights_area lights both look/emit along local -Z,
    with local +Y as 'up' (for rect lights: the `size` axis)."""
    f = normalize(sub(target, eye))
    if abs(dot(f, normalize(up))) > 0.999:  # looking straight up/down: pick another up
        up = (0.0, 0.0, -1.0) if f[1] < 0 else (0.0, 0.0, 1.0)
    r = normalize(cross(f, up))
    u = cross(r, f)
    return quat_from_basis(r, u, scale(f, -1.0))


def quat_rotate(q, v):
    x, y, z, w = q
    t = scale(cross((x, y, z), v), 2.0)
    return add(add(v, scale(t, w)), cross((x, y, z), t))


# ---------------------------------------------------------------- mesh helpers
class MeshData:
    """Accumulates positions / normals / uvs / triangle indices."""

    def __init__(self):
        self.pos, self.nrm, self.uv, self.idx = [], [], [], []

    def vertex(self, p, n, uv=(0.0, 0.0)):
        self.pos.append(tuple(p))
        self.nrm.append(tuple(n))
        self.uv.append(tuple(uv))
        return len(self.pos) - 1

    def quad(self, a, b, c, d, n=None, uvs=((0, 0), (1, 0), (1, 1), (0, 1))):
        """Planar quad a-b-c-d, counter-clockwise seen from the side `n` points to.

        The flat normal defaults to Newell's normal of the outline, so slightly
        non-planar measured quads (the Cornell walls) still get one face normal."""
        if n is None:
            pts = (a, b, c, d)
            nx = ny = nz = 0.0
            for i in range(4):
                p, q = pts[i], pts[(i + 1) % 4]
                nx += (p[1] - q[1]) * (p[2] + q[2])
                ny += (p[2] - q[2]) * (p[0] + q[0])
                nz += (p[0] - q[0]) * (p[1] + q[1])
            n = normalize((nx, ny, nz))
        i0 = self.vertex(a, n, uvs[0])
        self.vertex(b, n, uvs[1])
        self.vertex(c, n, uvs[2])
        self.vertex(d, n, uvs[3])
        self.idx += [i0, i0 + 1, i0 + 2, i0, i0 + 2, i0 + 3]

    def box(self, lo, hi, skip=()):
        """Axis-aligned box with outward flat normals; `skip` lists faces to omit
        ('-y' for a box standing on the floor saves hidden triangles)."""
        x0, y0, z0 = lo
        x1, y1, z1 = hi
        faces = {
            "+x": ((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (1, 0, 0)),
            "-x": ((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0), (-1, 0, 0)),
            "+y": ((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0), (0, 1, 0)),
            "-y": ((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1), (0, -1, 0)),
            "+z": ((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1), (0, 0, 1)),
            "-z": ((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (0, 0, -1)),
        }
        for key, (a, b, c, d, n) in faces.items():
            if key not in skip:
                self.quad(a, b, c, d, n)

    def uv_sphere(self, center, radius, seg_u, seg_v):
        """Smooth UV sphere; u wraps around +Y, v = 0 at the north pole.

        Pole rows keep one vertex per segment (for distinct uvs) but emit one
        triangle per segment, so there are no degenerate triangles."""
        base = len(self.pos)
        for j in range(seg_v + 1):
            th = math.pi * j / seg_v
            for i in range(seg_u + 1):
                ph = 2 * math.pi * i / seg_u
                n = (math.sin(th) * math.cos(ph), math.cos(th), -math.sin(th) * math.sin(ph))
                self.vertex(add(center, scale(n, radius)), n, (i / seg_u, j / seg_v))
        row = seg_u + 1
        for j in range(seg_v):
            for i in range(seg_u):
                a, b = base + j * row + i, base + j * row + i + 1
                c, d = a + row, b + row
                if j != 0:
                    self.idx += [a, c, b]
                if j != seg_v - 1:
                    self.idx += [b, c, d]

    def cylinder(self, center, radius, height, seg, caps=(True, True)):
        """Upright cylinder standing on `center` (its bottom centre)."""
        cx, cy, cz = center
        base = len(self.pos)
        for i in range(seg + 1):
            a = 2 * math.pi * i / seg
            n = (math.cos(a), 0.0, -math.sin(a))
            self.vertex((cx + radius * n[0], cy, cz + radius * n[2]), n, (i / seg, 1))
            self.vertex((cx + radius * n[0], cy + height, cz + radius * n[2]), n, (i / seg, 0))
        for i in range(seg):
            a = base + 2 * i
            self.idx += [a, a + 2, a + 1, a + 1, a + 2, a + 3]
        for top, want in ((False, caps[0]), (True, caps[1])):
            if want:
                self.disk((cx, cy + (height if top else 0.0), cz), radius, seg, up=top)

    def disk(self, center, radius, seg, up=True):
        """Horizontal disk facing +Y (up=True) or -Y."""
        n = (0.0, 1.0 if up else -1.0, 0.0)
        c = self.vertex(center, n, (0.5, 0.5))
        for i in range(seg):
            a = 2 * math.pi * i / seg
            p = (center[0] + radius * math.cos(a), center[1], center[2] - radius * math.sin(a))
            self.vertex(p, n, (0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a)))
        for i in range(seg):
            j = c + 1 + i
            k = c + 1 + (i + 1) % seg
            self.idx += [c, j, k] if up else [c, k, j]


# ---------------------------------------------------------------- document
def to_json(obj, indent=""):
    """Indented JSON with short scalar lists kept on one line (diff-friendly)."""
    step = indent + " "
    if isinstance(obj, dict):
        if not obj:
            return "{}"
        items = ",\n".join(step + json.dumps(k) + ": " + to_json(v, step) for k, v in obj.items())
        return "{\n" + items + "\n" + indent + "}"
    if isinstance(obj, list):
        if all(not isinstance(v, (dict, list)) for v in obj) and len(obj) <= 16:
            return "[" + ", ".join(json.dumps(v) for v in obj) + "]"
        return "[\n" + ",\n".join(step + to_json(v, step) for v in obj) + "\n" + indent + "]"
    return json.dumps(obj)


class GltfBuilder:
    def __init__(self, generator):
        self.doc = {"asset": {"version": "2.0", "generator": generator}}
        self.bin = bytearray()
        self.lists = {k: [] for k in ("scenes", "nodes", "cameras", "meshes", "materials",
                                      "accessors", "bufferViews")}
        self.area_lights = []
        self.ext_used = set()
        self.images = []  # (uri, PNG bytes): files beside a .gltf, buffer views in a .glb
        self.textures, self.samplers = [], []

    def _push(self, key, obj):
        self.lists[key].append(obj)
        return len(self.lists[key]) - 1

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        view = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target}
        self.bin += data
        return self._push("bufferViews", view)

    def accessor(self, rows, type_, with_bounds=False):
        """float32 vertex attribute accessor from a list of tuples."""
        flat = [c for r in rows for c in r]
        view = self._view(struct.pack("<%df" % len(flat), *flat), ARRAY_BUFFER)
        acc = {"bufferView": view, "componentType": FLOAT, "count": len(rows), "type": type_}
        if with_bounds:
            n = _NCOMP[type_]
            acc["min"] = [min(f32(r[i]) for r in rows) + 0.0 for i in range(n)]
            acc["max"] = [max(f32(r[i]) for r in rows) + 0.0 for i in range(n)]
        return self._push("accessors", acc)

    def index_accessor(self, idx, vertex_count):
        big = vertex_count > 65535
        fmt, ctype = ("<%dI", UINT) if big else ("<%dH", USHORT)
        data = struct.pack(fmt % len(idx), *idx)
        view = self._view(data, ELEMENT_ARRAY_BUFFER)
        return self._push("accessors", {"bufferView": view, "componentType": ctype,
                                        "count": len(idx), "type": "SCALAR"})

    def primitive(self, mesh, material, uvs=True):
        """Write a MeshData's arrays; returns a glTF primitive dict."""
        attrs = {"POSITION": self.accessor(mesh.pos, "VEC3", with_bounds=True),
                 "NORMAL": self.accessor(mesh.nrm, "VEC3")}
        if uvs:
            attrs["TEXCOORD_0"] = self.accessor(mesh.uv, "VEC2")
        prim = {"attributes": attrs, "indices": self.index_accessor(mesh.idx, len(mesh.pos)),
                "mode": 4}
        if material is not None:
            prim["material"] = material
        return prim

    def texture(self, png, uri, nearest=False):
        """A PNG texture; `nearest` samples it without filtering or mipmaps."""
        self.images.append((uri, png))
        tex = {"source": len(self.images) - 1}
        if nearest:
            self.samplers.append({"magFilter": 9728, "minFilter": 9728})
            tex["sampler"] = len(self.samplers) - 1
        self.textures.append(tex)
        return len(self.textures) - 1

    def material(self, name, base, metallic=0.0, roughness=1.0, emissive=None, strength=1.0,
                 alpha=1.0, alpha_mode=None, double_sided=False, base_texture=None,
                 extensions=None):
        """`extensions`: {"KHR_materials_x": {...}} added to the material (and to
        extensionsUsed)."""
        pbr = {"baseColorFactor": nums(list(base) + [alpha]),
               "metallicFactor": num(metallic),
               "roughnessFactor": num(roughness)}
        if base_texture is not None:
            pbr["baseColorTexture"] = {"index": base_texture}
        m = {"name": name, "pbrMetallicRoughness": pbr}
        if alpha_mode is not None:
            m["alphaMode"] = alpha_mode
        if double_sided:
            m["doubleSided"] = True
        if emissive is not None:
            m["emissiveFactor"] = nums(emissive)
            if strength != 1.0:
                m["extensions"] = {"KHR_materials_emissive_strength":
                                   {"emissiveStrength": num(strength)}}
                self.ext_used.add("KHR_materials_emissive_strength")
        for key, value in (extensions or {}).items():
            m.setdefault("extensions", {})[key] = value
            self.ext_used.add(key)
        return self._push("materials", m)

    def mesh(self, name, prims):
        return self._push("meshes", {"name": name, "primitives": prims})

    def node(self, name, mesh=None, camera=None, translation=None, rotation=None,
             scale_=None, children=None, extensions=None, extras=None):
        n = {"name": name}
        for key, val in (("mesh", mesh), ("camera", camera), ("children", children)):
            if val is not None:
                n[key] = val
        if rotation is not None:
            n["rotation"] = nums(rotation, 9)
        if scale_ is not None:
            n["scale"] = nums(scale_)
        if translation is not None:
            n["translation"] = nums(translation)
        if extensions:
            n["extensions"] = extensions
        if extras:
            n["extras"] = extras
        return self._push("nodes", n)

    def camera(self, name, yfov, aspect, znear, zfar):
        persp = {"yfov": num(yfov, 7), "znear": num(znear), "zfar": num(zfar)}
        if aspect:
            persp["aspectRatio"] = num(aspect, 7)
        return self._push("cameras", {"name": name, "type": "perspective", "perspective": persp})

    def material_nodes(self, meshes, materials):
        """One node per non-empty MeshData of `meshes`, with the material `materials[name]` =
        (base colour, metallic, roughness) of the same name. Returns the nodes."""
        nodes = []
        for name, (base, metal, rough) in materials.items():
            if meshes[name].idx:
                mat = self.material(name, base, metallic=metal, roughness=rough)
                mi = self.mesh(name, [self.primitive(meshes[name], mat)])
                nodes.append(self.node(name, mesh=mi))
        return nodes

    def lamp_node(self, name, kind, color, intensity, size, aspect, proxy, pos, target):
        """An EXT_lights_area light at `pos` facing `target`, with its emissive stand-in `proxy`
        (MeshData) as a child tagged extras.area_light_proxy. Returns the light's node."""
        ext = self.area_light(name, kind, color, intensity, size, aspect)
        lamp = self.material(name + "_surface", (0.0, 0.0, 0.0), emissive=color, strength=intensity)
        pm = self.mesh(name + "_surface", [self.primitive(proxy, lamp)])
        child = self.node(name + "_surface", mesh=pm,
                          extras={"area_light_proxy": len(self.area_lights) - 1})
        return self.node(name, translation=pos, rotation=quat_look(pos, target), extensions=ext,
                         children=[child])

    def area_light(self, name, kind, color, intensity, size, aspect=None):
        """EXT_lights_area light (draft vendor extension, KhronosGroup/glTF PR 2525).
        Emits one-sided toward local -Z; `size` is the local-Y extent (rect) or
        the diameter (disk); rect width = size * aspect along local X."""
        light = {"name": name, "type": kind, "color": nums(color), "intensity": num(intensity),
                 "size": num(size)}
        if kind == "rect":
            light["rect"] = {"aspect": num(aspect if aspect else 1.0)}
        self.area_lights.append(light)
        self.ext_used.add("EXT_lights_area")
        return {"EXT_lights_area": {"light": len(self.area_lights) - 1}}

    def scene(self, name, nodes):
        self.doc["scene"] = self._push("scenes", {"name": name, "nodes": nodes})

    def _finish(self, uri):
        while len(self.bin) % 4:
            self.bin.append(0)
        doc = dict(self.doc)
        if self.ext_used:
            doc["extensionsUsed"] = sorted(self.ext_used)
        for key in ("scenes", "nodes", "cameras", "meshes", "materials", "accessors",
                    "bufferViews"):
            if self.lists[key]:
                doc[key] = self.lists[key]
        if self.images:
            if uri:
                doc["images"] = [{"uri": name} for name, _ in self.images]
            else:
                doc["images"] = []
                for _, png in self.images:
                    view = len(self.lists["bufferViews"])
                    self._view(png, None)
                    del self.lists["bufferViews"][view]["target"]
                    doc["images"].append({"bufferView": view, "mimeType": "image/png"})
                doc["bufferViews"] = self.lists["bufferViews"]
                while len(self.bin) % 4:
                    self.bin.append(0)
            doc["textures"] = self.textures
            if self.samplers:
                doc["samplers"] = self.samplers
        buf = {"byteLength": len(self.bin)}
        if uri:
            buf["uri"] = uri
        doc["buffers"] = [buf]
        if self.area_lights:
            doc["extensions"] = {"EXT_lights_area": {"lights": self.area_lights}}
        return doc

    def write_gltf(self, path):
        """Writes `path` (.gltf, JSON) and its sibling .bin."""
        bin_name = os.path.splitext(os.path.basename(path))[0] + ".bin"
        doc = self._finish(bin_name)
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(to_json(doc) + "\n")
        with open(os.path.join(os.path.dirname(os.path.abspath(path)), bin_name), "wb") as f:
            f.write(self.bin)
        for name, png in self.images:
            with open(os.path.join(os.path.dirname(os.path.abspath(path)), name), "wb") as f:
                f.write(png)

    def write_glb(self, path):
        """Binary container: 12-byte header, JSON chunk padded with spaces,
        BIN chunk padded with zeros (glTF 2.0 spec, section 4.4)."""
        doc = self._finish(None)
        js = json.dumps(doc, separators=(",", ":")).encode("utf-8")
        js += b" " * (-len(js) % 4)
        total = 12 + 8 + len(js) + 8 + len(self.bin)
        out = struct.pack("<III", 0x46546C67, 2, total)
        out += struct.pack("<II", len(js), 0x4E4F534A) + js
        out += struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin)
        os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
        with open(path, "wb") as f:
            f.write(out)


def out_path(argv, default_dir, filename):
    """Generators take an optional output folder (used by the reproducibility test)."""
    import argparse
    ap = argparse.ArgumentParser(description="Writes %s (deterministic)." % filename)
    ap.add_argument("--out-dir", default=default_dir,
                    help="output folder (default: %(default)s)")
    args = ap.parse_args(argv)
    return os.path.join(args.out_dir, filename)


def repo_assets(*parts):
    """Default output folder: <repo>/assets/<parts> relative to this file."""
    here = os.path.dirname(os.path.abspath(__file__))
    return os.path.normpath(os.path.join(here, "..", "..", "assets", *parts))
