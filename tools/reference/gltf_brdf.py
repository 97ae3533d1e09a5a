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

The material extensions are rebuilt from the glTF file's own values (use_gltf_brdf(materials)):
  KHR_materials_ior           the Fresnel node's IOR
  KHR_materials_transmission  the dielectric base = mix(Lambert, BTDF, transmission): with a
                              KHR_materials_volume thickness a Refraction BSDF (GGX, the IOR; the
                              mesh is a closed solid for Cycles) and a Volume Absorption with
                              sigma = -ln(attenuationColor) / attenuationDistance; thin-walled a
                              Transparent BSDF tinted by the base colour (Blender has no BSDF for
                              glTF's rough thin-walled lobe, the reflection lobe mirrored through
                              the surface: a rough thin-walled material is rendered smooth, with
                              a warning)
  KHR_materials_clearcoat     mix(material, GGX coat, clearcoat x Fresnel(1.5)) at the geometric
                              normal
  KHR_materials_sheen         a Velvet BSDF of the sheen colour and roughness added over the base,
                              which is scaled by 1 - max(sheenColor) x 0.25. Blender 3.4 has no
                              Charlie sheen (the Velvet lobe is Ashikhmin's): the sheen reference
                              is approximate, and the evaluation says so.
"""
import math

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


def _math(tree, op, a, b):
    """A Math node computing op(a, b); a and b are sockets or numbers. Returns its output."""
    node = tree.nodes.new("ShaderNodeMath")
    node.operation = op
    for i, v in enumerate((a, b)):
        if isinstance(v, (int, float)):
            node.inputs[i].default_value = v
        else:
            tree.links.new(v, node.inputs[i])
    return node.outputs["Value"]


def replace_principled(material, ext=None):
    """Rebuilds one material; returns True when it had a Principled BSDF to replace. `ext`: the
    glTF material's "extensions" object."""
    ext = ext or {}
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

    ior = float(ext.get("KHR_materials_ior", {}).get("ior", 1.5))
    fresnel = N.new("ShaderNodeFresnel")
    fresnel.inputs["IOR"].default_value = max(ior, 1.0) if ior != 0.0 else 1000.0

    normal = _source(tree, inp["Normal"])
    if normal is not None:
        for node in (diffuse, spec, metal, fresnel):
            tree.links.new(normal, node.inputs["Normal"])

    base = diffuse.outputs["BSDF"]
    transmission = float(ext.get("KHR_materials_transmission", {}).get("transmissionFactor", 0.0))
    volume = ext.get("KHR_materials_volume", {})
    thickness = float(volume.get("thicknessFactor", 0.0))
    if transmission > 0.0:
        rough = inp["Roughness"].default_value
        if thickness > 0.0:
            btdf = N.new("ShaderNodeBsdfRefraction")
            btdf.distribution = "GGX"
            btdf.inputs["IOR"].default_value = max(ior, 1.0)
            _feed(tree, btdf.inputs["Roughness"], inp["Roughness"])
            dist = float(volume.get("attenuationDistance", 0.0))
            if dist > 0.0:
                colour = volume.get("attenuationColor", [1.0, 1.0, 1.0])
                sigma = [-math.log(max(c, 1e-6)) / dist for c in colour]
                density = max(max(sigma), 1e-6)
                absorb = N.new("ShaderNodeVolumeAbsorption")
                # Cycles: sigma_a = density x (1 - colour).
                absorb.inputs["Color"].default_value = tuple(1.0 - x / density for x in sigma) + (1.0,)
                absorb.inputs["Density"].default_value = density
                out_node = next(l.to_node for l in tree.links if l.from_node == bsdf)
                tree.links.new(absorb.outputs["Volume"], out_node.inputs["Volume"])
        else:
            if rough >= 0.05 or _source(tree, inp["Roughness"]) is not None:
                print("warning: %s: rough thin-walled transmission is rendered smooth (Blender has "
                      "no BSDF for glTF's mirrored reflection lobe)" % material.name)
            btdf = N.new("ShaderNodeBsdfTransparent")
        _feed(tree, btdf.inputs["Color"], inp["Base Color"])
        if normal is not None and "Normal" in btdf.inputs:
            tree.links.new(normal, btdf.inputs["Normal"])
        through = N.new("ShaderNodeMixShader")
        through.inputs["Fac"].default_value = transmission
        tree.links.new(diffuse.outputs["BSDF"], through.inputs[1])
        tree.links.new(btdf.outputs["BSDF"], through.inputs[2])
        base = through.outputs["Shader"]
        material.use_screen_refraction = True  # Eevee's refraction
        material.refraction_depth = thickness
        material.blend_method = "BLEND"
        material.show_transparent_back = False

    sheen = ext.get("KHR_materials_sheen")
    if sheen is not None:
        colour = sheen.get("sheenColorFactor", [0.0, 0.0, 0.0])
        if max(colour) > 0.0:
            velvet = N.new("ShaderNodeBsdfVelvet")
            velvet.inputs["Color"].default_value = tuple(colour) + (1.0,)
            velvet.inputs["Sigma"].default_value = max(float(sheen.get("sheenRoughnessFactor", 0.0)), 0.05)
            if normal is not None:
                tree.links.new(normal, velvet.inputs["Normal"])
            scaled = N.new("ShaderNodeMixShader")  # base x (1 - max(colour) 0.25)
            scaled.inputs["Fac"].default_value = max(colour) * 0.25
            tree.links.new(base, scaled.inputs[1])
            nothing = N.new("ShaderNodeEmission")
            nothing.inputs["Strength"].default_value = 0.0
            tree.links.new(nothing.outputs["Emission"], scaled.inputs[2])
            layered = N.new("ShaderNodeAddShader")
            tree.links.new(scaled.outputs["Shader"], layered.inputs[0])
            tree.links.new(velvet.outputs["BSDF"], layered.inputs[1])
            base = layered.outputs["Shader"]

    dielectric = N.new("ShaderNodeMixShader")
    tree.links.new(fresnel.outputs["Fac"], dielectric.inputs["Fac"])
    tree.links.new(base, dielectric.inputs[1])
    tree.links.new(spec.outputs["BSDF"], dielectric.inputs[2])

    by_metal = N.new("ShaderNodeMixShader")
    _feed(tree, by_metal.inputs["Fac"], inp["Metallic"])
    tree.links.new(dielectric.outputs["Shader"], by_metal.inputs[1])
    tree.links.new(metal.outputs["BSDF"], by_metal.inputs[2])
    result = by_metal.outputs["Shader"]

    coat = ext.get("KHR_materials_clearcoat")
    if coat is not None and float(coat.get("clearcoatFactor", 0.0)) > 0.0:
        glossy = N.new("ShaderNodeBsdfGlossy")
        glossy.distribution = "GGX"
        glossy.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        glossy.inputs["Roughness"].default_value = float(coat.get("clearcoatRoughnessFactor", 0.0))
        coat_fresnel = N.new("ShaderNodeFresnel")  # the geometric normal: no normal map link
        coat_fresnel.inputs["IOR"].default_value = 1.5
        coated = N.new("ShaderNodeMixShader")
        tree.links.new(_math(tree, "MULTIPLY", coat_fresnel.outputs["Fac"],
                             float(coat["clearcoatFactor"])), coated.inputs["Fac"])
        tree.links.new(result, coated.inputs[1])
        tree.links.new(glossy.outputs["BSDF"], coated.inputs[2])
        result = coated.outputs["Shader"]

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


def use_gltf_brdf(gltf_materials=()):
    """Replaces the Principled BSDF in every material (with the extensions of the glTF material
    of the same name); returns how many were rebuilt."""
    by_name = {m.get("name"): m.get("extensions", {}) for m in gltf_materials if m.get("name")}
    return sum(1 for m in bpy.data.materials if replace_principled(m, by_name.get(m.name)))
