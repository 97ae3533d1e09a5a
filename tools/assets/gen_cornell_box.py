#!/usr/bin/env python3
"""Cornell box (the measured 'Cornell Box Data' scene) as glTF 2.0.

Writes assets/cornell_box/cornell_box.gltf + cornell_box.bin (or --out-dir).

Source of the geometry and camera: Cornell University Program of Computer
Graphics, "Cornell Box Data", http://www.graphics.cornell.edu/online/box/data.html
(mirrored at https://bowers.cornell.edu/computer-graphics/data). Coordinates
there are in millimetres, +Y up, camera at (278, 273, -800) looking toward +Z.
The tables below are copied from that page, vertex order as published.

Frame conversion (why not just z -> -z): the published frame is right-handed
and, seen from its camera looking toward +Z, x = 0 (green wall) is on the
image *right* and x = 556 (red wall) on the *left*, as in the classic photos.
Mirroring only the depth axis would flip the image (red right). We therefore
apply the 180-degree rotation about +Y (x -> -x, z -> -z), which puts the
camera at +Z looking toward -Z and keeps red left / green right. A rotation
keeps handedness, so no winding flip is needed; windings are nevertheless
re-derived below from the wanted normal direction, so a data-order slip
cannot produce a back-facing wall. Result (metres):
    x' = (278.0 - x) / 1000   (camera on x' = 0; red wall at x' ~ -0.278)
    y' = y / 1000             (floor y' = 0, ceiling y' = 0.5488)
    z' = (279.6 - z) / 1000   (back wall z' = -0.2796, open front z' = +0.2796)
"""
import math
import sys

import gltf_builder as gb

# ---- Published data (mm). Each quad: four corners in the published order. ----
FLOOR = [(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]
CEILING = [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]
BACK_WALL = [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]
RIGHT_WALL_GREEN = [(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]
LEFT_WALL_RED = [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]
SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]
# Light opening in the ceiling: x 213..343, z 227..332, at y = 548.8.
LIGHT_X, LIGHT_Z, CEILING_Y = (213.0, 343.0), (227.0, 332.0), 548.8
# Camera: position (278, 273, -800), direction +Z, up +Y, focal 0.035 m, film 0.025 x 0.025 m.
CAM_POS, FOCAL, FILM = (278.0, 273.0, -800.0), 0.035, 0.025

# ---- Materials: linear-RGB fits of the measured reflectance spectra, as used by
# the widely shared Cornell box scenes of B. Bitterli's "Rendering Resources"
# (https://benedikt-bitterli.me/resources/, Mitsuba/PBRT "cornell-box"):
WHITE = (0.725, 0.71, 0.68)
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
# ---- Light: the same scenes use emitted radiance (17, 12, 4) for the lamp. With a
# renderer that takes EXT_lights_area nits directly as linear radiance at 0 EV that
# gives the classic look: colour = (17, 12, 4) / 17 (max component 1, as the
# extension wants colours in [0, 1]) and intensity = 17 nits.
LIGHT_RADIANCE = (17.0, 12.0, 4.0)
LIGHT_INTENSITY = max(LIGHT_RADIANCE)
LIGHT_COLOR = tuple(c / LIGHT_INTENSITY for c in LIGHT_RADIANCE)
LIGHT_DROP = 1.0   # mm: the light plane sits 1 mm under the ceiling (y' = 0.5478)
PROXY_DROP = 0.5   # mm: its visible emissive quad sits 0.5 mm under the ceiling


def to_m(p):
    """Published mm frame -> metres, +Y up, camera on +Z looking toward -Z."""
    return ((278.0 - p[0]) / 1000.0, p[1] / 1000.0, (279.6 - p[2]) / 1000.0)


def oriented_quad(mesh, corners_mm, toward=None, away=None):
    """Adds a quad whose winding (CCW = front) faces `toward` a point, or `away`
    from one; the flat normal follows the winding."""
    pts = [to_m(p) for p in corners_mm]
    n = gb.normalize(gb.cross(gb.sub(pts[1], pts[0]), gb.sub(pts[2], pts[0])))
    n2 = gb.normalize(gb.cross(gb.sub(pts[2], pts[0]), gb.sub(pts[3], pts[0])))
    n = gb.add(n, n2)
    c = gb.scale(gb.add(gb.add(pts[0], pts[1]), gb.add(pts[2], pts[3])), 0.25)
    want = gb.sub(toward, c) if toward is not None else gb.sub(c, away)
    if gb.dot(n, want) < 0:
        pts.reverse()
    mesh.quad(*pts)


def block(corners_list):
    m = gb.MeshData()
    allpts = [to_m(p) for quad in corners_list for p in quad]
    centroid = tuple(sum(p[i] for p in allpts) / len(allpts) for i in range(3))
    for quad in corners_list:
        oriented_quad(m, quad, away=centroid)
    return m


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("cornell_box"), "cornell_box.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_cornell_box.py")
    white = b.material("white", WHITE)
    red = b.material("red", RED)
    green = b.material("green", GREEN)
    # Visible lamp surface: black base (it reflects nothing) + emission equal to the
    # light's radiance, so a camera or a mirror sees the same (17, 12, 4).
    lamp = b.material("light", (0.0, 0.0, 0.0), emissive=LIGHT_COLOR, strength=LIGHT_INTENSITY)

    room_centre = to_m((278.0, 274.4, 279.6))
    nodes = []

    def add(name, mesh, mat, extras=None):
        mi = b.mesh(name, [b.primitive(mesh, mat, uvs=False)])
        nodes.append(b.node(name, mesh=mi, extras=extras))

    for name, quad, mat in (("floor", FLOOR, white), ("ceiling", CEILING, white),
                            ("back_wall", BACK_WALL, white),
                            ("left_wall_red", LEFT_WALL_RED, red),
                            ("right_wall_green", RIGHT_WALL_GREEN, green)):
        m = gb.MeshData()
        oriented_quad(m, quad, toward=room_centre)  # walls face the inside of the room
        add(name, m, mat)
    add("short_block", block(SHORT_BLOCK), white)   # blocks face outward
    add("tall_block", block(TALL_BLOCK), white)

    # Emissive quad covering the opening, facing down, 0.5 mm under the ceiling.
    # It is deliberately *above* the light plane (0.5 mm behind the emitter), not
    # below it: below, it would sit in front of the one-sided emitter and occlude
    # it for any renderer that shadow-maps from the light.
    y = CEILING_Y - PROXY_DROP
    opening = [(LIGHT_X[0], y, LIGHT_Z[0]), (LIGHT_X[1], y, LIGHT_Z[0]),
               (LIGHT_X[1], y, LIGHT_Z[1]), (LIGHT_X[0], y, LIGHT_Z[1])]
    m = gb.MeshData()
    oriented_quad(m, opening, toward=room_centre)
    # extras.area_light_proxy marks it as a visual stand-in for light 0, so renderers
    # that light from emissive geometry (path tracers) can skip it: no double counting.
    add("light_surface", m, lamp, extras={"area_light_proxy": 0})

    # Area light: centred on the opening, local -Z pointing straight down (-Y).
    # size = opening depth (local Y -> world Z), aspect = width / depth (local X -> world X).
    width = (LIGHT_X[1] - LIGHT_X[0]) / 1000.0
    depth = (LIGHT_Z[1] - LIGHT_Z[0]) / 1000.0
    centre_mm = (sum(LIGHT_X) / 2, CEILING_Y - LIGHT_DROP, sum(LIGHT_Z) / 2)
    ext = b.area_light("ceiling_light", "rect", LIGHT_COLOR, LIGHT_INTENSITY, depth,
                       aspect=width / depth)
    centre = to_m(centre_mm)
    rot = gb.quat_look(centre, gb.add(centre, (0.0, -1.0, 0.0)))
    nodes.append(b.node("ceiling_light", translation=centre, rotation=rot, extensions=ext))

    # Camera: glTF cameras look down local -Z, which is already the converted
    # viewing direction, so the node needs a translation only.
    yfov = 2.0 * math.atan((FILM / 2.0) / FOCAL)
    cam = b.camera("cornell", yfov, 1.0, 0.01, 10.0)
    nodes.append(b.node("cornell", camera=cam, translation=to_m(CAM_POS)))

    b.scene("cornell_box", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
