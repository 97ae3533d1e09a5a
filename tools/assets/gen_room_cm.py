#!/usr/bin/env python3
"""A small living room modelled in CENTIMETRES (issue #14: scenes at other scales).

Writes assets/room_cm/room_cm.gltf + room_cm.bin (or --out-dir).

Every length is in centimetres: one glTF unit = 1 cm, so to a glTF viewer (and to Blender's
importer, which reads glTF in metres) the room is 100 times its size. Nothing else changes:
light intensities are luminance (radiance), which does not depend on size, and Penumbra
derives its scene-unit settings (occlusion distance, shadow frusta and biases) from the
scene's bounds, so room_cm.json sets no distances.

+Y up. Room interior x -200..200, y 0..280, z -250..250 (4 x 2.8 x 5 m). Walls, floor and
ceiling are 15 cm thick closed boxes, so the room is closed to the sky except through a
window in the left (-X) wall: 160 cm wide (z -130..30), sill at 90 cm, top at 210 cm, no
glass. The environment (studio_sky.hdr, whose sun stands toward -X+Z at 35 degrees) lights
the room through it: the sun lays a patch on the floor in front of the back wall.
Furniture: a table with four legs and, on it, a vase, a bowl of fruit and a book; a low
cabinet against the back wall with a chrome ball on it; a rug under the table.

Light (EXT_lights_area, intensity in nits = Penumbra's linear radiance at 0 EV; emits toward
its node's local -Z, KhronosGroup/glTF PR 2525):
  ceiling_panel  rect 120 x 60 cm, 0.1 cm under the ceiling, pointing down, 6 nits, warm white
Its visible lamp surface is a child node 0.05 cm (0.5 mm, as in the metre scenes) behind the
emitter, tagged extras.area_light_proxy. Materials are glTF metallic-roughness factors only;
one mesh per material.
"""
import math
import sys

import gltf_builder as gb

ROOM = (-200.0, 200.0, 0.0, 280.0, -250.0, 250.0)  # x0, x1, y0, y1, z0, z1 (interior)
WALL = 15.0  # thickness
WINDOW = (-130.0, 30.0, 90.0, 210.0)  # z0, z1, y0, y1 in the x = x0 wall
PROXY_OFFSET = 0.05  # 0.5 mm behind the emitter, in cm

MATERIALS = {  # name: (base colour, metallic, roughness)
    "wall": ((0.80, 0.78, 0.74), 0.0, 0.9),
    "ceiling": ((0.88, 0.88, 0.87), 0.0, 1.0),
    "floor": ((0.50, 0.36, 0.24), 0.0, 0.5),
    "table": ((0.32, 0.20, 0.11), 0.0, 0.45),
    "cabinet": ((0.30, 0.40, 0.36), 0.0, 0.55),
    "rug": ((0.55, 0.16, 0.12), 0.0, 1.0),
    "ceramic": ((0.20, 0.35, 0.55), 0.0, 0.25),
    "bowl": ((0.90, 0.89, 0.85), 0.0, 0.3),
    "fruit": ((0.85, 0.45, 0.06), 0.0, 0.45),
    "book": ((0.12, 0.20, 0.45), 0.0, 0.7),
    "chrome": ((0.95, 0.95, 0.95), 1.0, 0.08),
}

LIGHTS = [  # name, kind, size, aspect, color, intensity, position, target
    ("ceiling_panel", "rect", 60.0, 2.0, (1.0, 0.93, 0.82), 25.0,
     (0.0, 279.9, -20.0), (0.0, 0.0, -20.0)),
]


def room(meshes):
    x0, x1, y0, y1, z0, z1 = ROOM
    t = WALL
    meshes["floor"].box((x0 - t, y0 - t, z0 - t), (x1 + t, y0, z1 + t))
    meshes["ceiling"].box((x0 - t, y1, z0 - t), (x1 + t, y1 + t, z1 + t))
    w = meshes["wall"]
    w.box((x0, y0, z0 - t), (x1, y1, z0))  # back (-Z)
    w.box((x0, y0, z1), (x1, y1, z1 + t))  # front (+Z), behind the camera
    w.box((x1, y0, z0 - t), (x1 + t, y1, z1 + t))  # right (+X)
    # Left (-X) wall around the window: below the sill, above the lintel, either side.
    wz0, wz1, wy0, wy1 = WINDOW
    w.box((x0 - t, y0, z0 - t), (x0, wy0, z1 + t))
    w.box((x0 - t, wy1, z0 - t), (x0, y1, z1 + t))
    w.box((x0 - t, wy0, z0 - t), (x0, wy1, wz0))
    w.box((x0 - t, wy0, wz1), (x0, wy1, z1 + t))


def table(meshes):
    cx, cz = -20.0, -70.0
    hw, hd = 70.0, 40.0
    meshes["table"].box((cx - hw, 72.0, cz - hd), (cx + hw, 76.0, cz + hd))
    for sx in (-1, 1):
        for sz in (-1, 1):
            x, z = cx + sx * (hw - 8.0), cz + sz * (hd - 8.0)
            meshes["table"].box((x - 2.5, 0.0, z - 2.5), (x + 2.5, 72.0, z + 2.5),
                                skip=("-y", "+y"))
    meshes["rug"].box((cx - 110.0, 0.0, cz - 75.0), (cx + 110.0, 1.0, cz + 75.0), skip=("-y",))
    top = 76.0
    meshes["ceramic"].cylinder((cx + 35.0, top, cz - 10.0), 7.0, 28.0, 32, caps=(False, True))
    meshes["bowl"].cylinder((cx - 15.0, top, cz + 5.0), 14.0, 6.0, 48)
    for x, z in ((-4.0, 0.0), (5.0, 4.0), (0.0, -6.0), (2.0, 12.0)):
        meshes["fruit"].uv_sphere((cx - 15.0 + x, top + 6.0 + 4.0, cz + 5.0 + z), 4.0, 24, 12)
    meshes["book"].box((cx - 55.0, top, cz - 25.0), (cx - 30.0, top + 3.0, cz - 8.0), skip=("-y",))


def cabinet(meshes):
    z0 = ROOM[4]
    meshes["cabinet"].box((40.0, 0.0, z0), (190.0, 50.0, z0 + 45.0), skip=("-y", "-z"))
    meshes["chrome"].uv_sphere((150.0, 62.0, z0 + 22.0), 12.0, 48, 24)
    meshes["ceramic"].cylinder((70.0, 50.0, z0 + 20.0), 9.0, 35.0, 32, caps=(False, True))


def proxy_mesh(size, aspect):
    """The rect's shape in its local XY plane, facing local -Z, PROXY_OFFSET behind."""
    m = gb.MeshData()
    z, n = PROXY_OFFSET, (0.0, 0.0, -1.0)
    hw, hh = size * aspect / 2, size / 2
    m.quad((-hw, -hh, z), (-hw, hh, z), (hw, hh, z), (hw, -hh, z), n)
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("room_cm"), "room_cm.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_room_cm.py")
    meshes = {name: gb.MeshData() for name in MATERIALS}
    room(meshes)
    table(meshes)
    cabinet(meshes)

    nodes = b.material_nodes(meshes, MATERIALS)

    for name, kind, size, aspect, color, intensity, pos, target in LIGHTS:
        nodes.append(b.lamp_node(name, kind, color, intensity, size, aspect,
                                 proxy_mesh(size, aspect), pos, target))

    # Camera in the front right corner, looking toward the back left (window and table).
    eye, target = (150.0, 165.0, 235.0), (-60.0, 125.0, -120.0)
    cam = b.camera("room", math.radians(60.0), 16.0 / 9.0, 5.0, 5000.0)
    nodes.append(b.node("room", camera=cam, translation=eye, rotation=gb.quat_look(eye, target)))

    b.scene("room_cm", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
