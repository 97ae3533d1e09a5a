#!/usr/bin/env python3
"""Kitchen-like interior lit by three EXT_lights_area lights (+ the environment).

Writes assets/kitchen/kitchen.gltf + kitchen.bin (or --out-dir).

Metres, +Y up. Room interior x -2..2, y 0..2.6, z -1.8..1.8; the front (+Z)
side is open like a film set, so the environment also leaks in. Along the back
wall: base cabinets with doors and bar handles, a stone countertop, two wall
shelves, a steel fridge. A table in the middle. Small objects (jars, cups,
plates, fruit, a chrome kettle) stand on surfaces so contact shadows show.

Lights (intensity in nits, taken as linear radiance at 0 EV by Penumbra; all
emit toward their node's local -Z, see EXT_lights_area, KhronosGroup/glTF PR 2525):
  ceiling_panel  rect 1.2 x 0.6 m just under the ceiling, 6 nits, neutral
  shelf_strip    rect 1.8 x 0.04 m under the lower shelf, 15 nits, warm
  pendant        disk 0.35 m diameter above the table, 15 nits, warm
Each light node has a child mesh node: an emissive copy of its shape 0.5 mm
*behind* the emitter (local +Z), so cameras and reflections see the lamp while
it never occludes the light. Materials are grouped: one mesh per material.
"""
import math
import sys

import gltf_builder as gb

ROOM = (-2.0, 2.0, 0.0, 2.6, -1.8, 1.8)
PROXY_OFFSET = 0.0005

MATERIALS = {  # name: (base colour, metallic, roughness)
    "wall": ((0.85, 0.83, 0.78), 0.0, 0.9),
    "ceiling": ((0.90, 0.90, 0.90), 0.0, 1.0),
    "floor": ((0.45, 0.40, 0.34), 0.0, 0.55),
    "cabinet": ((0.80, 0.78, 0.74), 0.0, 0.6),
    "door": ((0.35, 0.45, 0.38), 0.0, 0.45),
    "plinth": ((0.08, 0.08, 0.08), 0.0, 0.8),
    "stone": ((0.08, 0.08, 0.09), 0.0, 0.3),
    "wood": ((0.55, 0.38, 0.22), 0.0, 0.55),
    "steel": ((0.80, 0.80, 0.80), 1.0, 0.35),
    "chrome": ((0.95, 0.95, 0.95), 1.0, 0.08),
    "ceramic": ((0.92, 0.90, 0.86), 0.0, 0.25),
    "terracotta": ((0.70, 0.33, 0.20), 0.0, 0.7),
    "fruit": ((0.90, 0.40, 0.05), 0.0, 0.4),
    "lampshade": ((0.05, 0.05, 0.05), 1.0, 0.4),
}

LIGHTS = [  # name, kind, size, aspect, color, intensity, position, target
    ("ceiling_panel", "rect", 0.6, 2.0, (0.95, 0.97, 1.0), 6.0,
     (0.0, 2.599, -0.3), (0.0, 0.0, -0.3)),
    ("shelf_strip", "rect", 0.04, 45.0, (1.0, 0.85, 0.65), 15.0,
     (-0.6, 1.399, -1.66), (-0.6, 0.0, -1.66)),
    ("pendant", "disk", 0.35, None, (1.0, 0.82, 0.6), 15.0,
     (-0.2, 1.75, 0.1), (-0.2, 0.0, 0.1)),
]


def room(meshes):
    x0, x1, y0, y1, z0, z1 = ROOM
    meshes["floor"].quad((x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0), (0, 1, 0))
    meshes["ceiling"].quad((x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1), (0, -1, 0))
    w = meshes["wall"]
    w.quad((x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (0, 0, 1))    # back
    w.quad((x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (1, 0, 0))    # left
    w.quad((x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0), (-1, 0, 0))   # right


def counter(meshes):
    back = ROOM[4]
    meshes["plinth"].box((-1.9, 0.0, back), (1.1, 0.1, -1.27), skip=("-y", "-z"))
    meshes["cabinet"].box((-1.9, 0.1, back), (1.1, 0.86, -1.22), skip=("-z",))
    for k in range(5):  # five doors with horizontal bar handles
        xa = -1.9 + 0.6 * k
        meshes["door"].box((xa + 0.005, 0.12, -1.22), (xa + 0.595, 0.84, -1.20), skip=("-z",))
        xc = xa + 0.3
        meshes["steel"].box((xc - 0.12, 0.76, -1.20), (xc + 0.12, 0.78, -1.17), skip=("-z",))
    meshes["stone"].box((-1.92, 0.86, back), (1.12, 0.90, -1.18), skip=("-z",))
    for y in (1.40, 1.80):  # two wall shelves
        meshes["wood"].box((-1.7, y, back), (0.5, y + 0.035, -1.52), skip=("-z",))
    meshes["steel"].box((1.2, 0.0, back), (1.9, 2.0, -1.1), skip=("-y", "-z"))   # fridge
    meshes["chrome"].box((1.25, 0.9, -1.1), (1.28, 1.6, -1.07), skip=("-z",))   # its handle


def table(meshes):
    meshes["wood"].box((-0.9, 0.72, -0.3), (0.5, 0.76, 0.5))
    for x, z in ((-0.86, -0.26), (0.41, -0.26), (-0.86, 0.41), (0.41, 0.41)):
        meshes["wood"].box((x, 0.0, z), (x + 0.05, 0.72, z + 0.05), skip=("-y", "+y"))


def small_objects(meshes):
    top, shelf1, shelf2 = 0.90, 1.435, 1.835
    for k, (r, h) in enumerate(((0.055, 0.18), (0.05, 0.14), (0.045, 0.11))):   # jars
        meshes["ceramic"].cylinder((-1.6 + 0.14 * k, top, -1.6), r, h, 32, caps=(False, True))
    meshes["wood"].box((-0.8, top, -1.55), (-0.4, top + 0.02, -1.30), skip=("-y",))  # board
    meshes["chrome"].uv_sphere((0.45, top + 0.11, -1.45), 0.11, 32, 16)          # kettle
    meshes["steel"].cylinder((0.45, top + 0.2, -1.45), 0.02, 0.05, 12, caps=(False, True))
    meshes["terracotta"].cylinder((0.85, top, -1.5), 0.08, 0.16, 32, caps=(False, True))
    for k in range(3):  # stacked plates on the lower shelf
        meshes["ceramic"].cylinder((-1.45, shelf1 + 0.018 * k, -1.66), 0.11, 0.015, 32)
    for k in range(4):  # cups on the lower shelf
        meshes["terracotta" if k % 2 else "ceramic"].cylinder(
            (-1.05 + 0.13 * k, shelf1, -1.64), 0.04, 0.09, 24, caps=(False, True))
    for k, h in enumerate((0.22, 0.25, 0.2, 0.24)):   # books / boxes on the upper shelf
        meshes["door" if k % 2 else "wood"].box((-1.5 + 0.06 * k, shelf2, -1.75),
                                                (-1.45 + 0.06 * k, shelf2 + h, -1.56),
                                                skip=("-y",))
    meshes["ceramic"].cylinder((0.1, shelf2, -1.66), 0.07, 0.2, 32, caps=(False, True))
    # On the table: a bowl-less fruit group and a vase.
    t = 0.76
    for x, z in ((-0.35, 0.05), (-0.27, 0.12), (-0.30, -0.03), (-0.22, 0.02)):
        meshes["fruit"].uv_sphere((x, t + 0.04, z), 0.04, 24, 12)
    meshes["ceramic"].cylinder((0.2, t, 0.2), 0.06, 0.25, 32, caps=(False, True))
    # Pendant lamp: shade (open at the bottom) and cord.
    meshes["lampshade"].cylinder((-0.2, 1.751, 0.1), 0.19, 0.15, 48, caps=(False, True))
    meshes["lampshade"].cylinder((-0.2, 1.901, 0.1), 0.005, 2.6 - 1.901, 8, caps=(False, False))


def proxy_mesh(kind, size, aspect):
    """The light's shape in its local XY plane, facing local -Z, PROXY_OFFSET behind."""
    m = gb.MeshData()
    z, n = PROXY_OFFSET, (0.0, 0.0, -1.0)
    if kind == "rect":
        hw, hh = size * aspect / 2, size / 2
        m.quad((-hw, -hh, z), (-hw, hh, z), (hw, hh, z), (hw, -hh, z), n)
    else:
        seg, r = 48, size / 2
        c = m.vertex((0.0, 0.0, z), n, (0.5, 0.5))
        for i in range(seg):
            a = 2 * math.pi * i / seg
            m.vertex((r * math.cos(a), r * math.sin(a), z), n)
        for i in range(seg):
            m.idx += [c, c + 1 + (i + 1) % seg, c + 1 + i]   # clockwise from +Z = CCW from -Z
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("kitchen"), "kitchen.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_kitchen.py")
    meshes = {name: gb.MeshData() for name in MATERIALS}
    room(meshes)
    counter(meshes)
    table(meshes)
    small_objects(meshes)

    nodes = b.material_nodes(meshes, MATERIALS)

    for name, kind, size, aspect, color, intensity, pos, target in LIGHTS:
        nodes.append(b.lamp_node(name, kind, color, intensity, size, aspect,
                                 proxy_mesh(kind, size, aspect or 1.0), pos, target))

    eye, target = (0.9, 1.55, 1.7), (-0.4, 0.95, -1.3)
    cam = b.camera("kitchen", math.radians(50.0), 16.0 / 9.0, 0.05, 50.0)
    nodes.append(b.node("kitchen", camera=cam, translation=eye, rotation=gb.quat_look(eye, target)))

    b.scene("kitchen", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
