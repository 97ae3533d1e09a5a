#!/usr/bin/env python3
"""Regenerates the glTF, scene-JSON and image seeds in tests/fuzz/corpus from the assets
(stdlib only). The packed-environment seeds are penumbra-prefilter outputs (--size 4 and 8)
and are committed as they are. Usage: python3 tests/fuzz/make_seeds.py"""
import base64, json, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
C = os.path.join(HERE, "corpus")


def out(target, name, data):
    os.makedirs(os.path.join(C, target), exist_ok=True)
    with open(os.path.join(C, target, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def png(w, h, rgba):
    raw = b"".join(b"\0" + b"".join(bytes(rgba(x, y)) for x in range(w)) for y in range(h))
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def glb(doc, binary):
    j = json.dumps(doc, separators=(",", ":")).encode()
    j += b" " * (-len(j) % 4)
    binary += b"\0" * (-len(binary) % 4)
    body = struct.pack("<II", len(j), 0x4E4F534A) + j + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def data_uri(mime, data):
    return "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())


# --- glTF: the Cornell box embedded (.gltf with a data URI, and as .glb) ----------------------
cb = json.load(open(os.path.join(ROOT, "assets/cornell_box/cornell_box.gltf")))
cbbin = open(os.path.join(ROOT, "assets/cornell_box/cornell_box.bin"), "rb").read()
emb = json.loads(json.dumps(cb))
emb["buffers"][0]["uri"] = data_uri("application/octet-stream", cbbin)
out("gltf", "cornell_embedded.gltf", json.dumps(emb, separators=(",", ":")))
g = json.loads(json.dumps(cb))
del g["buffers"][0]["uri"]
out("gltf", "cornell.glb", glb(g, cbbin))

# --- glTF: one textured, indexed triangle with a light and a camera, in a .glb -------------
pos = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
uv = struct.pack("<6f", 0, 0, 1, 0, 0, 1)
idx = struct.pack("<3H", 0, 1, 2) + b"\0\0"
img = png(4, 4, lambda x, y: (x * 60, y * 60, 128, 255))
binary = pos + uv + idx + img + b"\0" * (-len(img) % 4)
tri = {
    "asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "intensity": 10, "spot": {"outerConeAngle": 0.5}}]}},
    "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [{"mesh": 0, "rotation": [0, 0, 0, 1]}, {"camera": 0, "translation": [0, 0, 3]},
              {"extensions": {"KHR_lights_punctual": {"light": 0}}, "translation": [0, 2, 0], "children": [3]},
              {"scale": [2, 2, 2]}],
    "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0}}],
    "textures": [{"source": 0, "sampler": 0}], "samplers": [{"magFilter": 9728, "wrapS": 33071}],
    "images": [{"bufferView": 3, "mimeType": "image/png"}],
    "buffers": [{"byteLength": len(binary)}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                    {"buffer": 0, "byteOffset": 60, "byteLength": 6},
                    {"buffer": 0, "byteOffset": 68, "byteLength": len(img)}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
                  {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}],
}
out("gltf", "textured_triangle.glb", glb(tri, binary))
# The same with a sparse accessor and an EXT_lights_area rect light.
t2 = json.loads(json.dumps(tri))
t2["accessors"][0]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                                "values": {"bufferView": 0}}
t2["extensionsUsed"] = ["EXT_lights_area"]
t2["extensions"] = {"EXT_lights_area": {"lights": [{"type": "rect", "intensity": 5, "width": 1, "height": 0.5}]}}
t2["nodes"][2]["extensions"] = {"EXT_lights_area": {"light": 0}}
out("gltf", "sparse_area_light.glb", glb(t2, binary))
# Numbers near and beyond float range (3.4e38): a factor, a light colour, a punctual light.
t3 = json.loads(json.dumps(tri))
t3["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [3.4e38, 1, 1e39, 1]},
                    "emissiveFactor": [1, 1, 1]}]
t3["extensionsUsed"] = ["KHR_lights_punctual"]
t3["extensions"] = {"KHR_lights_punctual": {"lights": [
    {"type": "spot", "intensity": 1e39, "color": [1, 3.5e38, 1], "spot": {"outerConeAngle": 1e39}}]}}
t3["nodes"][2]["extensions"] = {"KHR_lights_punctual": {"light": 0}}
out("gltf", "bad-float-range.glb", glb(t3, binary))

# --- scene JSON -------------------------------------------------------------------------------
for p in ["cornell_box/cornell_box.json", "material_grid/material_grid.json", "dense/dense.json"]:
    out("scene_json", os.path.basename(p), open(os.path.join(ROOT, "assets", p), "rb").read())
out("scene_json", "full.json", json.dumps({
    "gltf": "model.glb", "environment": {"path": "env.hdr", "intensity": 2, "rotation": 90},
    "camera": 0, "resolution": [64, 32], "exposure": -1, "toneMapper": "aces", "background": False,
    "progressive": {"frames": 16, "fd": 0.5, "occlusionDistance": 1, "lightSamples": 4,
                    "shadowMapSize": 256, "ssgi": False, "seed": 7}}))
out("scene_json", "bad-float-range.json", json.dumps({
    "gltf": "model.glb", "environment": {"uniform": [1e39, 0, 3.4e38]}, "exposure": 1e39,
    "progressive": {"occlusionDistance": 3.5e38, "fd": -1e39}}))

# --- HDR images (first byte: 0 = readImageFromMemory, 1 = Penumbra's RGBE codec) --------------
def rgbe_flat(w, h, px):
    hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w)
    return hdr + b"".join(bytes(px(x, y)) for y in range(h) for x in range(w))

flat = rgbe_flat(4, 2, lambda x, y: (128, 64 + x * 16, 32, 129 + y))
out("hdr_image", "flat_oiio.hdr", b"\0" + flat)
out("hdr_image", "flat_rgbe.hdr", b"\1" + flat)
white = open(os.path.join(ROOT, "assets/env/uniform_white.hdr"), "rb").read()
out("hdr_image", "rle_oiio.hdr", b"\0" + white)
out("hdr_image", "rle_rgbe.hdr", b"\1" + white)
pfm = b"PF\n4 2\n-1.0\n" + struct.pack("<24f", *([0.5, float("nan"), float("inf")] * 8))
out("hdr_image", "nan_inf.pfm", b"\0" + pfm)
out("hdr_image", "small.png", b"\0" + png(3, 2, lambda x, y: (255, x * 100, y * 200, 255)))
