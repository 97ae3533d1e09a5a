"""Render a Penumbra scene file with Blender (Cycles reference or Eevee peer).

Run by tools/reference/render:
  blender -b --factory-startup --python tools/reference/blender_scene.py -- \
      SCENE.json OUT.exr --engine cycles|eevee [--samples N] [--size WxH] [--threads T]
      [--bounces N]

What it does, so that Blender sees what Penumbra sees:
  * imports the glTF with Blender's importer (numpy.bool workaround first);
  * camera: the scene file's camera (name or index; else the first glTF camera), placed from
    the glTF node hierarchy read here, vertical field of view kept (sensor fit VERTICAL),
    aspect from the output size, as penumbra-render does;
  * EXT_lights_area lights, which the importer ignores, become Blender area lights
    (rect -> RECTANGLE size_x = size*aspect, size_y = size; disk -> DISK, size = diameter),
    power P = 4 L A (Blender's area light emits radiance P / (4 A)), same colour, placed with
    the node's world matrix so that local -Z (the emission direction) is kept;
  * the lamp-surface proxies (extras.area_light_proxy) stay visible to camera rays only, so the
    camera sees the lamp (as in Penumbra) but nothing is lit twice;
  * environment: panorama as world texture (Blender's convention is the one Penumbra uses),
    strength = intensity, rotation about +Y (glTF) = about +Z (Blender); or a uniform colour;
  * materials: glTF's BRDF rebuilt from Blender nodes (gltf_brdf.py; --material principled
    keeps the importer's Principled BSDF);
  * scale: Blender reads glTF units as metres, so a scene modelled in centimetres
    (assets/room_cm) is 100 times bigger there. Camera, light placement and sizes come from the
    file's numbers unchanged and P = 4 L A takes the area in those units, so the radiance L and
    the image are the same at any scale (checked with Cycles: room_cm and a copy in metres give
    the same image). Eevee's GTAO distance follows the scene's diagonal as Penumbra's occlusion
    distance does; its SSR thickness and light shadow clip start stay Blender's defaults;
  * Standard view transform, no denoising, box pixel filter 1 px (Penumbra's jittered running
    mean), linear 32-bit EXR, render time written to OUT.json.
"""
import json
import math
import os
import sys
import time

import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian's Blender 3.4 glTF importer uses numpy.bool (removed in numpy 1.24)

import bpy
import mathutils


def scene_diagonal():
    """The diagonal of the world-space bounding box of every mesh (as Penumbra's bounds)."""
    import mathutils
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH":
            continue
        for corner in ob.bound_box:
            w = ob.matrix_world @ mathutils.Vector(corner)
            for k in range(3):
                lo[k], hi[k] = min(lo[k], w[k]), max(hi[k], w[k])
    if lo[0] > hi[0]:
        return 4.0
    return sum((h - l) ** 2 for l, h in zip(lo, hi)) ** 0.5


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    import argparse
    ap = argparse.ArgumentParser(prog="blender_scene.py")
    ap.add_argument("scene")
    ap.add_argument("out")
    ap.add_argument("--engine", choices=["cycles", "eevee"], default="cycles")
    ap.add_argument("--samples", type=int, default=128)
    ap.add_argument("--size", default=None)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=1)
    # Cycles only: the path set, for the bias budget (tools/bias-budget): 0 = direct light only
    # (what the camera's first hit receives from lights and the environment), 1 = plus one
    # bounce, N = every kind of bounce up to N, -1 = Blender's defaults (12 in all, but diffuse
    # and glossy paths end after 4).
    ap.add_argument("--bounces", type=int, default=-1)
    # The bias budget's split of the direct term: the scene's lights alone (the world, and with
    # it the environment's sun, black).
    ap.add_argument("--no-world", action="store_true")
    # Cycles only: no indirect clamp (Blender's default clamps indirect samples at 10, which
    # removes energy from bright indirect paths); checks whether a reference is low by
    # construction (the room (cm): the same mean to 4 digits).
    ap.add_argument("--no-clamp", action="store_true")
    ap.add_argument("--material", choices=["gltf", "principled"], default="gltf",
                    help="gltf: glTF's BRDF as a node tree (default); principled: the importer's")
    return ap.parse_args(argv)


def load_scene(path):
    path = os.path.abspath(path)
    if path.endswith(".json"):
        with open(path) as f:
            sf = json.load(f)
        base = os.path.dirname(path)
        sf["gltf"] = os.path.normpath(os.path.join(base, sf["gltf"]))
        env = sf.get("environment")
        if isinstance(env, str):
            env = {"file": env}
        if isinstance(env, dict) and "file" in env:
            env["file"] = os.path.normpath(os.path.join(base, env["file"]))
        sf["environment"] = env
    else:
        sf = {"gltf": path}
    return sf


def read_gltf_json(path):
    if path.endswith(".glb"):
        import struct
        with open(path, "rb") as f:
            data = f.read()
        magic, version, length = struct.unpack_from("<III", data, 0)
        clen, ctype = struct.unpack_from("<II", data, 12)
        return json.loads(data[20:20 + clen].decode("utf-8"))
    with open(path) as f:
        return json.load(f)


def node_local(n):
    if "matrix" in n:
        m = n["matrix"]  # column-major
        return mathutils.Matrix([[m[c * 4 + r] for c in range(4)] for r in range(4)])
    t = n.get("translation", [0, 0, 0])
    r = n.get("rotation", [0, 0, 0, 1])
    s = n.get("scale", [1, 1, 1])
    q = mathutils.Quaternion((r[3], r[0], r[1], r[2]))
    return (mathutils.Matrix.Translation(t) @ q.to_matrix().to_4x4()
            @ mathutils.Matrix.Diagonal((s[0], s[1], s[2], 1.0)))


def world_matrices(g):
    """World matrix (glTF frame) of every node reachable from the default scene."""
    out = {}
    scene = g.get("scenes", [{}])[g.get("scene", 0)] if g.get("scenes") else {"nodes": []}

    def walk(i, parent):
        m = parent @ node_local(g["nodes"][i])
        out[i] = m
        for c in g["nodes"][i].get("children", []):
            walk(c, m)

    for i in scene.get("nodes", []):
        walk(i, mathutils.Matrix.Identity(4))
    return out


# glTF (x, y, z) -> Blender (x, -z, y): a rotation of +90 degrees about X.
# The EXT_lights_area shapes this reader knows: renderer/src/scene/light_kinds.cpp's area rows
# (tests/cli/light_readers.sh fails when a shape there is missing here).
AREA_SHAPES = ('rect', 'disk')
GLTF_TO_BLENDER = mathutils.Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))


def to_blender(m):
    # Cameras and lights look down local -Z in both glTF and Blender: keep the local frame,
    # change only the world frame.
    return GLTF_TO_BLENDER @ m


def main():
    a = parse_args()
    sf = load_scene(a.scene)
    g = read_gltf_json(sf["gltf"])
    worlds = world_matrices(g)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    bpy.ops.import_scene.gltf(filepath=sf["gltf"])
    rebuilt = 0
    if a.material == "gltf":
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from gltf_brdf import use_gltf_brdf
        rebuilt = use_gltf_brdf(g.get("materials", []), g,
                                os.path.dirname(os.path.abspath(sf["gltf"])))

    # ---- output size
    if a.size:
        w, h = (int(v) for v in a.size.lower().split("x"))
    elif "resolution" in sf:
        w, h = sf["resolution"]
    else:
        w, h = 1280, 720
    scene.render.resolution_x, scene.render.resolution_y = w, h
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0

    # ---- camera (penumbra-render: scene file's camera by name or index, else the first)
    cam_nodes = [i for i in sorted(worlds) if "camera" in g["nodes"][i]]
    want = sf.get("camera")
    cam_node = None
    if isinstance(want, int):
        cam_node = next((i for i in cam_nodes if g["nodes"][i]["camera"] == want), None)
    elif isinstance(want, str):
        for i in cam_nodes:
            n = g["nodes"][i]
            if n.get("name") == want or g["cameras"][n["camera"]].get("name") == want:
                cam_node = i
                break
    if cam_node is None:
        # the first camera of the file (cameras[0]) as penumbra-render does
        cam_node = next((i for i in cam_nodes if g["nodes"][i]["camera"] == 0),
                        cam_nodes[0] if cam_nodes else None)
    if cam_node is None:
        raise SystemExit("no camera in the glTF: Penumbra's automatic framing is not reproduced")
    gcam = g["cameras"][g["nodes"][cam_node]["camera"]]
    cdata = bpy.data.cameras.new("penumbra_camera")
    cdata.sensor_fit = "VERTICAL"
    cdata.sensor_height = 24.0
    if gcam.get("type") == "orthographic":
        # Penumbra keeps ymag (half the height) and takes the width from the image's aspect.
        ortho = gcam["orthographic"]
        cdata.type = "ORTHO"
        cdata.ortho_scale = 2.0 * ortho["ymag"]
        cdata.clip_start = max(ortho.get("znear", 0.0), 1e-4)
        cdata.clip_end = ortho["zfar"]
    else:
        persp = gcam["perspective"]
        cdata.angle_y = persp["yfov"]
        cdata.clip_start = persp.get("znear", 0.01)
        # No zfar: Penumbra's far plane is at infinity; Blender needs one, beyond the scene at
        # any scale (a room modelled in centimetres is hundreds of Blender metres across).
        cdata.clip_end = persp.get("zfar", max(1000.0, 100.0 * scene_diagonal()))
    cobj = bpy.data.objects.new("penumbra_camera", cdata)
    scene.collection.objects.link(cobj)
    cobj.matrix_world = to_blender(worlds[cam_node])
    scene.camera = cobj

    # ---- proxies: camera rays only
    nproxy = 0
    for obj in scene.objects:
        if "area_light_proxy" in obj.keys():
            nproxy += 1
            obj.visible_diffuse = False
            obj.visible_glossy = False
            obj.visible_transmission = False
            obj.visible_volume_scatter = False
            obj.visible_shadow = False

    # ---- EXT_lights_area
    lights = g.get("extensions", {}).get("EXT_lights_area", {}).get("lights", [])
    made = []
    for i, m in worlds.items():
        ext = g["nodes"][i].get("extensions", {}).get("EXT_lights_area")
        if not ext:
            continue
        L = lights[ext["light"]]
        kind = L.get("type", "rect")
        if kind not in AREA_SHAPES:
            raise ValueError("EXT_lights_area light of unknown type %r" % kind)
        size = float(L.get("size", 1.0))
        color = L.get("color", [1.0, 1.0, 1.0])
        nits = float(L.get("intensity", 1.0))
        ld = bpy.data.lights.new(L.get("name", "area") + "_blender", type="AREA")
        if kind == "disk":
            ld.shape = "DISK"
            ld.size = size
            area = math.pi * size * size / 4.0
        else:
            aspect = float(L.get("rect", {}).get("aspect", 1.0))
            ld.shape = "RECTANGLE"
            ld.size = size * aspect
            ld.size_y = size
            area = size * aspect * size
        ld.energy = 4.0 * nits * area
        ld.color = color[:3]
        ld.use_shadow = True
        if hasattr(ld, "cycles"):
            ld.cycles.max_bounces = 1024
        lo = bpy.data.objects.new(ld.name, ld)
        scene.collection.objects.link(lo)
        lo.matrix_world = to_blender(m)
        made.append({"node": g["nodes"][i].get("name"), "type": kind, "area": area,
                     "power_W": ld.energy, "dir_blender": list(lo.matrix_world.to_3x3() @ mathutils.Vector((0, 0, -1)))})

    # ---- environment
    world = bpy.data.worlds.new("penumbra_world")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    bg = nt.nodes["Background"]
    env = sf.get("environment")
    if env is None:
        env = {"uniform": [1.0, 1.0, 1.0]}  # penumbra-render's default: uniform radiance 1
    intensity = float(env.get("intensity", 1.0))
    if "file" in env:
        tex = nt.nodes.new("ShaderNodeTexEnvironment")
        tex.image = bpy.data.images.load(env["file"])
        tex.image.colorspace_settings.name = "Linear"
        tex.interpolation = "Linear"
        mapping = nt.nodes.new("ShaderNodeMapping")
        mapping.vector_type = "POINT"
        # Penumbra looks up directions turned by -rotation about glTF +Y = Blender +Z.
        mapping.inputs["Rotation"].default_value = (0.0, 0.0, -math.radians(float(env.get("rotation", 0.0))))
        coord = nt.nodes.new("ShaderNodeTexCoord")
        nt.links.new(coord.outputs["Generated"], mapping.inputs["Vector"])
        nt.links.new(mapping.outputs["Vector"], tex.inputs["Vector"])
        nt.links.new(tex.outputs["Color"], bg.inputs["Color"])
        bg.inputs["Strength"].default_value = intensity
    else:
        u = env.get("uniform", [1.0, 1.0, 1.0])
        bg.inputs["Color"].default_value = (u[0], u[1], u[2], 1.0)
        bg.inputs["Strength"].default_value = intensity
    if a.no_world:
        bg.inputs["Strength"].default_value = 0.0
    if sf.get("background", {}).get("show", True) is False:
        print("warning: background.show = false is not reproduced (the world stays visible)")

    # ---- colour management and output
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.render.threads_mode = "FIXED"
    scene.render.threads = a.threads
    scene.render.film_transparent = False
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_mode = "RGB"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"
    scene.render.filepath = os.path.abspath(a.out)
    scene.render.use_file_extension = False

    if a.engine == "cycles":
        scene.render.engine = "CYCLES"
        c = scene.cycles
        c.device = "CPU"
        c.samples = a.samples
        c.use_adaptive_sampling = False
        c.use_denoising = False
        c.pixel_filter_type = "BOX"
        c.filter_width = 1.0
        c.seed = a.seed
        # Light paths: defaults (12 bounces, indirect clamp 10, filter glossy 1) are kept
        # except the glossy filter, which blurs highlights a reference should keep sharp.
        c.blur_glossy = 0.0
        if a.no_clamp:
            c.sample_clamp_indirect = 0.0
            c.sample_clamp_direct = 0.0
        if a.bounces >= 0:
            # Every kind of bounce to N (Blender's defaults stop diffuse and glossy paths at 4);
            # transparency (alpha) is not a bounce.
            c.max_bounces = a.bounces
            c.diffuse_bounces = a.bounces
            c.glossy_bounces = a.bounces
            c.transmission_bounces = a.bounces
            c.volume_bounces = a.bounces
    else:
        scene.render.engine = "BLENDER_EEVEE"
        e = scene.eevee
        e.taa_render_samples = a.samples
        e.use_soft_shadows = True
        e.shadow_cube_size = "1024"
        e.shadow_cascade_size = "2048"
        e.use_gtao = True
        # Penumbra's occlusion distance; 0 or absent means automatic there: a quarter of the
        # scene's bounding-box diagonal (penumbra/settings.h, kAutoOcclusionFraction).
        d = float(sf.get("progressive", {}).get("occlusionDistance", 0.0))
        e.gtao_distance = d if d > 0 else 0.25 * scene_diagonal()
        e.use_ssr = True
        # Screen-space refraction for transmissive materials (gltf_brdf marks them).
        e.use_ssr_refraction = True
        scene.render.filter_size = 1.0

    t0 = time.time()
    bpy.ops.render.render(write_still=True)
    t1 = time.time()
    info = {"engine": a.engine, "samples": a.samples, "size": [w, h], "threads": a.threads,
            "render_seconds": round(t1 - t0, 3), "scene": os.path.abspath(a.scene),
            "camera_node": g["nodes"][cam_node].get("name"), "proxies_camera_only": nproxy,
            "lights": made, "blender": bpy.app.version_string, "material": a.material,
            "bounces": a.bounces, "clamp_indirect": None if a.engine != "cycles" else
            scene.cycles.sample_clamp_indirect,
            "materials_rebuilt": rebuilt}
    with open(os.path.splitext(os.path.abspath(a.out))[0] + ".json", "w") as f:
        json.dump(info, f, indent=1)
    print("PENUMBRA_REF", json.dumps(info))


main()
