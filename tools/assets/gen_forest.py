#!/usr/bin/env python3
"""A forest of instanced trees (EXT_mesh_gpu_instancing) for the instancing benchmark.

Writes assets/forest/forest.glb (or --out-dir): one tree mesh (a trunk and a crown, 300
triangles) drawn 2,304 times by one node's EXT_mesh_gpu_instancing TRANSLATION, ROTATION and
SCALE (a 48 x 48 jittered grid over 36 m, each copy turned and scaled by a fixed-seed LCG),
on a ground square, lit by a low sun (KHR_lights_punctual) and a sky, with a camera "forest".
This is how gltfpack and Blender export scattered foliage: about 0.7 million triangles
drawn from 0.1 MB of geometry. Metres, +Y up.
"""
import math
import struct
import sys

import gltf_builder as gb

GRID = 48
SPACING = 0.75


def instance_accessor(b, rows, type_):
    """A float32 accessor of per-instance values: a view without a vertex-buffer target."""
    flat = [c for r in rows for c in r]
    view = b._view(struct.pack("<%df" % len(flat), *flat), None)
    del b.lists["bufferViews"][view]["target"]
    return b._push("accessors", {"bufferView": view, "componentType": gb.FLOAT,
                                 "count": len(rows), "type": type_})


def copies():
    rng = gb.Lcg(20261128)
    t, r, s = [], [], []
    half = (GRID - 1) * SPACING / 2.0
    for j in range(GRID):
        for i in range(GRID):
            x = i * SPACING - half + (rng.next() - 0.5) * SPACING * 0.6
            z = j * SPACING - half + (rng.next() - 0.5) * SPACING * 0.6
            yaw = 2.0 * math.pi * rng.next()
            k = 0.7 + 0.6 * rng.next()
            t.append((x, 0.0, z))
            r.append(gb.quat_axis_angle((0.0, 1.0, 0.0), yaw))
            s.append((k, k * (0.8 + 0.4 * rng.next()), k))
    return t, r, s


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("forest"), "forest.glb")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_forest.py")
    trunk = gb.MeshData()
    trunk.cylinder((0.0, 0.0, 0.0), 0.05, 0.45, 8, caps=(False, False))
    crown = gb.MeshData()
    crown.uv_sphere((0.0, 0.7, 0.0), 0.3, 14, 10)
    bark = b.material("bark", (0.30, 0.20, 0.12), roughness=0.9)
    leaves = b.material("leaves", (0.12, 0.35, 0.10), roughness=0.7)
    tree = b.mesh("tree", [b.primitive(trunk, bark, uvs=False),
                           b.primitive(crown, leaves, uvs=False)])
    t, r, s = copies()
    b.ext_used.add("EXT_mesh_gpu_instancing")
    forest = b.node("trees", mesh=tree, extensions={"EXT_mesh_gpu_instancing": {"attributes": {
        "TRANSLATION": instance_accessor(b, t, "VEC3"),
        "ROTATION": instance_accessor(b, r, "VEC4"),
        "SCALE": instance_accessor(b, s, "VEC3")}}})
    ground = gb.MeshData()
    h = GRID * SPACING / 2.0 + 2.0
    ground.quad((-h, 0.0, h), (h, 0.0, h), (h, 0.0, -h), (-h, 0.0, -h), (0.0, 1.0, 0.0))
    soil = b.material("ground", (0.35, 0.30, 0.22), roughness=0.95)
    nodes = [forest, b.node("ground", mesh=b.mesh("ground", [b.primitive(ground, soil,
                                                                         uvs=False)]))]
    # A low sun from the left and behind: long shadows between the trees.
    b.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "sun", "type": "directional", "color": [1.0, 0.95, 0.85], "intensity": 3.0}]}}
    b.ext_used.add("KHR_lights_punctual")
    sun_from = (-0.6, 0.45, -0.5)
    nodes.append(b.node("sun", rotation=gb.quat_look(sun_from, (0.0, 0.0, 0.0)),
                        extensions={"KHR_lights_punctual": {"light": 0}}))
    eye, target = (0.0, 6.5, 18.0), (0.0, 0.0, 2.0)
    cam = b.camera("forest", math.radians(45.0), 16.0 / 9.0, 0.1, 100.0)
    nodes.append(b.node("forest", camera=cam, translation=eye, rotation=gb.quat_look(eye, target)))
    b.scene("forest", nodes)
    b.write_glb(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
