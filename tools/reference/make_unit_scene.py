#!/usr/bin/env python3
"""Write the light-unit check scene: a 20 x 20 m white (base colour 1, metallic 0, roughness 1)
plane at y = 0 under a 1 x 1 m EXT_lights_area rect light of L = 10 nits at y = 1 facing down,
seen by a narrow camera at y = 0.5 looking straight down at the point under the light's centre.
Black environment. Usage: make_unit_scene.py OUTDIR  (writes unit.gltf and unit.json; also sky.gltf and sky.json:
the same plane with the light at 0 nits, lit by assets/env/studio_sky.hdr, for the environment
energy check)."""
import base64, json, os, struct, sys

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
h = 10.0
pos = [(-h, 0, -h), (h, 0, -h), (h, 0, h), (-h, 0, h)]
nor = [(0, 1, 0)] * 4
idx = [0, 2, 1, 0, 3, 2]  # counter-clockwise seen from +Y
blob = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<3f", *n) for n in nor)
blob += struct.pack("<6H", *idx) + b"\0\0"
q = [-0.70710678, 0.0, 0.0, 0.70710678]  # local -Z -> world -Y
g = {
    "asset": {"version": "2.0", "generator": "penumbra tools/reference/make_unit_scene.py"},
    "extensionsUsed": ["EXT_lights_area"],
    "extensions": {"EXT_lights_area": {"lights": [
        {"name": "unit_light", "type": "rect", "color": [1, 1, 1], "intensity": 10.0, "size": 1.0,
         "rect": {"aspect": 1.0}}]}},
    "scene": 0,
    "scenes": [{"nodes": [0, 1, 2]}],
    "nodes": [
        {"name": "plane", "mesh": 0},
        {"name": "light", "translation": [0, 1, 0], "rotation": q, "extensions": {"EXT_lights_area": {"light": 0}}},
        {"name": "cam", "camera": 0, "translation": [0, 0.5, 0], "rotation": q},
    ],
    "cameras": [{"name": "cam", "type": "perspective",
                 "perspective": {"yfov": 0.2, "aspectRatio": 1.0, "znear": 0.01, "zfar": 10}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
    "materials": [{"name": "white", "pbrMetallicRoughness": {
        "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
    "buffers": [{"byteLength": len(blob),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48, "target": 34962},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 48, "target": 34962},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 12, "target": 34963}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-h, 0, -h], "max": [h, 0, h]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}],
}
with open(os.path.join(out, "unit.gltf"), "w") as f:
    json.dump(g, f, indent=1)
with open(os.path.join(out, "unit.json"), "w") as f:
    json.dump({"gltf": "unit.gltf", "environment": {"uniform": [0, 0, 0]}, "camera": "cam",
               "resolution": [64, 64], "exposure": 0.0,
               "progressive": {"frames": 64, "occlusionDistance": 0.3}}, f, indent=1)

g["extensions"]["EXT_lights_area"]["lights"][0]["intensity"] = 0.0
with open(os.path.join(out, "sky.gltf"), "w") as f:
    json.dump(g, f, indent=1)
env = os.path.relpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                   "assets", "env", "studio_sky.hdr"), os.path.abspath(out))
with open(os.path.join(out, "sky.json"), "w") as f:
    json.dump({"gltf": "sky.gltf", "environment": {"file": env}, "camera": "cam",
               "resolution": [64, 64], "exposure": 0.0,
               "progressive": {"frames": 64, "occlusionDistance": 0.3}}, f, indent=1)
