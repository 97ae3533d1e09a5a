#!/usr/bin/env python3
"""Procedural HDR environments as Radiance RGBE (.hdr) files, stdlib only.

Writes (or into --out-dir):
  assets/env/studio_sky.hdr     512 x 256 sky: gradient, ground, sun, 2 softboxes
  assets/env/uniform_white.hdr  64 x 32, radiance 1.0 everywhere (white furnace)
  assets/env/studio.hdr         128 x 64 neutral studio, the default environment of
                                scenes without lights (embedded in the library)

Panorama convention (the one the Penumbra prefilter tool uses, docs/ibl.md; Blender's
world-texture convention seen through its glTF importer), for pixel centre (u, v) in
[0,1]^2, v = 0 at the top row:
    theta = pi * v            (polar angle from +Y; row 0 looks straight up)
    phi   = 2 * pi * (u - 1/2)
    dir   = (sin(theta) cos(phi), cos(theta), sin(theta) sin(phi))
so u = 0.5 (the centre column) looks toward +X, u = 0.75 toward +Z, u = 0.25 toward -Z,
and the left and right edges toward -X.

Sky content (linear radiance, Rec.709 primaries):
  * sky: horizon (0.9, 0.9, 1.0) x 1.5 blending to zenith (0.3, 0.45, 0.9) with
    t = sqrt(sin(elevation)); ground (0.20, 0.17, 0.13) below the horizon,
    blended over +-1 degree so the horizon line is not aliased;
  * sun: disk of radius 3 degrees, radiance (1000, 880, 700), centred at
    elevation 35 degrees toward (-X, +Z), i.e. u = 0.875: for a camera on +Z
    looking toward -Z it lights objects from the front-left and above; edge
    pixels are 8 x 8 supersampled so the disk's energy does not depend on
    pixel phase;
  * two softboxes, rectangles in (azimuth, elevation) with 2-degree soft edges:
      key  u = 0.625 (+X,+Z: front-right), elevation 20, 36 x 24 deg, radiance 12
      rim  u = 0.125 (-X,-Z: back-left),   elevation 40, 20 x 40 deg, radiance 8
    so metal spheres seen from +Z show readable rectangular highlights.
No randomness: the files are a pure function of this script.

RGBE encoding (Greg Ward, "Real Pixels", Graphics Gems II; same as the
reference rgbe.c): e = frexp(max) exponent, mantissas = floor(c * 256 / 2^e),
exponent byte e + 128; zero below 1e-32. Scanlines are written flat
(uncompressed); readers (stb_image, OpenImageIO, Radiance) accept flat data
as long as a scanline does not start with the bytes 2, 2 (checked below).
"""
import math
import os
import sys

import gltf_builder as gb

HORIZON = (0.9 * 1.5, 0.9 * 1.5, 1.0 * 1.5)
ZENITH = (0.3, 0.45, 0.9)
GROUND = (0.20, 0.17, 0.13)
HORIZON_BLEND_DEG = 1.0
SUN = {"u": 0.875, "elev": 35.0, "radius": 3.0, "radiance": (1000.0, 880.0, 700.0)}
SOFTBOXES = [
    {"u": 0.625, "elev": 20.0, "width": 36.0, "height": 24.0, "radiance": (12.0, 12.0, 12.0)},
    {"u": 0.125, "elev": 40.0, "width": 20.0, "height": 40.0, "radiance": (8.0, 8.0, 8.0)},
]
SOFT_EDGE_DEG = 2.0


def direction(u, v):
    th, ph = math.pi * v, 2.0 * math.pi * (u - 0.5)
    return (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def sky(elev_deg):
    """Background radiance as a function of elevation only."""
    s = math.sin(math.radians(max(elev_deg, 0.0)))
    t = math.sqrt(s)
    up = tuple(h + (z - h) * t for h, z in zip(HORIZON, ZENITH))
    k = smoothstep(-HORIZON_BLEND_DEG, HORIZON_BLEND_DEG, elev_deg)  # 0 ground .. 1 sky
    return tuple(g + (a - g) * k for g, a in zip(GROUND, up))


def softbox_weight(box, u, elev_deg):
    """1 inside the panel, smooth falloff over SOFT_EDGE_DEG outside it."""
    du = (u - box["u"] + 0.5) % 1.0 - 0.5           # wrapped azimuth offset, in turns
    daz = abs(du) * 360.0
    de = abs(elev_deg - box["elev"])
    wx = 1.0 - smoothstep(box["width"] / 2, box["width"] / 2 + SOFT_EDGE_DEG, daz)
    wy = 1.0 - smoothstep(box["height"] / 2, box["height"] / 2 + SOFT_EDGE_DEG, de)
    return wx * wy


def studio_sky(w, h):
    sun_dir = direction(SUN["u"], 0.5 - SUN["elev"] / 180.0)
    cos_r = math.cos(math.radians(SUN["radius"]))
    near = math.cos(math.radians(SUN["radius"] + 2.0 * 360.0 / w))  # pixels that may touch it
    ss = 8
    rows = []
    for j in range(h):
        v = (j + 0.5) / h
        elev = 90.0 - 180.0 * v
        base = sky(elev)
        row = []
        for i in range(w):
            u = (i + 0.5) / w
            c = base
            for box in SOFTBOXES:
                k = softbox_weight(box, u, elev)
                if k > 0.0:
                    c = tuple(a + (r - a) * k for a, r in zip(c, box["radiance"]))
            if gb.dot(direction(u, v), sun_dir) > near:
                # Fraction of the pixel covered by the sun disk, by supersampling.
                hits = 0
                for sj in range(ss):
                    for si in range(ss):
                        d = direction((i + (si + 0.5) / ss) / w, (j + (sj + 0.5) / ss) / h)
                        hits += gb.dot(d, sun_dir) >= cos_r
                f = hits / (ss * ss)
                c = tuple(a + (r - a) * f for a, r in zip(c, SUN["radiance"]))
            row.append(c)
        rows.append(row)
    return rows


def neutral_studio(w, h):
    """Grey and colourless: a soft overhead light, two large softboxes left and right of the
    camera's +Z side, a mid-grey wall and a darker floor; no sun, so no hard shadows.
    Mean radiance about 0.5, so a white Lambert surface facing up reads about 0.9."""
    boxes = (
        {"u": 0.625, "elev": 25.0, "width": 50.0, "height": 40.0, "radiance": (3.0, 3.0, 3.0)},
        {"u": 0.875, "elev": 25.0, "width": 50.0, "height": 40.0, "radiance": (2.0, 2.0, 2.0)},
    )
    rows = []
    for j in range(h):
        v = (j + 0.5) / h
        elev = 90.0 - 180.0 * v
        top = smoothstep(30.0, 90.0, elev)                  # overhead soft light
        wall = 0.35 + 0.45 * top
        k = smoothstep(-HORIZON_BLEND_DEG, HORIZON_BLEND_DEG, elev)
        base = 0.12 + (wall - 0.12) * k
        row = []
        for i in range(w):
            u = (i + 0.5) / w
            c = base
            for box in boxes:
                f = softbox_weight(box, u, elev)
                c = c + (box["radiance"][0] - c) * f
            row.append((c, c, c))
        rows.append(row)
    return rows


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return b"\x00\x00\x00\x00"
    mant, e = math.frexp(m)
    s = mant * 256.0 / m
    return bytes((int(c[0] * s), int(c[1] * s), int(c[2] * s), e + 128))


def write_hdr(path, rows, note):
    h, w = len(rows), len(rows[0])
    out = bytearray(b"#?RADIANCE\n# " + note.encode("ascii") +
                    b"\nFORMAT=32-bit_rle_rgbe\n\n" + b"-Y %d +X %d\n" % (h, w))
    for row in rows:
        line = b"".join(rgbe(c) for c in row)
        # A flat scanline must not look like the start of an RLE scanline.
        assert not (line[0] == 2 and line[1] == 2 and line[2] < 128), "ambiguous scanline"
        out += line
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "wb") as f:
        f.write(out)
    print("wrote", path)


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("env"), "studio_sky.hdr")
    out_dir = os.path.dirname(path)
    write_hdr(path, studio_sky(512, 256),
              "Penumbra tools/assets/gen_environment.py: procedural studio sky")
    write_hdr(os.path.join(out_dir, "uniform_white.hdr"), [[(1.0, 1.0, 1.0)] * 64] * 32,
              "Penumbra tools/assets/gen_environment.py: uniform radiance 1.0")
    write_hdr(os.path.join(out_dir, "studio.hdr"), neutral_studio(128, 64),
              "Penumbra tools/assets/gen_environment.py: neutral studio")


if __name__ == "__main__":
    main(sys.argv[1:])
