"""glTF's metallic-roughness BRDF as a Blender node tree, for the reference renders.

Blender 3.4's glTF importer maps every material to a Principled BSDF, whose diffuse lobe is
Disney's (retro-reflective at grazing angles, up to several times Lambert at the silhouette when
the light is behind the viewer) and is not weighted by the specular layer's Fresnel. glTF 2.0
(Appendix B of the specification) defines instead

    dielectric = fresnel_mix(ior 1.5, base = Lambert(baseColor), layer = GGX specular)
    metal      = GGX specular tinted by baseColor
    material   = mix(dielectric, metal, metallic) + emission

which is what Penumbra renders. replace_principled() rebuilds each imported material with that
model from Blender's Diffuse BSDF (roughness 0 = Lambert), Glossy BSDF (GGX, the same
perceptual roughness), Fresnel (IOR 1.5 at the shading normal: the closest node Blender offers
to glTF's per-microfacet Schlick term) and Mix Shader nodes, keeping every texture and normal
map link the importer made. Cycles and Eevee then render the same material model as Penumbra,
so the evaluation compares rendering algorithms, not BRDFs.
"""
import bpy


def _source(tree, socket):
    """The output socket linked into `socket`, or None."""
    for link in tree.links:
        if link.to_socket == socket:
            return link.from_socket
    return None


def _feed(tree, dst_socket, fallback_input):
    """Links what fed the Principled input into dst_socket, or copies its default value."""
    src = _source(tree, fallback_input)
    if src is not None:
        tree.links.new(src, dst_socket)
    else:
        value = fallback_input.default_value
        try:
            dst_socket.default_value = value
        except TypeError:  # colour <- float or the reverse
            dst_socket.default_value = (value, value, value, 1.0) if isinstance(value, float) else value[0]


def replace_principled(material):
    """Rebuilds one material; returns True when it had a Principled BSDF to replace."""
    if not material or not material.use_nodes:
        return False
    tree = material.node_tree
    bsdf = next((n for n in tree.nodes if n.type == "BSDF_PRINCIPLED"), None)
    if bsdf is None:
        return False
    out_socket = next((l.to_socket for l in tree.links if l.from_node == bsdf), None)
    if out_socket is None:
        return False
    N = tree.nodes
    inp = bsdf.inputs

    diffuse = N.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0  # Lambert
    _feed(tree, diffuse.inputs["Color"], inp["Base Color"])

    spec = N.new("ShaderNodeBsdfGlossy")
    spec.distribution = "GGX"
    spec.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
    _feed(tree, spec.inputs["Roughness"], inp["Roughness"])

    metal = N.new("ShaderNodeBsdfGlossy")
    metal.distribution = "GGX"
    _feed(tree, metal.inputs["Color"], inp["Base Color"])
    _feed(tree, metal.inputs["Roughness"], inp["Roughness"])

    fresnel = N.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = 1.5

    normal = _source(tree, inp["Normal"])
    if normal is not None:
        for node in (diffuse, spec, metal, fresnel):
            tree.links.new(normal, node.inputs["Normal"])

    dielectric = N.new("ShaderNodeMixShader")
    tree.links.new(fresnel.outputs["Fac"], dielectric.inputs["Fac"])
    tree.links.new(diffuse.outputs["BSDF"], dielectric.inputs[1])
    tree.links.new(spec.outputs["BSDF"], dielectric.inputs[2])

    by_metal = N.new("ShaderNodeMixShader")
    _feed(tree, by_metal.inputs["Fac"], inp["Metallic"])
    tree.links.new(dielectric.outputs["Shader"], by_metal.inputs[1])
    tree.links.new(metal.outputs["BSDF"], by_metal.inputs[2])
    result = by_metal.outputs["Shader"]

    # Emission (KHR_materials_emissive_strength lands in "Emission Strength").
    emission_linked = _source(tree, inp["Emission"]) is not None
    if emission_linked or any(c > 0.0 for c in inp["Emission"].default_value[:3]):
        emit = N.new("ShaderNodeEmission")
        _feed(tree, emit.inputs["Color"], inp["Emission"])
        if "Emission Strength" in inp:
            _feed(tree, emit.inputs["Strength"], inp["Emission Strength"])
        add = N.new("ShaderNodeAddShader")
        tree.links.new(result, add.inputs[0])
        tree.links.new(emit.outputs["Emission"], add.inputs[1])
        result = add.outputs["Shader"]

    # Alpha (MASK and BLEND): a mix with a transparent BSDF, as the importer's Principled does.
    if _source(tree, inp["Alpha"]) is not None or inp["Alpha"].default_value < 1.0:
        clear = N.new("ShaderNodeBsdfTransparent")
        cut = N.new("ShaderNodeMixShader")
        _feed(tree, cut.inputs["Fac"], inp["Alpha"])
        tree.links.new(clear.outputs["BSDF"], cut.inputs[1])
        tree.links.new(result, cut.inputs[2])
        result = cut.outputs["Shader"]

    tree.links.new(result, out_socket)
    N.remove(bsdf)
    return True


def use_gltf_brdf():
    """Replaces the Principled BSDF in every material; returns how many were rebuilt."""
    return sum(1 for m in bpy.data.materials if replace_principled(m))
