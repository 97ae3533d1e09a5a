"""Cycles' shadow catcher on GroundShadowGLTest's scene (issue #62), for docs/features.md.

  blender -b --python tools/reference/ground_shadow_cycles.py -- [--samples 1024] [--size 192x144]

A unit sphere resting on a plane (Blender's shadow catcher, film transparent) under a uniform
white sky, seen from GroundShadowGLTest's camera (Penumbra's y-up (x, y, z) is Blender's
(x, -z, y)). Prints the catcher's alpha (the darkening) at ground points at distance d from the
sphere's foot, beside the analytic share of the sky the sphere hides, (d^2 + 1)^-3/2. Cycles'
catcher also counts the light the sphere reflects onto the ground, which Penumbra's ground
leaves out: --albedo 0 (a black sphere) compares the shadows alone. The catcher is white
(--catcher-albedo 1) and the sphere glTF's default dielectric, as in Penumbra's test.
"""
import argparse
import math
import sys

import bpy
from bpy_extras.object_utils import world_to_camera_view
from mathutils import Vector


def args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser()
    ap.add_argument("--samples", type=int, default=1024)
    ap.add_argument("--size", default="192x144")
    ap.add_argument("--albedo", type=float, default=0.5, help="the sphere's (0: no bounce)")
    ap.add_argument("--catcher-albedo", type=float, default=1.0,
                    help="the catcher's (Penumbra's ground is white; Blender's default 0.8)")
    return ap.parse_args(argv)


def main():
    a = args()
    w, h = (int(v) for v in a.size.split("x"))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.samples = a.samples
    scene.cycles.use_denoising = False
    scene.render.film_transparent = True
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    scene.render.image_settings.file_format = "OPEN_EXR"
    world = bpy.data.worlds.new("sky")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Color"].default_value = (1, 1, 1, 1)
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 1.0
    scene.world = world
    bpy.ops.mesh.primitive_uv_sphere_add(segments=96, ring_count=48, radius=1.0, location=(0, 0, 1))
    sphere = bpy.context.object
    bpy.ops.object.shade_smooth()
    mat = bpy.data.materials.new("grey")
    mat.use_nodes = True
    mat.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = (a.albedo,) * 3 + (1,)
    # lambert() of the test: glTF's dielectric (F0 0.04: Specular 0.5), roughness 1.
    mat.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.5
    mat.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    sphere.data.materials.append(mat)
    bpy.ops.mesh.primitive_plane_add(size=40.0, location=(0, 0, 0))
    bpy.context.object.is_shadow_catcher = True
    ground = bpy.data.materials.new("catcher")
    ground.use_nodes = True
    ground.node_tree.nodes["Principled BSDF"].inputs["Base Color"].default_value = \
        (a.catcher_albedo,) * 3 + (1,)
    ground.node_tree.nodes["Principled BSDF"].inputs["Specular"].default_value = 0.0
    ground.node_tree.nodes["Principled BSDF"].inputs["Roughness"].default_value = 1.0
    bpy.context.object.data.materials.append(ground)
    cam_data = bpy.data.cameras.new("cam")
    cam_data.sensor_fit = "VERTICAL"
    cam_data.angle = math.radians(40.0)
    cam = bpy.data.objects.new("cam", cam_data)
    scene.collection.objects.link(cam)
    cam.location = Vector((0.0, -6.0, 4.0))  # Penumbra's (0, 4, 6)
    target = Vector((0.0, 0.0, 0.5))        # Penumbra's (0, 0.5, 0)
    cam.rotation_euler = (target - cam.location).to_track_quat("-Z", "Y").to_euler()
    scene.camera = cam
    scene.render.filepath = "/tmp/ground_shadow_cycles.exr"
    bpy.ops.render.render(write_still=True)
    img = bpy.data.images.load(scene.render.filepath)
    px = list(img.pixels)

    def alpha(p):
        v = world_to_camera_view(scene, cam, Vector(p))
        x, y = int(v.x * w), int(v.y * h)
        s, n = 0.0, 0
        for dy in (-1, 0, 1):  # a 3x3 mean: Cycles' noise
            for dx in (-1, 0, 1):
                i = ((y + dy) * w + (x + dx)) * 4 + 3
                s += px[i]
                n += 1
        return s / n

    # The shadow region GroundShadowGLTest averages over: rings d = 1.1..2.0 from the sphere's
    # foot, at angles 0..180 degrees on the camera's side (Penumbra's (d cos a, 0, d sin a)).
    region = [(d * math.cos(math.radians(t)), 0.0, d * math.sin(math.radians(t)))
              for d in (1.1, 1.2, 1.4, 1.6, 2.0) for t in (0, 45, 90, 135, 180)]
    # Penumbra's (x, y, z) is Blender's (x, -z, y).
    mean = sum(alpha((x, -z, y)) for x, y, z in region) / len(region)
    print("ground-shadow: albedo %.2f region mean darkening %.4f over %d points" %
          (a.albedo, mean, len(region)))
    for d in (1.2, 1.6, 2.4):
        # GroundShadowGLTest's points: (d, 0, 0) and (-d, 0, 0) in Penumbra's frame.
        got = 0.5 * (alpha((d, 0.0, 0.0)) + alpha((-d, 0.0, 0.0)))
        print("ground-shadow: albedo %.2f d %.1f Cycles darkening %.3f analytic %.3f" %
              (a.albedo, d, got, (d * d + 1.0) ** -1.5))


main()
