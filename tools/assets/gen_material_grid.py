#!/usr/bin/env python3
"""5 x 5 grid of spheres sweeping metallic (x) and perceptual roughness (y).

Writes assets/material_grid/material_grid.gltf + .bin (or --out-dir).
Lit by the environment only (no area lights), for IBL / BRDF checks.

Layout (metres, +Y up, camera on +Z looking toward -Z):
  * column c = 0..4 at x = (c - 2) * SPACING: metallic = c / 4 (0 left .. 1 right);
  * row r = 0..4 at y = RADIUS + GAP + r * SPACING: roughness = 0.05 + 0.95 * r / 4,
    so the smoothest row is at the bottom and roughness grows upward (+y);
  * all 25 spheres share ONE set of vertex/index accessors; each has its own
    mesh (glTF binds materials per primitive, not per node), which keeps the
    .bin at a single sphere's size;
  * a 40 m x 40 m floor at y = 0 (white-ish, roughness 0.8); the bottom row
    floats GAP above it, so contact shadows and floor reflections are visible.
One base colour for all spheres, so only metallic/roughness change across the
grid: (0.90, 0.76, 0.52), a pale gold that reads as a light beige dielectric at
metallic 0 and as a grey-gold metal (F0 = base colour) at metallic 1.
"""
import math
import sys

import gltf_builder as gb

N = 5
RADIUS = 0.4
SPACING = 1.0
GAP = 0.1              # bottom row hovers 10 cm above the floor
SEG_U, SEG_V = 64, 32  # sphere tessellation: 2145 vertices, 4032 triangles
BASE = (0.90, 0.76, 0.52)
FLOOR = (0.80, 0.80, 0.78)
FLOOR_HALF = 20.0


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("material_grid"), "material_grid.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_material_grid.py")

    sphere = gb.MeshData()
    sphere.uv_sphere((0.0, 0.0, 0.0), RADIUS, SEG_U, SEG_V)
    shared = b.primitive(sphere, None)  # accessors written once, reused 25 times

    nodes = []
    for r in range(N):
        rough = 0.05 + 0.95 * r / (N - 1)
        for c in range(N):
            metal = c / (N - 1)
            name = "sphere_m%.2f_r%.4f" % (metal, rough)
            mat = b.material(name, BASE, metallic=metal, roughness=rough)
            prim = dict(shared)
            prim["material"] = mat
            mesh = b.mesh(name, [prim])
            nodes.append(b.node(name, mesh=mesh,
                                translation=((c - 2) * SPACING, RADIUS + GAP + r * SPACING, 0.0),
                                extras={"metallic": gb.num(metal), "roughness": gb.num(rough)}))

    floor = gb.MeshData()
    h = FLOOR_HALF
    # UVs in metres / 1 (one unit per metre) so a checker texture could be added later.
    floor.quad((-h, 0.0, h), (h, 0.0, h), (h, 0.0, -h), (-h, 0.0, -h), (0.0, 1.0, 0.0),
               uvs=((0, 0), (2 * h, 0), (2 * h, 2 * h), (0, 2 * h)))
    floor_mat = b.material("floor", FLOOR, metallic=0.0, roughness=0.8)
    nodes.append(b.node("floor", mesh=b.mesh("floor", [b.primitive(floor, floor_mat)])))

    # Camera straight on, centred on the grid. The grid spans y 0.1..4.9 and
    # x -2.4..2.4; a 30-degree vertical field of view at 11 m frames it with a margin,
    # and the floor shows below the bottom row.
    yfov = math.radians(30.0)
    centre_y = RADIUS + GAP + 2 * SPACING
    cam = b.camera("grid", yfov, 1.0, 0.05, 100.0)
    nodes.append(b.node("grid", camera=cam, translation=(0.0, centre_y, 11.0)))

    b.scene("material_grid", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
