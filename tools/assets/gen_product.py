#!/usr/bin/env python3
"""Product shot: a glossy torus knot and a chrome ball on a studio sweep.

Writes assets/product/product.gltf + product.bin (or --out-dir).
Meant to be lit by the environment (assets/env/studio_sky.hdr) plus two
EXT_lights_area lights (intensity in nits = linear radiance at 0 EV):
  key   rect 0.8 x 0.5 m, front-left above, 8 nits, warm-neutral
  fill  disk 0.6 m diameter, right,          3 nits, cool
each with an emissive child quad/disk 0.5 mm behind the emitter (local +Z) so
the chrome ball shows the lamps in reflection without occluding them.

Metres, +Y up, camera on +Z looking toward -Z. The sweep (cyclorama) is a
6 m wide floor from z = +3 to z = -1 that bends up with a 1 m radius into a
wall at z = -2 rising to y = 3, with smooth normals along the bend.
The knot is the (p, q) = (2, 3) torus knot (parametrisation as in three.js
TorusKnotGeometry), standing upright in its XY plane, touching the floor.
"""
import math
import sys

import gltf_builder as gb
from gen_kitchen import proxy_mesh

KNOT_RADIUS, TUBE, P, Q = 0.12, 0.035, 2, 3
KNOT_SEG, TUBE_SEG = 384, 32     # 12705 vertices, 24576 triangles
PROXY = True


def sweep():
    m = gb.MeshData()
    prof = [((0.0, 3.0), (0.0, 1.0, 0.0))]          # (y, z), normal
    bend = 24
    for k in range(bend + 1):
        a = (math.pi / 2) * k / bend
        prof.append(((1.0 - math.cos(a), -1.0 - math.sin(a)), (0.0, math.cos(a), math.sin(a))))
    prof.append(((3.0, -2.0), (0.0, 0.0, 1.0)))
    x0, x1 = -3.0, 3.0
    for (y, z), n in prof:
        m.vertex((x0, y, z), n, (0.0, z))
        m.vertex((x1, y, z), n, (1.0, z))
    for k in range(len(prof) - 1):
        a = 2 * k
        m.idx += [a, a + 1, a + 3, a, a + 3, a + 2]
    return m


def knot_point(t):
    cu, su = math.cos(t), math.sin(t)
    quo = Q / P * t
    cs = math.cos(quo)
    return (KNOT_RADIUS * (2 + cs) * 0.5 * cu, KNOT_RADIUS * (2 + cs) * su * 0.5,
            KNOT_RADIUS * math.sin(quo) * 0.5)


def torus_knot():
    """Tube around the knot curve, frame as in three.js (periodic, so no seam twist)."""
    m = gb.MeshData()
    span = P * 2 * math.pi
    for i in range(KNOT_SEG + 1):
        t = span * (i % KNOT_SEG) / KNOT_SEG
        p1, p2 = knot_point(t), knot_point(t + 0.01)
        tan = gb.sub(p2, p1)
        nrm = gb.add(p2, p1)
        bin_ = gb.normalize(gb.cross(tan, nrm))
        nrm = gb.normalize(gb.cross(bin_, tan))
        for j in range(TUBE_SEG + 1):
            v = 2 * math.pi * (j % TUBE_SEG) / TUBE_SEG
            cx, cy = -TUBE * math.cos(v), TUBE * math.sin(v)
            off = gb.add(gb.scale(nrm, cx), gb.scale(bin_, cy))
            m.vertex(gb.add(p1, off), gb.normalize(off), (i / KNOT_SEG, j / TUBE_SEG))
    row = TUBE_SEG + 1
    for i in range(KNOT_SEG):
        for j in range(TUBE_SEG):
            a, b = i * row + j, (i + 1) * row + j
            m.idx += [a, b, a + 1, b, b + 1, a + 1]
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("product"), "product.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_product.py")
    nodes = []

    backdrop = b.material("backdrop", (0.75, 0.75, 0.75), roughness=0.6)
    nodes.append(b.node("sweep", mesh=b.mesh("sweep", [b.primitive(sweep(), backdrop)])))

    knot = torus_knot()
    if gb.dot(gb.cross(gb.sub(knot.pos[knot.idx[1]], knot.pos[knot.idx[0]]),
                       gb.sub(knot.pos[knot.idx[2]], knot.pos[knot.idx[0]])),
              knot.nrm[knot.idx[0]]) < 0:
        # Which way the tube winds depends on the frame's handedness: make it CCW-out.
        for k in range(0, len(knot.idx), 3):
            knot.idx[k + 1], knot.idx[k + 2] = knot.idx[k + 2], knot.idx[k + 1]
    lift = -min(p[1] for p in knot.pos)  # rest the lowest point on the floor
    glaze = b.material("glaze", (0.9, 0.35, 0.1), roughness=0.25)
    nodes.append(b.node("torus_knot", mesh=b.mesh("torus_knot", [b.primitive(knot, glaze)]),
                        translation=(0.0, lift, 0.0),
                        rotation=gb.quat_axis_angle((0, 1, 0), math.radians(-25.0))))

    ball = gb.MeshData()
    ball.uv_sphere((0.0, 0.0, 0.0), 0.07, 48, 24)
    chrome = b.material("chrome", (0.95, 0.95, 0.95), metallic=1.0, roughness=0.05)
    nodes.append(b.node("chrome_ball", mesh=b.mesh("chrome_ball", [b.primitive(ball, chrome)]),
                        translation=(0.33, 0.07, 0.15)))

    target = (0.0, 0.2, 0.0)
    for name, kind, size, aspect, color, intensity, pos in (
            ("key", "rect", 0.5, 1.6, (1.0, 0.95, 0.9), 8.0, (-0.9, 1.1, 0.9)),
            ("fill", "disk", 0.6, None, (0.85, 0.9, 1.0), 3.0, (1.1, 0.6, 0.5))):
        nodes.append(b.lamp_node(name, kind, color, intensity, size, aspect,
                                 proxy_mesh(kind, size, aspect or 1.0), pos, target))

    eye = (0.08, 0.36, 1.1)
    cam = b.camera("product", math.radians(32.0), 1.5, 0.02, 50.0)
    nodes.append(b.node("product", camera=cam, translation=eye,
                        rotation=gb.quat_look(eye, (0.12, 0.17, 0.0))))

    b.scene("product", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
