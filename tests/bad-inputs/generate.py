#!/usr/bin/env python3
"""Writes every input of the bad-input catalogue (tests/bad-inputs/cases.tsv) into OUTDIR.
Stdlib only; each file is a few KB at most. Usage: python3 generate.py OUTDIR
Inputs are generated rather than committed so that each one is reviewable as code: the one
thing wrong with it is the line that makes it."""
import base64, json, math, os, struct, sys, zlib

OUT = sys.argv[1]
os.makedirs(OUT, exist_ok=True)


def write(name, data):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)


def png(w, h, rgba=lambda x, y: (200, 200, 200, 255), idat=None):
    if idat is None:
        raw = b"".join(b"\0" + b"".join(bytes(rgba(x, y)) for x in range(w)) for y in range(h))
        idat = zlib.compress(raw)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", idat) + chunk(b"IEND", b""))


def glb(doc, binary=b""):
    j = json.dumps(doc, separators=(",", ":")).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j
    if binary:
        binary += b"\0" * (-len(binary) % 4)
        body += struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def model(positions, indices=None, extra=None, nodes=None, binary_extra=b""):
    """A one-mesh glTF document with an embedded buffer; returns the dict."""
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}]
    finite = [p for p in positions if all(math.isfinite(c) for c in p)] or [(0, 0, 0)]
    acc = [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
            "min": [min(p[i] for p in finite) for i in range(3)],
            "max": [max(p[i] for p in finite) for i in range(3)]}]
    binary = pos
    prim = {"attributes": {"POSITION": 0}}
    if indices is not None:
        ib = struct.pack("<%dI" % len(indices), *indices)
        views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(ib)})
        acc.append({"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
        binary += ib
        prim["indices"] = 1
    binary += binary_extra
    doc = {"asset": {"version": "2.0"}, "scene": 0,
           "scenes": [{"nodes": nodes if nodes is not None else [0]}],
           "nodes": [{"mesh": 0}], "meshes": [{"primitives": [prim]}],
           "buffers": [{"byteLength": len(binary), "uri": uri(binary)}],
           "bufferViews": views, "accessors": acc}
    if extra:
        extra(doc)
    return doc


TRI = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
# A unit cube around the origin (12 triangles), for the camera-inside-geometry case.
CUBE_P = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_I = [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4,
          1, 5, 7, 1, 7, 3]


def dump(name, doc):
    write(name, json.dumps(doc, indent=1))


good = model(TRI)
good_glb_doc = json.loads(json.dumps(good))
good_bin = base64.b64decode(good_glb_doc["buffers"][0].pop("uri").split(",", 1)[1])
good_glb = glb(good_glb_doc, good_bin)

# --- container level -----------------------------------------------------------------------
write("truncated.glb", good_glb[: len(good_glb) // 2])
write("wrong_magic.glb", b"GLTX" + good_glb[4:])
write("glb_version1.glb", good_glb[:4] + struct.pack("<I", 1) + good_glb[8:])
write("glb_gigabyte_length.glb", good_glb[:8] + struct.pack("<I", 0xFFFFFFF0) + good_glb[12:])
bad_chunk = bytearray(good_glb)
struct.pack_into("<I", bad_chunk, 12, 0xFFFFFF00)  # JSON chunk claims ~4 GB
write("glb_gigabyte_chunk.glb", bytes(bad_chunk))
write("glb_not_json.glb", glb_raw := (struct.pack("<III", 0x46546C67, 2, 12 + 8 + 8) +
                                      struct.pack("<II", 8, 0x4E4F534A) + b"{not js}"))
write("empty_file.gltf", b"")
write("not_gltf.gltf", "[1, 2, 3]")

# --- declared sizes and references -----------------------------------------------------------
d = model(TRI)
d["buffers"].append({"byteLength": 6_000_000_000, "uri": uri(b"tiny")})  # claims 6 GB
d["bufferViews"].append({"buffer": 1, "byteOffset": 0, "byteLength": 5_999_999_999})
d["accessors"].append({"bufferView": 1, "componentType": 5126, "count": 499_999_999, "type": "VEC3"})
d["meshes"][0]["primitives"].append({"attributes": {"POSITION": 1}})
dump("gigabyte_buffer.gltf", d)
d = model(TRI)
d["accessors"][0]["count"] = 1_000_000  # far beyond the 36-byte view
dump("accessor_out_of_range.gltf", d)
d = model(TRI)
d["accessors"][0]["byteOffset"] = 4096
dump("accessor_offset_out_of_range.gltf", d)
dump("index_out_of_range.gltf", model(TRI, indices=[0, 1, 300]))
dump("mesh_index_out_of_range.gltf", model(TRI, extra=lambda d: d["nodes"][0].update(mesh=7)))
d = model(TRI)
d["buffers"][0] = {"byteLength": 36, "uri": "missing.bin"}
dump("missing_buffer_file.gltf", d)
dump("cyclic_nodes.gltf", model(TRI, extra=lambda d: d["nodes"].extend(
    [{"children": [2]}, {"children": [1], "mesh": 0}]) or d["scenes"][0]["nodes"].append(1)))
dump("self_parent_node.gltf", model(TRI, extra=lambda d: d["nodes"][0].update(children=[0])))
dump("required_extension.gltf", model(TRI, extra=lambda d: d.update(
    extensionsUsed=["EXT_penumbra_unknown"], extensionsRequired=["EXT_penumbra_unknown"])))

# --- geometry --------------------------------------------------------------------------------
nan = float("nan")
# NaN and Inf live in the binary buffer (JSON cannot carry them).
dump("nan_positions.gltf", model([(nan, 0, 0), (1, nan, 0), (0, 1, float("inf"))]))
dump("degenerate_triangles.gltf", model([(0, 0, 0), (0, 0, 0), (0, 0, 0), (1, 1, 1), (2, 2, 2), (3, 3, 3)]))
dump("empty_scene.gltf", {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}]})
dump("no_scenes.gltf", {"asset": {"version": "2.0"}})


def cam_inside(d):
    d["nodes"].append({"camera": 0, "translation": [0, 0, 0.2]})
    d["scenes"][0]["nodes"].append(1)
    d["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05}}]
dump("camera_inside_geometry.gltf", model(CUBE_P, indices=CUBE_I, extra=cam_inside))


# --- lights ----------------------------------------------------------------------------------
def area_light(size, intensity, scale=1):
    def f(d):
        d["extensionsUsed"] = ["EXT_lights_area"]
        d["extensions"] = {"EXT_lights_area": {"lights": [
            {"type": "rect", "intensity": intensity, "size": size, "rect": {"aspect": 1}}]}}
        d["nodes"].append({"extensions": {"EXT_lights_area": {"light": 0}}, "translation": [0, 1, 1],
                           "scale": [scale, scale, scale]})
        d["scenes"][0]["nodes"].append(1)
    return f
dump("zero_area_light.gltf", model(TRI, extra=area_light(0, 10)))
dump("zero_scale_light.gltf", model(TRI, extra=area_light(1, 10, scale=0)))
dump("negative_intensity_light.gltf", model(TRI, extra=area_light(1, -5)))

# Numbers JSON can hold but a float cannot (1e39 > 3.4e38): refused by path, not turned into
# infinity on the way in.
def set_factor(d):
    d["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [1e39, 1, 1, 1]}}]
    d["meshes"][0]["primitives"][0]["material"] = 0
dump("factor_overflow.gltf", model(TRI, extra=set_factor))
dump("scale_overflow.gltf", model(TRI, extra=lambda d: d["nodes"][0].update(scale=[1e39, 1, 1])))
def emissive_strength(d):
    d["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    d["materials"] = [{"emissiveFactor": [1, 1, 1], "extensions": {
        "KHR_materials_emissive_strength": {"emissiveStrength": 1e39}}}]
    d["meshes"][0]["primitives"][0]["material"] = 0
dump("emissive_overflow.gltf", model(TRI, extra=emissive_strength))
def punctual(intensity, color=(1, 1, 1)):
    def f(d):
        d["extensionsUsed"] = ["KHR_lights_punctual"]
        d["extensions"] = {"KHR_lights_punctual": {"lights": [
            {"type": "point", "intensity": intensity, "color": list(color)}]}}
        d["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 1, 1]})
        d["scenes"][0]["nodes"].append(1)
    return f
dump("punctual_overflow.gltf", model(TRI, extra=punctual(1e39)))
dump("light_color_overflow.gltf", model(TRI, extra=punctual(1, color=(1, 1e39, 1))))

# --- textures --------------------------------------------------------------------------------
def textured(image):
    def f(d):
        d["images"] = [image]
        d["textures"] = [{"source": 0}]
        d["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        d["meshes"][0]["primitives"][0]["material"] = 0
    return f
dump("missing_texture.gltf", model(TRI, extra=textured({"uri": "no_such_texture.png"})))
# A PNG whose header claims 20000x20000 but carries one row of data: refused or replaced
# without a 1.6 GB allocation.
huge = png(20000, 20000, idat=zlib.compress(b"\0" * 80001))
dump("huge_texture_header.gltf", model(TRI, extra=textured(
    {"uri": "data:image/png;base64," + base64.b64encode(huge).decode()})))
dump("corrupt_texture.gltf", model(TRI, extra=textured(
    {"uri": "data:image/png;base64," + base64.b64encode(b"\x89PNG\r\n\x1a\nrubbish").decode()})))

# --- scene files -----------------------------------------------------------------------------
write("truncated_scene.json", '{"gltf": "ok.gltf", "resolution": [32,')
dump("ok.gltf", good)
write("negative_resolution.json", json.dumps({"gltf": "ok.gltf", "resolution": [-4, 32]}))
write("unknown_keys.json", json.dumps({"gltf": "ok.gltf", "colour": "blue", "resolution": [16, 16]}))
write("wrong_type.json", json.dumps({"gltf": 42}))
write("exposure_overflow.json", json.dumps({"gltf": "ok.gltf", "exposure": 1e39}))
write("uniform_env_overflow.json", json.dumps({"gltf": "ok.gltf", "environment": {"uniform": [1e39, 0, 0]}}))

# --- environments ----------------------------------------------------------------------------
def pfm(name, w, h, pixel):
    write(name, b"PF\n%d %d\n-1.0\n" % (w, h) +
          b"".join(struct.pack("<3f", *pixel(x, y)) for y in range(h) for x in range(w)))
bad = {(1, 1): (nan, 1.0, 1.0), (2, 2): (float("inf"), 1.0, 1.0), (3, 3): (-1.0, 1.0, 1.0)}
pfm("nan_inf_panorama.pfm", 32, 16, lambda x, y: bad.get((x, y), (1.0, 1.0, 1.0)))
pfm("panorama_64x32.pfm", 64, 32, lambda x, y: (0.5, 0.5, 0.5))
# Every texel with exponent byte 255: decodes to about 1e38, finite but no usable radiance.
write("overflow_panorama.hdr", b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 32\n" +
      bytes([200, 200, 200, 255]) * (32 * 16))
pfm("not_2to1.pfm", 30, 20, lambda x, y: (1.0, 1.0, 1.0))
write("garbage.hdr", b"#?RADIANCE\nthis is not an image\n")
# Packed environments derived from a real prefilter output (the fuzz seed, --size 4).
packed = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "fuzz", "corpus",
                           "packed_env", "uniform_size4.hdr"), "rb").read()
write("truncated_packed.hdr", packed[: len(packed) // 2])
write("packed_wrong_face_size.hdr", packed.replace(b'"faceSize":4', b'"faceSize":64', 1))
write("packed_bad_manifest.hdr", packed.replace(b"PENUMBRA_ENV={", b"PENUMBRA_ENV={{", 1))
