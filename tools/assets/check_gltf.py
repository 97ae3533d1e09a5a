#!/usr/bin/env python3
"""Structural checker for the generated .gltf / .glb / .hdr assets (stdlib only).

Not a full Khronos glTF-Validator: it checks what our generators could get
wrong and what the Penumbra loader relies on, then prints a summary.
  * buffers / bufferViews / accessors in range, 4-byte aligned views,
    valid componentType / type / target;
  * POSITION min/max present and equal to the stored float32 values;
  * index accessors: unsigned type, count % 3 == 0, every index < vertex count;
  * attributes of a primitive share one count; NORMALs unit length and on the
    front side of each triangle's winding (CCW = front, spec 3.7.2.1);
  * node graph: valid references, no node with two parents, no cycles;
  * cameras and EXT_lights_area lights well formed, extensionsUsed complete.
Radiance .hdr files: header, resolution line, pixel count, min/max/mean.
Usage: check_gltf.py FILE... ; exit status 1 if any error was found.
"""
import json
import math
import os
import struct
import sys

# The EXT_lights_area shapes this reader knows: renderer/src/scene/light_kinds.cpp's area rows
# (tests/cli/light_readers.sh fails when a shape there is missing here).
AREA_SHAPES = ('rect', 'disk')

COMP = {5120: ("b", 1), 5121: ("B", 1), 5122: ("h", 2), 5123: ("H", 2), 5125: ("I", 4),
        5126: ("f", 4)}
NCOMP = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT2": 4, "MAT3": 9, "MAT4": 16}


class Checker:
    def __init__(self, path):
        self.path, self.errors = path, []

    def err(self, msg):
        self.errors.append(msg)

    # ------------------------------------------------------------ loading
    def load(self):
        raw = open(self.path, "rb").read()
        if self.path.endswith(".glb"):
            magic, version, length = struct.unpack_from("<III", raw, 0)
            if magic != 0x46546C67 or version != 2 or length != len(raw):
                self.err("bad GLB header")
            jlen, jtype = struct.unpack_from("<II", raw, 12)
            if jtype != 0x4E4F534A or jlen % 4:
                self.err("bad JSON chunk")
            self.doc = json.loads(raw[20:20 + jlen].decode("utf-8"))
            off = 20 + jlen
            blen, btype = struct.unpack_from("<II", raw, off)
            if btype != 0x004E4942 or blen % 4:
                self.err("bad BIN chunk")
            glb_bin = raw[off + 8:off + 8 + blen]
        else:
            self.doc = json.loads(raw.decode("utf-8"))
            glb_bin = None
        self.buffers = []
        for i, buf in enumerate(self.doc.get("buffers", [])):
            if "uri" in buf:
                p = os.path.join(os.path.dirname(self.path), buf["uri"])
                data = open(p, "rb").read() if os.path.exists(p) else b""
                if not data:
                    self.err("buffer %d: %s missing" % (i, buf["uri"]))
            else:
                data = glb_bin or b""
            if len(data) < buf["byteLength"]:
                self.err("buffer %d: %d bytes < byteLength %d" % (i, len(data), buf["byteLength"]))
            self.buffers.append(data)

    def read_accessor(self, ai):
        acc = self.doc["accessors"][ai]
        fmt, size = COMP[acc["componentType"]]
        n = NCOMP[acc["type"]]
        view = self.doc["bufferViews"][acc["bufferView"]]
        stride = view.get("byteStride", size * n)
        base = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        data = self.buffers[view["buffer"]]
        return [struct.unpack_from("<%d%s" % (n, fmt), data, base + k * stride)
                for k in range(acc["count"])]

    # ------------------------------------------------------------ checks
    def check_layout(self):
        doc = self.doc
        if doc.get("asset", {}).get("version") != "2.0":
            self.err("asset.version must be '2.0'")
        for i, v in enumerate(doc.get("bufferViews", [])):
            end = v.get("byteOffset", 0) + v["byteLength"]
            if v["buffer"] >= len(self.buffers) or end > doc["buffers"][v["buffer"]]["byteLength"]:
                self.err("bufferView %d out of its buffer" % i)
            if v.get("byteOffset", 0) % 4:
                self.err("bufferView %d byteOffset not 4-aligned" % i)
            if v.get("target") not in (None, 34962, 34963):
                self.err("bufferView %d bad target" % i)
        for i, a in enumerate(doc.get("accessors", [])):
            if a.get("componentType") not in COMP or a.get("type") not in NCOMP:
                self.err("accessor %d bad componentType/type" % i)
                continue
            if a["count"] < 1:
                self.err("accessor %d count < 1" % i)
            v = doc["bufferViews"][a["bufferView"]]
            size = COMP[a["componentType"]][1]
            elem = size * NCOMP[a["type"]]
            stride = v.get("byteStride", elem)
            if (v.get("byteOffset", 0) + a.get("byteOffset", 0)) % size:
                self.err("accessor %d misaligned" % i)
            if a.get("byteOffset", 0) + stride * (a["count"] - 1) + elem > v["byteLength"]:
                self.err("accessor %d overruns bufferView %d" % (i, a["bufferView"]))

    def check_meshes(self):
        doc, self.mesh_tris = self.doc, {}
        for mi, mesh in enumerate(doc.get("meshes", [])):
            tris = 0
            for pi, prim in enumerate(mesh["primitives"]):
                where = "mesh %d (%s) prim %d" % (mi, mesh.get("name", ""), pi)
                attrs = prim["attributes"]
                counts = {doc["accessors"][a]["count"] for a in attrs.values()}
                if len(counts) != 1:
                    self.err(where + ": attribute counts differ")
                nverts = counts.pop()
                pa = doc["accessors"][attrs["POSITION"]]
                pos = self.read_accessor(attrs["POSITION"])
                if "min" not in pa or "max" not in pa:
                    self.err(where + ": POSITION lacks min/max")
                else:
                    for k in range(3):
                        lo = min(p[k] for p in pos)
                        hi = max(p[k] for p in pos)
                        if lo != pa["min"][k] or hi != pa["max"][k]:
                            self.err(where + ": POSITION min/max differ from data (axis %d)" % k)
                if prim.get("mode", 4) != 4:
                    self.err(where + ": only triangles expected")
                if "indices" in prim:
                    ia = doc["accessors"][prim["indices"]]
                    if ia["componentType"] not in (5121, 5123, 5125) or ia["type"] != "SCALAR":
                        self.err(where + ": bad index accessor type")
                    v = doc["bufferViews"][ia["bufferView"]]
                    if v.get("target") != 34963:
                        self.err(where + ": index view target should be 34963")
                    idx = [t[0] for t in self.read_accessor(prim["indices"])]
                else:
                    idx = list(range(nverts))
                if len(idx) % 3:
                    self.err(where + ": index count not a multiple of 3")
                if idx and max(idx) >= nverts:
                    self.err(where + ": index %d >= vertex count %d" % (max(idx), nverts))
                    continue
                tris += len(idx) // 3
                if "NORMAL" in attrs:
                    self.check_normals(where, pos, self.read_accessor(attrs["NORMAL"]), idx)
                if "material" in prim and prim["material"] >= len(doc.get("materials", [])):
                    self.err(where + ": material out of range")
            self.mesh_tris[mi] = tris

    def check_normals(self, where, pos, nrm, idx):
        bad_len = sum(1 for n in nrm if abs(math.sqrt(n[0]**2 + n[1]**2 + n[2]**2) - 1) > 1e-3)
        if bad_len:
            self.err(where + ": %d normals not unit length" % bad_len)
        back = degenerate = 0
        for t in range(0, len(idx) - 2, 3):
            a, b, c = (pos[idx[t + k]] for k in range(3))
            e1 = [b[k] - a[k] for k in range(3)]
            e2 = [c[k] - a[k] for k in range(3)]
            g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0])
            if g[0] ** 2 + g[1] ** 2 + g[2] ** 2 < 1e-24:
                degenerate += 1
                continue
            ns = [sum(nrm[idx[t + k]][j] for k in range(3)) for j in range(3)]
            if g[0] * ns[0] + g[1] * ns[1] + g[2] * ns[2] <= 0:
                back += 1
        if back:
            self.err(where + ": %d triangles whose winding disagrees with NORMAL" % back)
        if degenerate:
            self.err(where + ": %d degenerate triangles" % degenerate)

    def world_matrices(self):
        nodes = self.doc.get("nodes", [])
        parent = {}
        for i, n in enumerate(nodes):
            for c in n.get("children", []):
                if c >= len(nodes):
                    self.err("node %d: child %d out of range" % (i, c))
                elif c in parent:
                    self.err("node %d has two parents" % c)
                else:
                    parent[c] = i
        self.world = {}

        def local(n):
            if "matrix" in n:
                m = n["matrix"]
                return [[m[c * 4 + r] for c in range(4)] for r in range(4)]
            x, y, z, w = n.get("rotation", [0, 0, 0, 1])
            sx, sy, sz = n.get("scale", [1, 1, 1])
            t = n.get("translation", [0, 0, 0])
            r = [[1 - 2 * (y*y + z*z), 2 * (x*y - z*w), 2 * (x*z + y*w)],
                 [2 * (x*y + z*w), 1 - 2 * (x*x + z*z), 2 * (y*z - x*w)],
                 [2 * (x*z - y*w), 2 * (y*z + x*w), 1 - 2 * (x*x + y*y)]]
            return [[r[i][0] * sx, r[i][1] * sy, r[i][2] * sz, t[i]] for i in range(3)] + \
                [[0, 0, 0, 1]]

        def mul(a, b):
            return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]

        def visit(i, m, depth):
            if depth > len(nodes):
                self.err("node cycle at %d" % i)
                return
            self.world[i] = mul(m, local(nodes[i]))
            for c in nodes[i].get("children", []):
                if c < len(nodes):
                    visit(c, self.world[i], depth + 1)

        ident = [[1 if i == j else 0 for j in range(4)] for i in range(4)]
        for s in self.doc.get("scenes", []):
            for r in s["nodes"]:
                if r in parent:
                    self.err("scene root %d is a child" % r)
                visit(r, ident, 0)

    @staticmethod
    def xform(m, p, w=1.0):
        return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] * w
                     for i in range(3))

    def check_extras(self):
        doc = self.doc
        used = set(doc.get("extensionsUsed", []))
        if not set(doc.get("extensionsRequired", [])) <= used:
            self.err("extensionsRequired not a subset of extensionsUsed")
        seen = set(doc.get("extensions", {}))
        for key in ("nodes", "materials"):
            for o in doc.get(key, []):
                seen |= set(o.get("extensions", {}))
        if seen - used:
            self.err("extensions not declared in extensionsUsed: %s" % sorted(seen - used))
        for i, c in enumerate(doc.get("cameras", [])):
            p = c.get("perspective", {})
            if c.get("type") != "perspective" or not 0 < p.get("yfov", 0) < math.pi or \
               p.get("znear", 0) <= 0 or p.get("zfar", math.inf) <= p["znear"]:
                self.err("camera %d malformed" % i)
        self.lights = doc.get("extensions", {}).get("EXT_lights_area", {}).get("lights", [])
        for i, lt in enumerate(self.lights):
            ok = lt.get("type") in AREA_SHAPES and lt.get("size", 1.0) > 0 and \
                lt.get("intensity", 1000.0) > 0 and \
                all(0 <= c <= 1 for c in lt.get("color", [1, 1, 1])) and \
                (lt["type"] != "rect" or "rect" in lt)
            if not ok:
                self.err("EXT_lights_area light %d malformed" % i)
        for i, n in enumerate(doc.get("nodes", [])):
            ext = n.get("extensions", {}).get("EXT_lights_area")
            if ext is not None and not 0 <= ext.get("light", -1) < len(self.lights):
                self.err("node %d: light index out of range" % i)
            if n.get("mesh", 0) >= len(doc.get("meshes", [])) or \
               n.get("camera", 0) >= len(doc.get("cameras", [1])):
                self.err("node %d: mesh/camera out of range" % i)

    def bounds(self):
        """World bounds (lo, hi) of the meshes' POSITION min/max boxes (after world_matrices)."""
        doc, lo, hi = self.doc, [math.inf] * 3, [-math.inf] * 3
        for i, m in self.world.items():
            n = doc["nodes"][i]
            for prim in doc["meshes"][n["mesh"]]["primitives"] if "mesh" in n else []:
                a = doc["accessors"][prim["attributes"]["POSITION"]]
                for c in range(8):
                    w = self.xform(m, [(a["max"] if c >> k & 1 else a["min"])[k] for k in range(3)])
                    lo = [min(lo[k], w[k]) for k in range(3)]
                    hi = [max(hi[k], w[k]) for k in range(3)]
        return lo, hi

    def summary(self):
        doc = self.doc
        tris = sum(self.mesh_tris.get(doc["nodes"][i]["mesh"], 0) for i in self.world
                   if "mesh" in doc["nodes"][i])
        lo, hi = self.bounds()
        size = sum(len(b) for b in self.buffers)
        print("%s: %d triangles (instanced), %d meshes, %d materials, buffer %d bytes" %
              (self.path, tris, len(doc.get("meshes", [])), len(doc.get("materials", [])), size))
        print("  bounds min %s max %s" % (fmt(lo), fmt(hi)))
        for i, m in sorted(self.world.items()):
            n = doc["nodes"][i]
            pos = self.xform(m, (0, 0, 0))
            fwd = self.xform(m, (0, 0, -1), 0.0)
            if "camera" in n:
                c = doc["cameras"][n["camera"]]["perspective"]
                print("  camera '%s' at %s looking %s yfov %.2f deg aspect %s" %
                      (n.get("name"), fmt(pos), fmt(fwd), math.degrees(c["yfov"]),
                       c.get("aspectRatio", "viewport")))
            ext = n.get("extensions", {}).get("EXT_lights_area")
            if ext is not None and ext.get("light", -1) < len(self.lights):
                lt = self.lights[ext["light"]]
                s = lt.get("size", 1.0)
                area = s * s * lt["rect"].get("aspect", 1.0) if lt["type"] == "rect" \
                    else math.pi * s * s / 4
                L = lt.get("intensity", 1000.0)
                print("  light '%s' %s at %s emitting %s size %.4g area %.4g m^2 "
                      "radiance %s flux %.4g" % (n.get("name"), lt["type"], fmt(pos), fmt(fwd),
                                                 s, area, fmt([L * c for c in lt["color"]]),
                                                 L * area * math.pi))


def fmt(v):
    return "(" + ", ".join("%.4g" % x for x in v) + ")"


def check_hdr(path):
    raw = open(path, "rb").read()
    errs = []
    end = raw.find(b"\n\n")
    header = raw[:end].decode("ascii", "replace").split("\n")
    if header[0] not in ("#?RADIANCE", "#?RGBE") or "FORMAT=32-bit_rle_rgbe" not in header:
        errs.append("bad header")
    nl = raw.index(b"\n", end + 2)
    res = raw[end + 2:nl].decode("ascii").split()
    h, w = int(res[1]), int(res[3])
    if res[0] != "-Y" or res[2] != "+X":
        errs.append("unexpected orientation %s" % res)
    px = raw[nl + 1:]
    if len(px) != 4 * w * h:
        errs.append("expected %d flat pixel bytes, found %d" % (4 * w * h, len(px)))
    vals = []
    for k in range(0, min(len(px), 4 * w * h), 4):
        e = px[k + 3]
        f = math.ldexp(1.0, e - 136) if e else 0.0
        vals.append((px[k] * f, px[k + 1] * f, px[k + 2] * f))
    lum = [0.2126 * r + 0.7152 * g + 0.0722 * b for r, g, b in vals]
    print("%s: %d x %d RGBE, luminance min %.4g max %.4g mean %.4g" %
          (path, w, h, min(lum), max(lum), sum(lum) / len(lum)))
    return errs


def main(paths):
    failed = 0
    for p in paths:
        if p.endswith(".hdr"):
            errs = check_hdr(p)
        else:
            c = Checker(p)
            try:
                c.load()
                c.check_layout()
                c.check_meshes()
                c.world_matrices()
                c.check_extras()
                c.summary()
            except (KeyError, IndexError, ValueError, struct.error) as e:
                c.err("exception %r" % e)
            errs = c.errors
        for e in errs:
            print("  ERROR %s: %s" % (p, e))
        failed += bool(errs)
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1:]))
