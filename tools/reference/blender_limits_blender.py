"""What Blender 3.4 makes of minimal glTF files, one feature each (run by tools/blender-limits):

  blender -b --factory-startup --python-exit-code 1 \
      --python tools/reference/blender_limits_blender.py -- CASES.json RESULTS.json

CASES.json: {"cases": [{"name", "file", "plain" (the same file without the feature, or
null)}]}. For each case the file is imported with Blender's own glTF importer (as
tools/reference/fidelity_blender.py does) and what came in is described: the mesh objects and
their vertices after evaluation, each material's node types and every unlinked input value, the
images and whether they hold pixels. A case with a "plain" twin also says whether the two
imports are the same. RESULTS.json gets one object per case plus what this Blender's Cycles
offers at all ("nodes": the shader nodes and Principled BSDF inputs whose names mention thin
film, iridescence or sheen). Facts only: tools/blender-limits words the verdicts.
"""
import json
import sys
import traceback

import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Debian's Blender 3.4 glTF importer uses numpy.bool (removed in numpy 1.24)

import bpy


def value(v):
    """An input's default value as JSON (vectors and colours as lists, rounded)."""
    try:
        return [round(float(x), 4) for x in v]
    except TypeError:
        return round(float(v), 4) if isinstance(v, (int, float)) else str(v)


def describe_material(m):
    if not m.use_nodes:
        return {"name": m.name, "nodes": []}
    nodes = []
    for n in sorted(m.node_tree.nodes, key=lambda n: (n.bl_idname, n.name)):
        inputs = {}
        for s in n.inputs:
            if not s.is_linked and hasattr(s, "default_value"):
                inputs[s.name] = value(s.default_value)
        nodes.append({"type": n.bl_idname, "inputs": inputs})
    return {"name": m.name, "nodes": nodes}


def import_file(path):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=path)
    depsgraph = bpy.context.evaluated_depsgraph_get()
    meshes, vertices = 0, 0
    for ob in bpy.context.scene.objects:
        if ob.type != "MESH":
            continue
        meshes += 1
        vertices += len(ob.evaluated_get(depsgraph).data.vertices)
    images = []
    for im in bpy.data.images:
        if im.type != "IMAGE":
            continue
        im.update()
        images.append({"name": im.name, "file": bpy.path.basename(im.filepath),
                       "size": list(im.size), "has_data": bool(im.has_data)})
    return {"mesh_objects": meshes, "vertices": vertices,
            "materials": [describe_material(m) for m in bpy.data.materials],
            "images": images}


def cycles_offers():
    words = ("thin", "film", "irides", "sheen", "velvet")
    nodes = sorted(n for n in dir(bpy.types) if n.startswith("ShaderNode") and
                   any(w in n.lower() for w in words))
    bpy.ops.wm.read_factory_settings(use_empty=True)
    m = bpy.data.materials.new("probe")
    m.use_nodes = True
    p = next(n for n in m.node_tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
    principled = [s.name for s in p.inputs if any(w in s.name.lower() for w in words)]
    return {"blender": bpy.app.version_string, "shader_nodes": nodes,
            "principled_inputs": principled}


def main():
    argv = sys.argv[sys.argv.index("--") + 1:]
    cases = json.load(open(argv[0]))["cases"]
    out = {"cycles": cycles_offers(), "cases": []}
    for c in cases:
        r = {"name": c["name"]}
        try:
            r["import"] = import_file(c["file"])
            if c.get("plain"):
                plain = import_file(c["plain"])
                r["plain_import"] = plain
                r["same_as_plain"] = (plain["materials"] == r["import"]["materials"] and
                                      plain["mesh_objects"] == r["import"]["mesh_objects"])
        except Exception as e:  # the importer raises RuntimeError with its traceback as text
            r["error"] = str(e).strip().splitlines()[-1] if str(e).strip() else type(e).__name__
            traceback.print_exc()
        out["cases"].append(r)
    json.dump(out, open(argv[1], "w"), indent=1)


main()
