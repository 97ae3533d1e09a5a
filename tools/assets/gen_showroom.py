#!/usr/bin/env python3
"""Showroom: the material extensions product models use, on the product scene's studio sweep.

Writes assets/showroom/showroom.gltf + showroom.bin (or --out-dir).
Lit by the studio sky (assets/env/studio_sky.hdr) and one EXT_lights_area rect key light
(0.5 x 0.8 m, 8 nits) front-left above, with its emissive stand-in:
  paint    a sphere of red car paint: a rough dielectric base under a smooth clearcoat
           (KHR_materials_clearcoat)
  glass    a solid glass ball (KHR_materials_transmission, KHR_materials_volume: thickness
           its diameter, ior 1.5, a faint green Beer-Lambert tint), smooth, in front of the
           paint sphere
  pane     an upright thin-walled pane of pale blue glass (transmission, smooth) in front of
           the cushion, which it tints (rough thin-walled transmission is left to the GL tests:
           Blender 3.4, the reference, has no BSDF for glTF's mirrored thin-walled lobe)
  cushion  a rounded block of dark blue velvet (KHR_materials_sheen over a rough base)
  plinth   a grey block the glass ball rests on
Metres, +Y up, camera on +Z looking toward -Z.
"""
import math
import sys

import gltf_builder as gb
from gen_kitchen import proxy_mesh
from gen_product import sweep


def rounded_block(lo, hi, r, seg):
    """A box with edges rounded by radius r: a superellipsoid-like sphere mapped onto the box
    (each sphere octant pushed out to the box corner), smooth normals."""
    m = gb.MeshData()
    c = [(lo[i] + hi[i]) * 0.5 for i in range(3)]
    h = [(hi[i] - lo[i]) * 0.5 - r for i in range(3)]
    rows, cols = seg, 2 * seg
    for i in range(rows + 1):
        th = math.pi * i / rows
        for j in range(cols + 1):
            ph = 2 * math.pi * (j % cols) / cols
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            p = tuple(c[k] + math.copysign(h[k], n[k]) + r * n[k] for k in range(3))
            m.vertex(p, n, (j / cols, i / rows))
    for i in range(rows):
        for j in range(cols):
            a, b = i * (cols + 1) + j, (i + 1) * (cols + 1) + j
            if i > 0:  # the top row's a and a + 1 are both the pole
                m.idx += [a, a + 1, b]
            if i < rows - 1:  # the bottom row's b and b + 1 are
                m.idx += [b, a + 1, b + 1]
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("showroom"), "showroom.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_showroom.py")
    nodes = []

    backdrop = b.material("backdrop", (0.75, 0.75, 0.75), roughness=0.6)
    nodes.append(b.node("sweep", mesh=b.mesh("sweep", [b.primitive(sweep(), backdrop)])))

    paint_ball = gb.MeshData()
    paint_ball.uv_sphere((-0.24, 0.12, -0.12), 0.12, 64, 32)
    paint = b.material("car_paint", (0.55, 0.02, 0.03), roughness=0.45, extensions={
        "KHR_materials_clearcoat": {"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.03}})
    nodes.append(b.node("paint", mesh=b.mesh("paint", [b.primitive(paint_ball, paint)])))

    plinth = gb.MeshData()
    plinth.box((-0.1, 0.0, 0.12), (0.1, 0.06, 0.32), skip=("-y",))
    grey = b.material("plinth", (0.35, 0.35, 0.37), roughness=0.5)
    nodes.append(b.node("plinth", mesh=b.mesh("plinth", [b.primitive(plinth, grey)])))

    ball = gb.MeshData()
    ball.uv_sphere((0.0, 0.16, 0.22), 0.1, 64, 32)
    glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.0, extensions={
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_volume": {"thicknessFactor": 0.2, "attenuationDistance": 0.4,
                                 "attenuationColor": [0.8, 0.95, 0.85]},
        "KHR_materials_ior": {"ior": 1.5}})
    nodes.append(b.node("glass", mesh=b.mesh("glass", [b.primitive(ball, glass)])))

    pane = gb.MeshData()
    pane.quad((0.22, 0.0, 0.42), (0.5, 0.0, 0.5), (0.5, 0.26, 0.5), (0.22, 0.26, 0.42))
    tinted = b.material("pane", (0.8, 0.9, 1.0), roughness=0.0, double_sided=True,
                        extensions={"KHR_materials_transmission": {"transmissionFactor": 1.0}})
    nodes.append(b.node("pane", mesh=b.mesh("pane", [b.primitive(pane, tinted)])))

    cushion = rounded_block((0.2, 0.0, 0.08), (0.5, 0.1, 0.3), 0.04, 16)
    velvet = b.material("velvet", (0.04, 0.06, 0.25), roughness=0.9, extensions={
        "KHR_materials_sheen": {"sheenColorFactor": [0.55, 0.6, 0.95],
                                "sheenRoughnessFactor": 0.45}})
    nodes.append(b.node("cushion", mesh=b.mesh("cushion", [b.primitive(cushion, velvet)])))

    target = (0.0, 0.15, 0.0)
    nodes.append(b.lamp_node("key", "rect", (1.0, 0.95, 0.9), 8.0, 0.5, 1.6,
                             proxy_mesh("rect", 0.5, 1.6), (-0.9, 1.1, 0.9), target))

    eye = (0.0, 0.42, 1.25)
    cam = b.camera("showroom", math.radians(32.0), 1.5, 0.02, 50.0)
    nodes.append(b.node("showroom", camera=cam, translation=eye,
                        rotation=gb.quat_look(eye, (0.05, 0.12, 0.0))))

    b.scene("showroom", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
