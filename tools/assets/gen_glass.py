#!/usr/bin/env python3
"""Glass shelf: transparent (BLEND) and cut-out (MASK) materials for the evaluation.

Writes assets/glass/glass.gltf + glass.bin + lattice.png (or --out-dir).
A floor and a back wall, lit by a dim uniform sky and one EXT_lights_area rect light
(0.7 x 0.5 m, 25 nits) above front-left, so every transparent part casts a shadow:
  pane     an upright blue-tinted glass pane (BLEND, alpha 0.3, double-sided),
           in front of an opaque orange box
  bubble   a red sphere of alpha 0.45 (BLEND, double-sided: front and back layers)
  lattice  a green trellis cut from one quad by an 8 x 8 texture whose alpha is a
           checkerboard of holes (MASK, cutoff 0.5, nearest filtering)
  stand    an opaque grey block under the bubble
Metres, +Y up, camera on +Z looking toward -Z.
"""
import math
import os
import struct
import sys
import zlib

import gltf_builder as gb


def png_rgba(width, height, pixel):
    """An RGBA8 PNG (zlib is the standard library's; the container is four chunks)."""
    raw = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y))
                   for y in range(height))

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data +
                struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def lattice_texel(x, y):
    hole = (x + y) % 2 == 1 and 0 < x < 7 and 0 < y < 7  # a solid frame around the holes
    return (255, 255, 255, 0 if hole else 255)


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("glass"), "glass.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_glass.py")
    nodes = []

    room = gb.MeshData()
    room.quad((-3, 0, 2), (3, 0, 2), (3, 0, -1.2), (-3, 0, -1.2), (0, 1, 0))
    room.quad((-3, 0, -1.2), (3, 0, -1.2), (3, 2.5, -1.2), (-3, 2.5, -1.2), (0, 0, 1))
    walls = b.material("walls", (0.7, 0.7, 0.7), roughness=0.8)
    nodes.append(b.node("room", mesh=b.mesh("room", [b.primitive(room, walls)])))

    box = gb.MeshData()
    box.box((-0.5, 0.0, -0.55), (-0.15, 0.35, -0.25), skip=("-y",))
    orange = b.material("orange", (0.85, 0.35, 0.08), roughness=0.5)
    nodes.append(b.node("box", mesh=b.mesh("box", [b.primitive(box, orange)])))

    pane = gb.MeshData()
    pane.quad((-0.7, 0.0, 0.05), (-0.05, 0.0, 0.05), (-0.05, 0.55, 0.05), (-0.7, 0.55, 0.05),
              (0, 0, 1))
    glass = b.material("blue_glass", (0.35, 0.6, 0.95), roughness=0.05, alpha=0.3,
                       alpha_mode="BLEND", double_sided=True)
    nodes.append(b.node("pane", mesh=b.mesh("pane", [b.primitive(pane, glass)])))

    stand = gb.MeshData()
    stand.box((0.2, 0.0, -0.05), (0.5, 0.12, 0.25), skip=("-y",))
    grey = b.material("stand", (0.4, 0.4, 0.42), roughness=0.4)
    nodes.append(b.node("stand", mesh=b.mesh("stand", [b.primitive(stand, grey)])))

    bubble = gb.MeshData()
    bubble.uv_sphere((0.35, 0.3, 0.1), 0.18, 48, 24)
    red = b.material("red_bubble", (0.9, 0.15, 0.1), roughness=0.15, alpha=0.45,
                     alpha_mode="BLEND", double_sided=True)
    nodes.append(b.node("bubble", mesh=b.mesh("bubble", [b.primitive(bubble, red)])))

    trellis = gb.MeshData()
    trellis.quad((0.1, 0.0, -0.6), (0.9, 0.0, -0.6), (0.9, 0.8, -0.6), (0.1, 0.8, -0.6), (0, 0, 1),
                 uvs=((0, 1), (1, 1), (1, 0), (0, 0)))
    tex = b.texture(png_rgba(8, 8, lattice_texel), "lattice.png", nearest=True)
    green = b.material("green_lattice", (0.2, 0.6, 0.25), roughness=0.6, alpha_mode="MASK",
                       double_sided=True, base_texture=tex)
    nodes.append(b.node("lattice", mesh=b.mesh("lattice", [b.primitive(trellis, green)])))

    pos, target = (-0.8, 1.7, 1.0), (0.0, 0.2, -0.2)
    ext = b.area_light("key", "rect", (1.0, 0.97, 0.92), 25.0, 0.5, 1.4)
    nodes.append(b.node("key", translation=pos, rotation=gb.quat_look(pos, target), extensions=ext))

    eye = (0.15, 0.75, 1.9)
    cam = b.camera("glass", math.radians(38.0), 16.0 / 9.0, 0.05, 50.0)
    nodes.append(b.node("glass", camera=cam, translation=eye,
                        rotation=gb.quat_look(eye, (0.0, 0.25, -0.25))))

    b.scene("glass", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
