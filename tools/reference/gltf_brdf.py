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
  KHR_materials_clearcoat     mix(material, GGX coat, clearcoat x Fresnel(1.5)) at the coat's own
                              normal map (clearcoatNormalTexture, a Normal Map node of its
                              scale), else the geometric normal
  KHR_materials_specular      the dielectric's Fresnel scaled by specularFactor (x the texture's
                              .a) and its specular lobe tinted by specularColorFactor (x the
                              texture's sRGB .rgb), capped at 1 / F0 so that the tinted F0 is
                              glTF's min(F0 x colour, 1); glTF's F90 stays untinted, this one
                              is tinted (a difference at grazing angles only)
  KHR_materials_sheen         a Velvet BSDF of the sheen colour and roughness added over the base,
                              which is scaled by 1 - max(sheenColor) x 0.25. Blender 3.4 has no
                              Charlie sheen (the Velvet lobe is Ashikhmin's): the sheen reference
                              is approximate, and the evaluation says so.
  KHR_materials_diffuse_transmission  the diffuse base = mix(Lambert(baseColor),
                              Translucent(diffuseTransmissionColor), diffuseTransmission), each
                              factor times its texture (.a strength, .rgb sRGB colour)
  KHR_materials_anisotropy    the specular and metal lobes become Anisotropic BSDFs (GGX) on the
                              UV map's tangent, with Cycles' (roughness, anisotropy) solved for
                              glTF's alpha_t = mix(alpha, 1, strength^2) along the tangent and
                              alpha_b = alpha across it; the texture's .b scales the strength
                              (its .rg direction and the rotation are taken as the tangent: a
                              warning names a material whose rotation is not 0)
  KHR_materials_iridescence, KHR_materials_dispersion: Blender 3.4 has neither a thin film nor
                              dispersion: rendered without (a warning names the material).
"""
import math
import os

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


def _texture(tree, textures, info, colour):
    """An Image Texture node for a glTF textureInfo (`textures`: index -> image file path), on
    the first UV map; None when the file is unknown."""
    path = textures.get(info.get("index")) if info else None
    if not path:
        return None
    node = tree.nodes.new("ShaderNodeTexImage")
    node.image = bpy.data.images.load(path, check_existing=True)
    node.image.colorspace_settings.name = "sRGB" if colour else "Non-Color"
    return node


MIN_ALPHA = 0.045 * 0.045  # Penumbra's smallest GGX alpha (MIN_PERCEPTUAL_ROUGHNESS squared)


def _scaled(tree, factor, tex_socket):
    """factor x texture socket (a number when there is no texture)."""
    return factor if tex_socket is None else _math(tree, "MULTIPLY", tex_socket, factor)


def _anisotropic(tree, aniso, textures, alpha_socket):
    """An Anisotropic BSDF (GGX, on the UV map's tangent) with glTF's alpha_t / alpha_b for
    alpha (a socket or number); its Color and Normal are still to be fed."""
    node = tree.nodes.new("ShaderNodeBsdfAnisotropic")
    node.distribution = "GGX"
    tangent = tree.nodes.new("ShaderNodeTangent")
    tangent.direction_type = "UV_MAP"
    tree.links.new(tangent.outputs["Tangent"], node.inputs["Tangent"])
    strength = float(aniso.get("anisotropyStrength", 0.0))
    tex = _texture(tree, textures, aniso.get("anisotropyTexture"), False)
    b = None
    if tex is not None:
        sep = tree.nodes.new("ShaderNodeSeparateRGB")
        tree.links.new(tex.outputs["Color"], sep.inputs["Image"])
        b = sep.outputs["B"]
    s = _scaled(tree, strength, b)
    # alpha_t = a + (1 - a) s^2, alpha_b = a; Cycles: alpha_x = R / (1 + k), alpha_y = R (1 + k)
    # for k < 0 with R = roughness^2 (x along the tangent): R = sqrt(at ab), 1 + k = sqrt(ab / at).
    # alpha_b no smaller than Penumbra's (perceptual roughness 0.045, brdf.glsl): Cycles takes
    # R and the ratio, and at roughness 0 R = sqrt(at * 0) = 0 made every stretched sphere of
    # AnisotropyStrengthTest's first column a plain mirror, where glTF asks for a streak.
    a = _math(tree, "MAXIMUM", alpha_socket, MIN_ALPHA) if not isinstance(alpha_socket, float) \
        else max(alpha_socket, MIN_ALPHA)
    s2 = _math(tree, "MULTIPLY", s, s) if not isinstance(s, float) else s * s
    one_minus_a = _math(tree, "SUBTRACT", 1.0, a)
    at = _math(tree, "ADD", a, _math(tree, "MULTIPLY", one_minus_a, s2))
    r = _math(tree, "SQRT", _math(tree, "MULTIPLY", at, a), 0.0)
    k = _math(tree, "SUBTRACT", _math(tree, "SQRT", _math(tree, "DIVIDE", a, at), 0.0), 1.0)
    tree.links.new(_math(tree, "SQRT", r, 0.0), node.inputs["Roughness"])
    tree.links.new(k, node.inputs["Anisotropy"])
    return node


def replace_principled(material, ext=None, textures=None):
    """Rebuilds one material; returns True when it had a Principled BSDF to replace. `ext`: the
    glTF material's "extensions" object; `textures`: glTF texture index -> image file."""
    ext = ext or {}
    textures = textures or {}
    for name in ("KHR_materials_iridescence", "KHR_materials_dispersion"):
        if name in ext:
            print("warning: %s: %s is rendered without (Blender 3.4 has no equivalent)" %
                  (material.name if material else "?", name))
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

    # KHR_materials_specular: how much of the Fresnel weight goes to the specular lobe, and its tint.
    layer_weight = fresnel.outputs["Fac"]
    specx = ext.get("KHR_materials_specular")
    if specx is not None:
        stex = _texture(tree, textures, specx.get("specularTexture"), False)
        amount = _scaled(tree, float(specx.get("specularFactor", 1.0)),
                         stex.outputs["Alpha"] if stex is not None else None)
        layer_weight = _math(tree, "MULTIPLY", layer_weight, amount)
        f0 = ((ior - 1.0) / (ior + 1.0)) ** 2 if ior > 1.0 else 0.04
        cap = 1.0 / max(f0, 1e-4)
        colour = list(specx.get("specularColorFactor", [1.0, 1.0, 1.0]))
        ctex = _texture(tree, textures, specx.get("specularColorTexture"), True)
        if ctex is None:
            spec.inputs["Color"].default_value = tuple(min(c, cap) for c in colour) + (1.0,)
        else:
            tint = N.new("ShaderNodeMixRGB")
            tint.blend_type = "MULTIPLY"
            tint.inputs["Fac"].default_value = 1.0
            tint.inputs["Color1"].default_value = tuple(colour) + (1.0,)
            tree.links.new(ctex.outputs["Color"], tint.inputs["Color2"])
            capped = N.new("ShaderNodeVectorMath")
            capped.operation = "MINIMUM"
            tree.links.new(tint.outputs["Color"], capped.inputs[0])
            capped.inputs[1].default_value = (cap, cap, cap)
            tree.links.new(capped.outputs["Vector"], spec.inputs["Color"])

    aniso = ext.get("KHR_materials_anisotropy")
    if aniso is not None and float(aniso.get("anisotropyStrength", 0.0)) > 0.0:
        if float(aniso.get("anisotropyRotation", 0.0)) != 0.0:
            print("warning: %s: the anisotropy's rotation is not rebuilt" % material.name)
        # alpha = perceptual roughness squared, from what fed the Principled roughness.
        rough_src = _source(tree, inp["Roughness"])
        rough = rough_src if rough_src is not None else inp["Roughness"].default_value
        alpha = _math(tree, "MULTIPLY", rough, rough)
        new_spec = _anisotropic(tree, aniso, textures, alpha)
        new_spec.inputs["Color"].default_value = (1.0, 1.0, 1.0, 1.0)
        new_metal = _anisotropic(tree, aniso, textures, alpha)
        _feed(tree, new_metal.inputs["Color"], inp["Base Color"])
        N.remove(spec)
        N.remove(metal)
        spec, metal = new_spec, new_metal
        if normal is not None:
            for node in (spec, metal):
                tree.links.new(normal, node.inputs["Normal"])

    base = diffuse.outputs["BSDF"]
    dt = ext.get("KHR_materials_diffuse_transmission")
    if dt is not None and float(dt.get("diffuseTransmissionFactor", 0.0)) > 0.0:
        translucent = N.new("ShaderNodeBsdfTranslucent")
        colour = list(dt.get("diffuseTransmissionColorFactor", [1.0, 1.0, 1.0]))
        ctex = _texture(tree, textures, dt.get("diffuseTransmissionColorTexture"), True)
        if ctex is not None:
            tint = N.new("ShaderNodeMixRGB")
            tint.blend_type = "MULTIPLY"
            tint.inputs["Fac"].default_value = 1.0
            tint.inputs["Color1"].default_value = tuple(colour) + (1.0,)
            tree.links.new(ctex.outputs["Color"], tint.inputs["Color2"])
            tree.links.new(tint.outputs["Color"], translucent.inputs["Color"])
        else:
            translucent.inputs["Color"].default_value = tuple(colour) + (1.0,)
        if normal is not None:
            tree.links.new(normal, translucent.inputs["Normal"])
        stex = _texture(tree, textures, dt.get("diffuseTransmissionTexture"), False)
        share = N.new("ShaderNodeMixShader")
        amount = _scaled(tree, float(dt["diffuseTransmissionFactor"]),
                         stex.outputs["Alpha"] if stex is not None else None)
        if isinstance(amount, float):
            share.inputs["Fac"].default_value = amount
        else:
            tree.links.new(amount, share.inputs["Fac"])
        tree.links.new(diffuse.outputs["BSDF"], share.inputs[1])
        tree.links.new(translucent.outputs["BSDF"], share.inputs[2])
        base = share.outputs["Shader"]
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
    tree.links.new(layer_weight, dielectric.inputs["Fac"])
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
        coat_fresnel = N.new("ShaderNodeFresnel")
        coat_fresnel.inputs["IOR"].default_value = 1.5
        # The coat's own normal map; without one, the geometric normal (no link).
        ntex = _texture(tree, textures, coat.get("clearcoatNormalTexture"), False)
        if ntex is not None:
            nmap = N.new("ShaderNodeNormalMap")
            nmap.space = "TANGENT"
            nmap.inputs["Strength"].default_value = float(
                coat["clearcoatNormalTexture"].get("scale", 1.0))
            tree.links.new(ntex.outputs["Color"], nmap.inputs["Color"])
            for node in (glossy, coat_fresnel):
                tree.links.new(nmap.outputs["Normal"], node.inputs["Normal"])
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


def use_gltf_brdf(gltf_materials=(), gltf=None, base_dir=""):
    """Replaces the Principled BSDF in every material (with the extensions of the glTF material
    of the same name, and the extensions' textures from `gltf`'s images beside `base_dir`);
    returns how many were rebuilt."""
    by_name = {m.get("name"): m.get("extensions", {}) for m in gltf_materials if m.get("name")}
    textures = {}
    gltf = gltf or {}
    images = gltf.get("images", [])
    for i, t in enumerate(gltf.get("textures", [])):
        src = t.get("source")
        if src is not None and src < len(images) and "uri" in images[src]:
            textures[i] = os.path.join(base_dir, images[src]["uri"])
    return sum(1 for m in bpy.data.materials
               if replace_principled(m, by_name.get(m.name), textures))
