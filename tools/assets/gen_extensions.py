#!/usr/bin/env python3
"""The later KHR_materials_* extensions side by side, for the evaluation and the GL/browser tests.

Writes assets/extensions/extensions.gltf + .bin + four PNGs (or --out-dir).
Four objects on a floor before a checkered back wall, left to right (metres, +Y up, camera
on +Z looking toward -Z):
  film     a dark glossy sphere with a soap-film coat (KHR_materials_iridescence: ior 1.3,
           thickness 200..600 nm from a texture that ramps across the sphere's u, whose red
           channel weakens the film in bands)
  brushed  a metal sphere with KHR_materials_anisotropy (strength 0.9 along the UV
           sphere's u, halved in bands of v by its texture: highlights stretched around it)
  leaf     an upright double-sided card (KHR_materials_diffuse_transmission 0.8, yellow-green,
           darker veins that pass less light: one texture for colour and strength) with a rect
           light behind it facing the camera: its glow is light passed through
  prism    a glass ball (KHR_materials_transmission + _volume, ior 1.7) with
           KHR_materials_dispersion 1.5: the checks seen through it part into colours
A dim uniform sky and a key light above front-left light the rest.
"""
import math
import sys

import gltf_builder as gb
from gen_glass import png_rgba

R = 0.32  # sphere radius


def ramp_texel(x, y):
    # Film thickness along u: .g from 0 (minimum) to 255 (maximum) and back (seamless); the
    # film's strength (.r) drops to a quarter in every fourth band of four texels.
    g = int(round(255 * (1.0 - abs(2.0 * x / 31.0 - 1.0))))
    return (64 if (x // 4) % 4 == 3 else 255, g, 0, 255)


def brush_texel(x, y):
    # Anisotropy along the tangent (.rg = (1, 0) in [-1, 1]), its strength (.b) in bands of v:
    # full, then half.
    return (255, 128, 255 if (y // 4) % 2 == 0 else 128, 255)


def leaf_texel(x, y):
    # Veins (a midrib and six side veins) pass less light (.a 0.35) in a darker green; the blade
    # passes it all in yellow-green.
    u, v = (x + 0.5) / 32.0, (y + 0.5) / 32.0
    vein = abs(u - 0.5) < 0.03 or any(abs((v - 0.15 * k) - abs(u - 0.5) * 0.8) < 0.025
                                      for k in range(1, 7))
    return (60, 110, 20, 90) if vein else (225, 255, 80, 255)


def checker_texel(x, y):
    v = 235 if (x + y) % 2 == 0 else 30
    return (v, v, v, 255)


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("extensions"), "extensions.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_extensions.py")
    nodes = []

    floor = gb.MeshData()
    floor.quad((-3, 0, 2), (3, 0, 2), (3, 0, -1.2), (-3, 0, -1.2), (0, 1, 0))
    grey = b.material("floor", (0.6, 0.6, 0.6), roughness=0.7)
    nodes.append(b.node("floor", mesh=b.mesh("floor", [b.primitive(floor, grey)])))
    wall = gb.MeshData()
    wall.quad((-3, 0, -1.2), (3, 0, -1.2), (3, 2.0, -1.2), (-3, 2.0, -1.2), (0, 0, 1),
              uvs=((0, 5), (12, 5), (12, 0), (0, 0)))
    checks = b.texture(png_rgba(2, 2, checker_texel), "checker.png", nearest=True)
    walls = b.material("checks", (1.0, 1.0, 1.0), roughness=0.8, base_texture=checks)
    nodes.append(b.node("wall", mesh=b.mesh("wall", [b.primitive(wall, walls)])))

    def sphere(name, x, material):
        m = gb.MeshData()
        m.uv_sphere((x, R + 0.02, 0.0), R, 64, 32)
        nodes.append(b.node(name, mesh=b.mesh(name, [b.primitive(m, material)])))

    ramp = b.texture(png_rgba(32, 1, ramp_texel), "film_thickness.png")
    film = b.material("film", (0.04, 0.04, 0.05), roughness=0.12, extensions={
        "KHR_materials_iridescence": {
            "iridescenceFactor": 1.0, "iridescenceIor": 1.3,
            "iridescenceThicknessMinimum": 200, "iridescenceThicknessMaximum": 600,
            "iridescenceTexture": {"index": ramp},
            "iridescenceThicknessTexture": {"index": ramp}}})
    sphere("film", -1.5, film)
    brush = b.texture(png_rgba(16, 16, brush_texel), "brush.png")
    brushed = b.material("brushed", (0.92, 0.92, 0.95), metallic=1.0, roughness=0.35,
                         extensions={"KHR_materials_anisotropy": {
                             "anisotropyStrength": 0.9, "anisotropyTexture": {"index": brush}}})
    sphere("brushed", -0.5, brushed)

    card = gb.MeshData()
    card.quad((0.2, 0.05, 0.0), (0.8, 0.05, 0.0), (0.8, 0.75, 0.0), (0.2, 0.75, 0.0), (0, 0, 1),
              uvs=((0, 1), (1, 1), (1, 0), (0, 0)))
    veins = b.texture(png_rgba(32, 32, leaf_texel), "leaf.png")
    leaf = b.material("leaf", (0.25, 0.5, 0.1), roughness=0.6, double_sided=True, extensions={
        "KHR_materials_diffuse_transmission": {
            "diffuseTransmissionFactor": 0.8,
            "diffuseTransmissionTexture": {"index": veins},
            "diffuseTransmissionColorFactor": [0.9, 1.0, 0.3],
            "diffuseTransmissionColorTexture": {"index": veins}}})
    nodes.append(b.node("leaf", mesh=b.mesh("leaf", [b.primitive(card, leaf)])))
    pos, target = (0.5, 0.4, -0.7), (0.5, 0.4, 0.0)
    ext = b.area_light("behind_leaf", "rect", (1.0, 0.95, 0.85), 12.0, 0.5, 1.0)
    nodes.append(b.node("behind_leaf", translation=pos, rotation=gb.quat_look(pos, target),
                        extensions=ext))

    prism = b.material("prism", (1.0, 1.0, 1.0), roughness=0.0, extensions={
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_volume": {"thicknessFactor": 2 * R},
        "KHR_materials_ior": {"ior": 1.7},
        "KHR_materials_dispersion": {"dispersion": 1.5}})
    sphere("prism", 1.5, prism)

    pos, target = (-1.2, 2.2, 1.6), (0.0, 0.3, 0.0)
    ext = b.area_light("key", "rect", (1.0, 0.97, 0.92), 30.0, 0.6, 1.4)
    nodes.append(b.node("key", translation=pos, rotation=gb.quat_look(pos, target), extensions=ext))

    eye = (0.0, 0.95, 3.0)
    cam = b.camera("extensions", math.radians(38.0), 16.0 / 9.0, 0.05, 50.0)
    nodes.append(b.node("extensions", camera=cam, translation=eye,
                        rotation=gb.quat_look(eye, (0.0, 0.35, 0.0))))

    b.scene("extensions", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
