#!/usr/bin/env python3
"""Layers: the showroom's objects with every KHR_materials_* texture, for issue #37's texture
budget (each extension texture a layer of one texture array per material).

Writes assets/layers/layers.gltf + layers.bin + five PNGs (or --out-dir).
Lit by the studio sky (assets/env/studio_sky.hdr) and the showroom's rect key light:
  paint    red car paint whose clearcoat comes in bands (clearcoatTexture .r: coat 1 / 0.25)
           and whose coat roughness changes between its halves (clearcoatRoughnessTexture .g),
           with the coat's own normal map (ripples: clearcoatNormalTexture)
  cushion  dark velvet with a checker of two sheen colours (sheenColorTexture, sRGB) and two
           sheen roughnesses (sheenRoughnessTexture .a), on a 2x UV transform
  plinth   a black dielectric block with stripes of specular strength (specularTexture .a) and
           colour (specularColorTexture, sRGB)
  pane     an upright thin-walled pane whose transmission comes in bars (transmissionTexture
           .r: 1 / 0.3)
  glass    a glass ball whose volume thickness varies (thicknessTexture .g), on the plinth
The textures differ in size (16, 32, 64 texels), so a material's layers are resampled to one.
Metres, +Y up, camera on +Z looking toward -Z.
"""
import math
import sys

import gltf_builder as gb
from gen_glass import png_rgba
from gen_kitchen import proxy_mesh
from gen_product import sweep
from gen_showroom import rounded_block


def coat_texel(x, y):
    """16x16: .r the coat in horizontal bands, .g the coat roughness by halves."""
    return (255 if (y // 4) % 2 == 0 else 64, 20 if x < 8 else 200, 0, 255)


def ripple_texel(x, y):
    """32x32 tangent-space normals: ripples along u."""
    s = math.sin(2 * math.pi * x / 8)
    n = gb.normalize((0.5 * s, 0.0, 1.0))
    return tuple(int(round((c * 0.5 + 0.5) * 255)) for c in n) + (255,)


def sheen_texel(x, y):
    """16x16 checker: sRGB colour (warm / cool), .a roughness (0.3 / 0.8)."""
    warm = ((x // 4) + (y // 4)) % 2 == 0
    return (230, 180, 120, 77) if warm else (120, 170, 235, 204)


def specular_texel(x, y):
    """64x64 vertical stripes: sRGB specular colour (white / orange), .a strength (1 / 0.2)."""
    if (x // 8) % 2 == 0:
        return (255, 255, 255, 255)
    return (255, 140, 40, 51)


def pane_texel(x, y):
    """32x32: .r transmission in vertical bars (1 / 0.3), .g the glass ball's thickness."""
    return (255 if (x // 4) % 2 == 0 else 77, 64 + 6 * y, 0, 255)


def main(argv):
    path = gb.out_path(argv, gb.repo_assets("layers"), "layers.gltf")
    b = gb.GltfBuilder("Penumbra tools/assets/gen_layers.py")
    nodes = []
    coat = b.texture(png_rgba(16, 16, coat_texel), "coat.png")
    ripples = b.texture(png_rgba(32, 32, ripple_texel), "ripples.png")
    sheen = b.texture(png_rgba(16, 16, sheen_texel), "sheen.png")
    specular = b.texture(png_rgba(64, 64, specular_texel), "specular.png")
    bars = b.texture(png_rgba(32, 32, pane_texel), "bars.png")

    backdrop = b.material("backdrop", (0.75, 0.75, 0.75), roughness=0.6)
    nodes.append(b.node("sweep", mesh=b.mesh("sweep", [b.primitive(sweep(), backdrop)])))

    paint_ball = gb.MeshData()
    paint_ball.uv_sphere((-0.24, 0.12, -0.12), 0.12, 64, 32)
    paint = b.material("car_paint", (0.55, 0.02, 0.03), roughness=0.45, extensions={
        "KHR_materials_clearcoat": {
            "clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 1.0,
            "clearcoatTexture": {"index": coat},
            "clearcoatRoughnessTexture": {"index": coat},
            "clearcoatNormalTexture": {"index": ripples, "scale": 0.6}}})
    nodes.append(b.node("paint", mesh=b.mesh("paint", [b.primitive(paint_ball, paint)])))

    plinth = gb.MeshData()
    plinth.box((-0.1, 0.0, 0.12), (0.1, 0.06, 0.32), skip=("-y",))
    black = b.material("plinth", (0.02, 0.02, 0.02), roughness=0.25, extensions={
        "KHR_materials_specular": {"specularFactor": 1.0, "specularColorFactor": [1, 1, 1],
                                   "specularTexture": {"index": specular},
                                   "specularColorTexture": {"index": specular}}})
    nodes.append(b.node("plinth", mesh=b.mesh("plinth", [b.primitive(plinth, black)])))

    ball = gb.MeshData()
    ball.uv_sphere((0.0, 0.16, 0.22), 0.1, 64, 32)
    glass = b.material("glass", (1.0, 1.0, 1.0), roughness=0.0, extensions={
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_volume": {"thicknessFactor": 0.2, "attenuationDistance": 0.15,
                                 "attenuationColor": [0.8, 0.95, 0.85],
                                 "thicknessTexture": {"index": bars}},
        "KHR_materials_ior": {"ior": 1.5}})
    nodes.append(b.node("glass", mesh=b.mesh("glass", [b.primitive(ball, glass)])))

    pane = gb.MeshData()
    pane.quad((0.22, 0.0, 0.42), (0.5, 0.0, 0.5), (0.5, 0.26, 0.5), (0.22, 0.26, 0.42))
    tinted = b.material("pane", (0.8, 0.9, 1.0), roughness=0.0, double_sided=True,
                        extensions={"KHR_materials_transmission": {
                            "transmissionFactor": 1.0,
                            "transmissionTexture": {"index": bars}}})
    nodes.append(b.node("pane", mesh=b.mesh("pane", [b.primitive(pane, tinted)])))

    cushion = rounded_block((0.2, 0.0, 0.08), (0.5, 0.1, 0.3), 0.04, 16)
    twice = {"KHR_texture_transform": {"scale": [2.0, 2.0]}}
    velvet = b.material("velvet", (0.04, 0.04, 0.05), roughness=0.9, extensions={
        "KHR_materials_sheen": {"sheenColorFactor": [1.0, 1.0, 1.0],
                                "sheenRoughnessFactor": 1.0,
                                "sheenColorTexture": {"index": sheen, "extensions": twice},
                                "sheenRoughnessTexture": {"index": sheen, "extensions": twice}}})
    b.ext_used.add("KHR_texture_transform")
    nodes.append(b.node("cushion", mesh=b.mesh("cushion", [b.primitive(cushion, velvet)])))

    target = (0.0, 0.15, 0.0)
    nodes.append(b.lamp_node("key", "rect", (1.0, 0.95, 0.9), 8.0, 0.5, 1.6,
                             proxy_mesh("rect", 0.5, 1.6), (-0.9, 1.1, 0.9), target))

    eye = (0.0, 0.42, 1.25)
    cam = b.camera("layers", math.radians(32.0), 1.5, 0.02, 50.0)
    nodes.append(b.node("layers", camera=cam, translation=eye,
                        rotation=gb.quat_look(eye, (0.05, 0.12, 0.0))))

    b.scene("layers", nodes)
    b.write_gltf(path)
    print("wrote", path)


if __name__ == "__main__":
    main(sys.argv[1:])
