"""Cycles renders of many glTF models in one Blender process, from Penumbra's own cameras, and
their comparison with Penumbra's EXRs (run by tools/fidelity):

  blender -b --factory-startup --python-exit-code 1 \
      --python tools/reference/fidelity_blender.py -- JOBS.json RESULTS.jsonl

JOBS.json: {"env": panorama, "size": [w, h], "samples": N, "threads": T, "cell": [cw, ch],
"models": [{"name", "file", "camera" (penumbra-render's results "camera"), "cycles_exr",
"penumbra_exr" (or null), "cells" (a path prefix for the cell PNGs)}]}. One JSON line per model
is appended to RESULTS.jsonl as it finishes, so tools/fidelity can restart Blender after a
crash on the models still to do.

Set-up as tools/reference/blender_scene.py does it, so that Cycles sees what Penumbra sees:
the importer's scene with glTF's BRDF rebuilt from nodes (gltf_brdf.py), the panorama as the
world (Linear, Generated coordinates, strength 1), Standard view transform, box filter 1 px,
no denoising, linear EXR. Differences from it, each to render what glTF (and Penumbra) does:
  * the camera is the one penumbra-render reports (the file's first camera or its automatic
    framing, with its aspect fit);
  * KHR_lights_punctual lights come in with the "Unitless" lighting mode (Penumbra reads
    candela and lux as radiometric W/sr and W/m^2, which is what that mode gives Cycles);
  * animation is cleared (skins and morph targets at rest), only the default scene's nodes
    stay, primitives without a material get glTF's default one, single-sided materials are
    culled from behind for camera rays, and the metal lobes scatter multiply (see
    multiscatter(); the job's "multiscatter": false keeps plain GGX).

The reference is two renders of N/2 samples with seeds 1 and 2, averaged: half their RMS
difference estimates the averaged image's own noise (the floor under any renderer's RMSE).
"""
import json
import math
import os
import re
import sys
import time
import traceback

import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian's Blender 3.4 glTF importer uses numpy.bool (removed in numpy 1.24)
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from image_metrics import luma, pbr_neutral, ssim  # noqa: E402 (numpy only; shared with evaluate.py)

import bpy
import mathutils

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import fidelity_png  # noqa: E402
from gltf_brdf import use_gltf_brdf  # noqa: E402

# glTF (x, y, z) -> Blender (x, -z, y), as in blender_scene.py.
GLTF_TO_BLENDER = mathutils.Matrix(((1, 0, 0, 0), (0, 0, -1, 0), (0, 1, 0, 0), (0, 0, 0, 1)))
DIFF_SCALE = 0.25  # display-space |difference| shown as full scale in the difference cells


# ---------------------------------------------------------------- images and metrics
def read_exr(path):
    """Linear RGB float64 (rows top to bottom) of an EXR, through Blender's image loader."""
    img = bpy.data.images.load(path, check_existing=False)
    img.colorspace_settings.name = "Non-Color"  # no view transform: the stored values
    w, h = img.size
    a = np.empty(w * h * 4, dtype=np.float32)
    img.pixels.foreach_get(a)
    bpy.data.images.remove(img)
    return a.reshape(h, w, 4)[::-1, :, :3].astype(np.float64)


def write_exr(path, rgb):
    h, w = rgb.shape[:2]
    img = bpy.data.images.new("fidelity_out", w, h, alpha=True, float_buffer=True)
    img.colorspace_settings.name = "Non-Color"
    a = np.ones((h, w, 4), dtype=np.float32)
    a[..., :3] = rgb[::-1]
    img.pixels.foreach_set(a.ravel())
    img.filepath_raw = path
    img.file_format = "OPEN_EXR"
    img.save()
    bpy.data.images.remove(img)


def display(lin, exposure=0.0):
    x = np.clip(pbr_neutral(lin * 2.0 ** exposure), 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def to_cell(rgb01, cw, ch):
    """Area-average down to the cell size (nearest up), as 8-bit RGB bytes."""
    h, w = rgb01.shape[:2]
    ys = (np.arange(ch + 1) * h) // ch
    xs = (np.arange(cw + 1) * w) // cw
    if h >= ch and w >= cw:
        c = np.add.reduceat(np.add.reduceat(rgb01, ys[:-1], axis=0), xs[:-1], axis=1)
        c /= np.outer(np.diff(ys), np.diff(xs))[..., None]
    else:
        c = rgb01[np.minimum(ys[:-1], h - 1)][:, np.minimum(xs[:-1], w - 1)]
    return (np.clip(c, 0, 1) * 255 + 0.5).astype(np.uint8).tobytes()


def heat(x):
    """False colour for 0..1: black, red, yellow, white."""
    x = np.clip(x, 0.0, 1.0)[..., None]
    return np.clip(np.concatenate([3 * x, 3 * x - 1, 3 * x - 2], axis=-1), 0.0, 1.0)


def compare(pen, ref, noise, cells, cw, ch):
    """Metrics of Penumbra's image against the reference, and the Cycles and difference cells."""
    dp, dr = display(pen), display(ref)
    out = {"rmse": float(np.sqrt(np.mean((pen - ref) ** 2))),
           "ssim": ssim(luma(dp), luma(dr)),
           "mae_tm": float(np.mean(np.abs(dp - dr))),
           "mean_ratio": float(luma(pen).mean() / max(luma(ref).mean(), 1e-9)),
           "cycles_noise_rmse": noise}
    diff = luma(np.abs(dp - dr)) / DIFF_SCALE
    fidelity_png.write_png(cells + "diff.png", cw, ch, to_cell(heat(diff), cw, ch))
    return out


# ---------------------------------------------------------------- scene set-up
def clear_animation(g):
    """Penumbra renders skins and morph targets at rest (the nodes' own transforms, the meshes'
    default weights). The importer makes the first animation active and writes its first
    frame into the pose bones and shape keys: drop the actions, put every pose bone back to its
    edit bone (imported with guess_original_bind_pose off, the edit bones are the nodes' own
    transforms), and every shape key back to its mesh's default weight."""
    for ob in bpy.data.objects:
        ob.animation_data_clear()
        if ob.type == "ARMATURE":
            for pb in ob.pose.bones:
                pb.location = (0.0, 0.0, 0.0)
                pb.rotation_mode = "QUATERNION"
                pb.rotation_quaternion = (1.0, 0.0, 0.0, 0.0)
                pb.scale = (1.0, 1.0, 1.0)
    weights = {}
    for mesh in g.get("meshes", []):
        weights.setdefault(mesh.get("name"), mesh.get("weights", []))
    for key in bpy.data.shape_keys:
        key.animation_data_clear()
        w = weights.get(key.user.name.split(".")[0] if key.user else None, [])
        for i, block in enumerate(key.key_blocks[1:]):
            block.value = w[i] if i < len(w) else 0.0


def keep_default_scene(g):
    """The importer makes objects for the nodes of every scene; Penumbra renders the default
    scene's: remove the objects of nodes no scene root of it reaches (by the importer's names:
    the node's name, else its mesh's, else Node_<index>)."""
    scenes = g.get("scenes", [])
    if len(scenes) < 2:
        return 0
    nodes, reached = g.get("nodes", []), set()
    stack = list(scenes[g.get("scene", 0)].get("nodes", []))
    while stack:
        i = stack.pop()
        if i not in reached:
            reached.add(i)
            stack += nodes[i].get("children", [])
    meshes = g.get("meshes", [])

    def name(i):  # an unnamed node with a mesh takes the mesh's name, as the importer does
        n = nodes[i]
        if n.get("name"):
            return n["name"]
        if "mesh" in n and n["mesh"] < len(meshes):
            return meshes[n["mesh"]].get("name") or "Mesh_%d" % n["mesh"]
        return "Node_%d" % i
    keep = {name(i) for i in reached}
    drop = {name(i) for i in range(len(nodes)) if i not in reached} - keep
    gone = [ob for ob in bpy.data.objects if ob.name in drop]
    for ob in gone:
        bpy.data.objects.remove(ob)
    return len(gone)


def default_material():
    """glTF's default material (base colour 1, metallic 1, roughness 1; times COLOR_0 when the
    mesh has one) where the importer left a primitive without one (Cycles would shade it grey
    diffuse), rebuilt as glTF's BRDF like the file's own materials."""
    made = {}
    for ob in bpy.data.objects:
        if ob.type != "MESH":
            continue
        colour = "Col" in ob.data.color_attributes
        slots = [i for i, m in enumerate(ob.data.materials) if m is None]
        if not slots and len(ob.data.materials) > 0:
            continue
        if colour not in made:
            mat = bpy.data.materials.new("gltf_default" + ("_col" if colour else ""))
            mat.use_nodes = True
            mat.use_backface_culling = True  # glTF's default material is single-sided
            bsdf = mat.node_tree.nodes["Principled BSDF"]
            bsdf.inputs["Base Color"].default_value = (1.0, 1.0, 1.0, 1.0)
            bsdf.inputs["Metallic"].default_value = 1.0
            bsdf.inputs["Roughness"].default_value = 1.0
            if colour:
                vc = mat.node_tree.nodes.new("ShaderNodeVertexColor")
                vc.layer_name = "Col"
                mat.node_tree.links.new(vc.outputs["Color"], bsdf.inputs["Base Color"])
            made[colour] = mat
        if slots:
            for i in slots:
                ob.data.materials[i] = made[colour]
        else:
            ob.data.materials.append(made[colour])
    return len(made)


def multiscatter():
    """Cycles' multiple-scattering GGX for the metal lobes gltf_brdf.py builds. Penumbra
    compensates the energy single-scattering GGX loses by 1 + F0 (1 / E_ss - 1) (docs/ibl.md):
    in full for a metal (F0 = the base colour), next to nothing for a dielectric (F0 = 0.04).
    So the metal lobes (a Glossy or Anisotropic BSDF whose mix is not weighted by a Fresnel or
    Math node: the dielectric's specular layer and the clearcoat are) scatter multiply here,
    and the rest stays single-scattering GGX, as in tools/evaluate's references."""
    n = 0
    for mat in bpy.data.materials:
        if not mat.use_nodes:
            continue
        links = mat.node_tree.links
        for node in mat.node_tree.nodes:
            if node.type not in ("BSDF_GLOSSY", "BSDF_ANISOTROPIC") or node.distribution != "GGX":
                continue
            weighted = False
            for l in links:
                if l.from_node == node and l.to_node.type == "MIX_SHADER":
                    fac = l.to_node.inputs["Fac"]
                    weighted |= any(f.to_socket == fac and f.from_node.type in ("FRESNEL", "MATH")
                                    for f in links)
            if not weighted:
                node.distribution = "MULTI_GGX"
                n += 1
    return n


def cull_back_faces():
    """glTF culls the back faces of single-sided materials (the importer marks them
    use_backface_culling, which only Eevee and the viewport obey); Cycles draws them. For
    camera rays only (shadows and bounces still see both sides, as Penumbra's shadow maps and
    refraction do), such a material turns transparent where it is seen from behind."""
    n = 0
    for mat in bpy.data.materials:
        if not mat.use_backface_culling or not mat.use_nodes:
            continue
        nt = mat.node_tree
        out = next((nd for nd in nt.nodes if nd.type == "OUTPUT_MATERIAL" and nd.is_active_output),
                   None)
        link = next((l for l in nt.links if out and l.to_socket == out.inputs["Surface"]), None)
        if link is None:
            continue
        geo, path = nt.nodes.new("ShaderNodeNewGeometry"), nt.nodes.new("ShaderNodeLightPath")
        both = nt.nodes.new("ShaderNodeMath")
        both.operation = "MULTIPLY"
        nt.links.new(geo.outputs["Backfacing"], both.inputs[0])
        nt.links.new(path.outputs["Is Camera Ray"], both.inputs[1])
        mix, clear = nt.nodes.new("ShaderNodeMixShader"), nt.nodes.new("ShaderNodeBsdfTransparent")
        src = link.from_socket
        nt.links.new(both.outputs["Value"], mix.inputs["Fac"])
        nt.links.new(src, mix.inputs[1])
        nt.links.new(clear.outputs["BSDF"], mix.inputs[2])
        nt.links.new(mix.outputs["Shader"], out.inputs["Surface"])
        n += 1
    return n


def gltf_materials(g):
    """The file's materials under the names the importer gave them (an unnamed one is
    Material_<index>; a copy made for COLOR_0 gets a .001 suffix), so that gltf_brdf.py, which
    matches by name, finds every material's extensions."""
    mats = []
    for i, m in enumerate(g.get("materials", [])):
        mats.append(dict(m, name=m.get("name") or "Material_%d" % i))
    by_name = {m["name"]: m for m in mats}
    for bm in bpy.data.materials:
        base = re.sub(r"\.\d{3}$", "", bm.name)
        if bm.name not in by_name and base in by_name:
            mats.append(dict(by_name[base], name=bm.name))
    return mats


# Extension textures gltf_brdf.py rebuilds (from files beside a .gltf, or a .glb's images
# written out by glb_images); the others are left out of the reference.
REBUILT_TEXTURES = {"anisotropyTexture", "diffuseTransmissionTexture",
                    "diffuseTransmissionColorTexture", "clearcoatNormalTexture",
                    "specularTexture", "specularColorTexture"}


def glb_images(g, path, out_dir):
    """A copy of a .glb's JSON whose images are files in out_dir (their bytes from the binary
    chunk), so that gltf_brdf.py finds extension textures as it does beside a .gltf."""
    import struct
    with open(path, "rb") as f:
        data = f.read()
    clen = struct.unpack_from("<I", data, 12)[0]
    start = 20 + clen
    binary = data[start + 8:start + 8 + struct.unpack_from("<I", data, start)[0]] \
        if len(data) > start + 8 else b""
    g = dict(g)
    images = []
    for i, im in enumerate(g.get("images", [])):
        im = dict(im)
        view = g.get("bufferViews", [])[im["bufferView"]] if "bufferView" in im else None
        ext = {"image/png": ".png", "image/jpeg": ".jpg"}.get(im.get("mimeType"))
        # (Blender reads PNG and JPEG; a KTX2 image stays out, as beside a .gltf.)
        if view is not None and "uri" not in im and ext is not None:
            name = "image%d%s" % (i, ext)
            off = view.get("byteOffset", 0)
            with open(os.path.join(out_dir, name), "wb") as f:
                f.write(binary[off:off + view["byteLength"]])
            im["uri"] = name
        images.append(im)
    g["images"] = images
    return g


def reference_limits(g, path):
    """What of this file's materials the reference leaves out, in words."""
    left = set()
    for m in g.get("materials", []):
        for ext in m.get("extensions", {}).values():
            for key in ext:
                if key.endswith("Texture") and key not in REBUILT_TEXTURES:
                    left.add(key)
    out = ["extension textures not in the reference: " + ", ".join(sorted(left))] if left else []
    # A morph target without NORMAL leaves the normals as they are (glTF, and Penumbra);
    # Blender shades the shape key with normals recomputed from the moved positions.
    for mesh in g.get("meshes", []):
        if any(w for w in mesh.get("weights", [])) and any(
                "NORMAL" in p.get("attributes", {}) and any("NORMAL" not in t for t in p.get("targets", []))
                for p in mesh.get("primitives", [])):
            out.append("a morphed mesh: Blender recomputes its normals (glTF keeps them)")
            break
    return out


def bounds():
    lo, hi = [float("inf")] * 3, [float("-inf")] * 3
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH":
            continue
        for corner in ob.bound_box:
            w = ob.matrix_world @ mathutils.Vector(corner)
            for k in range(3):
                lo[k], hi[k] = min(lo[k], w[k]), max(hi[k], w[k])
    if lo[0] > hi[0]:
        return mathutils.Vector((0, 0, 0)), 1.0
    centre = mathutils.Vector([(a + b) / 2 for a, b in zip(lo, hi)])
    return centre, max(sum((b - a) ** 2 for a, b in zip(lo, hi)) ** 0.5, 1e-6)


def make_camera(scene, cam, w, h):
    """Penumbra's camera (penumbra-render's results "camera") as a Blender camera. The image
    keeps the vertical extent unless it is narrower than the camera's aspect, when it keeps
    the horizontal one (renderer/src/passes/camera_math.cpp): both become a vertical fit here."""
    m = cam["world"]  # column-major camera-to-world, glTF frame
    world = mathutils.Matrix([[m[c * 4 + r] for c in range(4)] for r in range(4)])
    for c in range(3):  # only the rigid part defines the view, as in camera_math.cpp
        col = world.col[c].xyz
        if col.length > 0:
            world.col[c].xyz = col / col.length
    aspect = w / h
    fit = cam["aspect"] / aspect if cam["aspect"] > 0 and aspect < cam["aspect"] else 1.0
    data = bpy.data.cameras.new("penumbra_camera")
    data.sensor_fit = "VERTICAL"
    data.sensor_height = 24.0
    if cam["orthographic"]:
        data.type = "ORTHO"
        data.ortho_scale = 2.0 * cam["ymag"] * fit
    else:
        data.angle_y = 2.0 * math.atan(math.tan(0.5 * cam["yfov"]) * fit)
    ob = bpy.data.objects.new("penumbra_camera", data)
    scene.collection.objects.link(ob)
    ob.matrix_world = GLTF_TO_BLENDER @ world
    # Clip planes from the scene's size and distance (the results carry no znear or zfar).
    centre, diag = bounds()
    dist = (ob.matrix_world.translation - centre).length
    data.clip_start = max(1e-5, 1e-3 * min(dist, diag))
    data.clip_end = 10.0 * (dist + diag)
    scene.camera = ob


def make_world(scene, env):
    """The panorama exactly as blender_scene.py sets it (its convention is Penumbra's)."""
    world = bpy.data.worlds.new("penumbra_world")
    scene.world = world
    world.use_nodes = True
    nt = world.node_tree
    if env == "none":  # the scene's lights alone (penumbra-render --env none)
        nt.nodes["Background"].inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        nt.nodes["Background"].inputs["Strength"].default_value = 0.0
        return
    tex = nt.nodes.new("ShaderNodeTexEnvironment")
    tex.image = bpy.data.images.load(env)
    tex.image.colorspace_settings.name = "Linear"
    tex.interpolation = "Linear"
    coord = nt.nodes.new("ShaderNodeTexCoord")
    nt.links.new(coord.outputs["Generated"], tex.inputs["Vector"])
    nt.links.new(tex.outputs["Color"], nt.nodes["Background"].inputs["Color"])
    nt.nodes["Background"].inputs["Strength"].default_value = 1.0


def set_output(scene, job):
    w, h = job["size"]
    r = scene.render
    r.resolution_x, r.resolution_y, r.resolution_percentage = w, h, 100
    r.pixel_aspect_x = r.pixel_aspect_y = 1.0
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    r.threads_mode = "FIXED"
    r.threads = job["threads"]
    r.film_transparent = False
    r.use_persistent_data = True  # the second seed reuses the first render's BVH
    s = r.image_settings
    s.file_format, s.color_mode, s.color_depth, s.exr_codec = "OPEN_EXR", "RGB", "32", "ZIP"
    r.use_file_extension = False
    r.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.samples = max(1, job["samples"] // 2)
    c.use_adaptive_sampling = False
    c.use_denoising = False  # Debian's build has no OpenImageDenoise
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.blur_glossy = 0.0  # as blender_scene.py: a reference keeps highlights sharp


def read_gltf_json(path):
    if path.lower().endswith(".glb"):
        import struct
        with open(path, "rb") as f:
            data = f.read()
        clen = struct.unpack_from("<I", data, 12)[0]
        return json.loads(data[20:20 + clen].decode("utf-8"))
    with open(path, encoding="utf-8") as f:
        return json.load(f)


# ---------------------------------------------------------------- one model
def render_model(job, m):
    res = {"name": m["name"], "status": "ok", "warnings": []}
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    g = read_gltf_json(m["file"])
    if "KHR_draco_mesh_compression" in g.get("extensionsUsed", []):
        from io_scene_gltf2.io.com import gltf2_io_draco_compression_extension as draco
        if not draco.dll_exists(quiet=True):
            res.update(status="import_failed", reason="Draco: this Blender has no Draco decoder "
                       "(libextern_draco.so; Debian's 3.4 ships none)")
            return res
    t0 = time.time()
    try:
        bpy.ops.import_scene.gltf(filepath=m["file"], convert_lighting_mode="COMPAT",
                                  guess_original_bind_pose=False)
    except Exception as e:  # the importer raises RuntimeError with its traceback as text
        found = re.findall(r"^\s*(\w+(?:Error|Exception): .*)$", str(e), re.M)
        res.update(status="import_failed", reason=found[-1] if found else type(e).__name__)
        return res
    res["import_seconds"] = round(time.time() - t0, 3)
    clear_animation(g)
    res["other_scenes_removed"] = keep_default_scene(g)
    default_material()  # before use_gltf_brdf, which rebuilds it too
    base_dir, with_images = os.path.dirname(os.path.abspath(m["file"])), g
    if m["file"].lower().endswith(".glb"):
        import tempfile
        base_dir = tempfile.mkdtemp(prefix="fidelity_glb_")
        with_images = glb_images(g, m["file"], base_dir)
    res["materials_rebuilt"] = use_gltf_brdf(gltf_materials(g), with_images, base_dir)
    res["limits"] = reference_limits(g, m["file"])
    res["culled_materials"] = cull_back_faces()
    if job.get("multiscatter", True):
        res["multiscatter_lobes"] = multiscatter()
    for ob in list(scene.objects):  # the file's cameras: Penumbra's is added below
        if ob.type == "CAMERA":
            bpy.data.objects.remove(ob)
    for ob in scene.objects:
        if ob.type == "LIGHT" and ob.data.type == "SUN":
            ob.data.angle = math.radians(0.53)  # Penumbra's directionalAngle default
    w, h = job["size"]
    make_camera(scene, m["camera"], w, h)
    make_world(scene, job["env"])
    set_output(scene, job)
    halves, seconds = [], 0.0
    for seed in (1, 2):
        scene.cycles.seed = seed
        scene.render.filepath = m["cycles_exr"] + ".seed%d.exr" % seed
        t0 = time.time()
        bpy.ops.render.render(write_still=True)
        seconds += time.time() - t0
        halves.append(read_exr(scene.render.filepath))
        os.remove(scene.render.filepath)
    ref = 0.5 * (halves[0] + halves[1])
    write_exr(m["cycles_exr"], ref)
    res["cycles_seconds"] = round(seconds, 3)
    res["cycles_samples"] = 2 * scene.cycles.samples
    noise = float(np.sqrt(np.mean((halves[0] - halves[1]) ** 2)) / 2.0)
    cw, ch = job["cell"]
    fidelity_png.write_png(m["cells"] + "cycles.png", cw, ch, to_cell(display(ref), cw, ch))
    # The displayed reference at full size, beside Penumbra's PNG, for a closer look.
    fidelity_png.write_png(m["cells"] + "full.png", w, h, to_cell(display(ref), w, h))
    pen_exr = m.get("penumbra_exr")
    if pen_exr and os.path.exists(pen_exr):
        pen = read_exr(pen_exr)
        if pen.shape != ref.shape:
            res["warnings"].append("size mismatch %s vs %s" % (pen.shape, ref.shape))
        else:
            res.update(compare(pen, ref, noise, m["cells"], cw, ch))
    else:
        res["cycles_noise_rmse"] = noise
    return res


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    with open(argv[0], encoding="utf-8") as f:
        job = json.load(f)
    out = open(argv[1], "a", encoding="utf-8")
    for m in job["models"]:
        print("FIDELITY model %s" % m["name"], flush=True)
        try:
            res = render_model(job, m)
        except Exception:
            res = {"name": m["name"], "status": "failed",
                   "reason": traceback.format_exc().strip().splitlines()[-1]}
        res["blender"] = bpy.app.version_string
        out.write(json.dumps(res) + "\n")
        out.flush()
        print("FIDELITY done %s" % json.dumps(res), flush=True)
    out.close()


main()
