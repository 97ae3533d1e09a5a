#!/usr/bin/env python3
"""Tiny pure-Python rasterizer for eyeballing generated scenes (not a renderer).

Draws every triangle from a glTF camera, flat-shaded: base colour times a
headlight term (so faces are told apart), emissive materials at their
(clamped) emission, back faces culled as glTF specifies for single-sided
materials. Area lights are outlined in yellow with a short magenta stroke
along their emission direction (local -Z). Writes an 8-bit sRGB PNG with zlib.

Use it to check orientation conventions (red wall left, light facing down...),
never as a reference image.
Usage: preview_gltf.py SCENE.gltf|.glb OUT.png [--camera NAME] [--width W]
"""
import argparse
import math
import struct
import zlib

from check_gltf import Checker

# The EXT_lights_area shapes this reader knows: renderer/src/scene/light_kinds.cpp's area rows
# (tests/cli/light_readers.sh fails when a shape there is missing here).
AREA_SHAPES = ('rect', 'disk')


def write_png(path, w, h, rows):
    """rows: list of bytes objects, 3*w bytes each (RGB8)."""
    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + r for r in rows)  # filter type 0 on every row
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def srgb(c):
    c = min(max(c, 0.0), 1.0)
    v = 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055
    return int(v * 255 + 0.5)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--camera", default=None)
    ap.add_argument("--width", type=int, default=400)
    args = ap.parse_args()

    c = Checker(args.scene)
    c.load()
    c.world_matrices()
    doc, nodes = c.doc, c.doc["nodes"]
    cam_nodes = [i for i in c.world if "camera" in nodes[i]]
    if args.camera:
        cam_nodes = [i for i in cam_nodes if nodes[i].get("name") == args.camera]
    ci = cam_nodes[0]
    m = c.world[ci]
    persp = doc["cameras"][nodes[ci]["camera"]]["perspective"]
    aspect = persp.get("aspectRatio", 16 / 9)
    W = args.width
    H = max(1, int(round(W / aspect)))
    tan_y = math.tan(persp["yfov"] / 2)
    eye = [m[i][3] for i in range(3)]

    def unit(v):
        n = math.sqrt(sum(x * x for x in v))
        return [x / n for x in v]
    right = unit([m[i][0] for i in range(3)])
    up = unit([m[i][1] for i in range(3)])
    back = unit([m[i][2] for i in range(3)])
    znear = persp["znear"]

    def to_cam(p):
        d = [p[k] - eye[k] for k in range(3)]
        return (sum(d[k] * right[k] for k in range(3)), sum(d[k] * up[k] for k in range(3)),
                -sum(d[k] * back[k] for k in range(3)))

    def to_screen(q):
        return ((q[0] / (q[2] * tan_y * aspect) * 0.5 + 0.5) * W,
                (0.5 - q[1] / (q[2] * tan_y) * 0.5) * H, 1.0 / q[2])

    color = [[(0.02, 0.02, 0.03)] * W for _ in range(H)]
    depth = [[0.0] * W for _ in range(H)]  # stores 1/z; larger is closer

    def raster(tri, rgb):
        (x0, y0, w0), (x1, y1, w1), (x2, y2, w2) = tri
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area >= 0:  # screen y points down, so front faces (CCW) have area < 0
            return
        for py in range(max(0, int(min(y0, y1, y2))), min(H, int(max(y0, y1, y2)) + 1)):
            cy = py + 0.5
            for px in range(max(0, int(min(x0, x1, x2))), min(W, int(max(x0, x1, x2)) + 1)):
                cx = px + 0.5
                a = ((x1 - cx) * (y2 - cy) - (x2 - cx) * (y1 - cy)) / area
                b = ((x2 - cx) * (y0 - cy) - (x0 - cx) * (y2 - cy)) / area
                g = 1.0 - a - b
                if a < 0 or b < 0 or g < 0:
                    continue
                wz = a * w0 + b * w1 + g * w2
                if wz > depth[py][px]:
                    depth[py][px] = wz
                    color[py][px] = rgb

    mats = doc.get("materials", [])
    for ni, wm in c.world.items():
        if "mesh" not in nodes[ni]:
            continue
        for prim in doc["meshes"][nodes[ni]["mesh"]]["primitives"]:
            mat = mats[prim["material"]] if "material" in prim else {}
            base = mat.get("pbrMetallicRoughness", {}).get("baseColorFactor", [1, 1, 1, 1])
            emis = mat.get("emissiveFactor", [0, 0, 0])
            strength = mat.get("extensions", {}).get("KHR_materials_emissive_strength", {}) \
                .get("emissiveStrength", 1.0)
            pos = [Checker.xform(wm, p) for p in c.read_accessor(prim["attributes"]["POSITION"])]
            cam = [to_cam(p) for p in pos]
            idx = [t[0] for t in c.read_accessor(prim["indices"])]
            for t in range(0, len(idx), 3):
                tri = [cam[idx[t]], cam[idx[t + 1]], cam[idx[t + 2]]]
                e1 = [tri[1][k] - tri[0][k] for k in range(3)]
                e2 = [tri[2][k] - tri[0][k] for k in range(3)]
                # Camera space here is (right, up, forward): left-handed, so the
                # front-face normal is e2 x e1 rather than e1 x e2.
                n = unit([e2[1] * e1[2] - e2[2] * e1[1], e2[2] * e1[0] - e2[0] * e1[2],
                          e2[0] * e1[1] - e2[1] * e1[0]]) if any(e1) and any(e2) else [0, 0, -1]
                view = unit([-x for x in tri[0]]) if any(tri[0]) else [0, 0, -1]
                shade = 0.25 + 0.75 * max(0.0, sum(n[k] * view[k] for k in range(3)))
                if any(emis):
                    rgb = tuple(min(1.0, e * strength) for e in emis)
                else:
                    rgb = tuple(b_ * shade for b_ in base[:3])
                poly = clip_near(tri, znear)
                scr = [to_screen(q) for q in poly]
                for k in range(1, len(scr) - 1):
                    raster((scr[0], scr[k], scr[k + 1]), rgb)

    # Overlays: area light outlines and emission direction.
    lights = doc.get("extensions", {}).get("EXT_lights_area", {}).get("lights", [])
    for ni, wm in c.world.items():
        ext = nodes[ni].get("extensions", {}).get("EXT_lights_area")
        if ext is None:
            continue
        lt = lights[ext["light"]]
        if lt.get("type") not in AREA_SHAPES:
            continue  # check_gltf reports it
        s = lt.get("size", 1.0)
        hw = s * (lt["rect"].get("aspect", 1.0) if lt["type"] == "rect" else 1.0) / 2
        if lt["type"] == "rect":
            outline = [(-hw, -s / 2), (hw, -s / 2), (hw, s / 2), (-hw, s / 2)]
        else:
            outline = [(s / 2 * math.cos(a * math.pi / 8), s / 2 * math.sin(a * math.pi / 8))
                       for a in range(16)]
        pts = [to_cam(Checker.xform(wm, (x, y, 0))) for x, y in outline]
        for k in range(len(pts)):
            line(color, W, H, pts[k], pts[(k + 1) % len(pts)], znear, to_screen, (1, 1, 0))
        line(color, W, H, to_cam(Checker.xform(wm, (0, 0, 0))),
             to_cam(Checker.xform(wm, (0, 0, -max(s, 0.05)))), znear, to_screen, (1, 0, 1))

    rows = [bytes(v for px in row for v in (srgb(px[0]), srgb(px[1]), srgb(px[2])))
            for row in color]
    write_png(args.out, W, H, rows)
    print("wrote %s (%dx%d) from camera '%s'" % (args.out, W, H, nodes[ci].get("name")))


def clip_near(poly, zn):
    """Sutherland-Hodgman against the plane z = zn (camera space, z forward)."""
    out = []
    for i, p in enumerate(poly):
        q = poly[(i + 1) % len(poly)]
        if p[2] >= zn:
            out.append(p)
        if (p[2] >= zn) != (q[2] >= zn):
            t = (zn - p[2]) / (q[2] - p[2])
            out.append(tuple(p[k] + t * (q[k] - p[k]) for k in range(3)))
    return out


def line(color, W, H, a, b, zn, to_screen, rgb):
    seg = clip_near([a, b], zn)
    if len(seg) < 2:
        return
    (x0, y0, _), (x1, y1, _) = to_screen(seg[0]), to_screen(seg[1])
    n = int(max(abs(x1 - x0), abs(y1 - y0))) + 1
    for k in range(n + 1):
        x = int(x0 + (x1 - x0) * k / n)
        y = int(y0 + (y1 - y0) * k / n)
        if 0 <= x < W and 0 <= y < H:
            color[y][x] = rgb


if __name__ == "__main__":
    main()
