// JSON -> Document, the materials (gltf_parse.cpp has the rest): the core properties, texture
// references with KHR_texture_transform, and the material extensions' factors.
#include <algorithm>
#include <cmath>

#include "scene/gltf_document.h"
#include "scene/gltf_json.h"

namespace penumbra::gltf {
namespace {

TextureInfoDesc parseTextureInfo(Parser& p, const json& info, const std::string& path,
                                 size_t textureCount) {
  TextureInfoDesc t;
  t.texture = p.index(info, "index", path, textureCount, "textures", true);
  t.texCoord = static_cast<int>(p.integer(info, "texCoord", path, 0, false, 0, 1 << 20));
  const json* ext = p.object(info, "extensions", path);
  const json* tt = ext ? p.object(*ext, "KHR_texture_transform", path + ".extensions") : nullptr;
  if (tt) {
    const std::string tp = path + ".extensions.KHR_texture_transform";
    const glm::vec2 offset = p.vec<2>(*tt, "offset", tp, glm::vec2(0.0f));
    const glm::vec2 scale = p.vec<2>(*tt, "scale", tp, glm::vec2(1.0f));
    const float rotation = static_cast<float>(p.number(*tt, "rotation", tp, 0.0));
    t.texCoord = static_cast<int>(p.integer(*tt, "texCoord", tp, t.texCoord, false, 0, 1 << 20));
    // glm is column-major: mat3(col0, col1, col2). The rotation follows the Khronos sample
    // viewer, three.js and the TextureTransformTest model (u' = c*u + s*v, v' = -s*u + c*v);
    // the GLSL listing in the extension's README has the opposite sign (KhronosGroup/glTF#1563).
    const float c = std::cos(rotation);
    const float s = std::sin(rotation);
    const glm::mat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
    const glm::mat3 rot(c, -s, 0, s, c, 0, 0, 0, 1);
    const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    t.transform = translation * rot * scaling;
  }
  return t;
}

// An extension's texture `name` (in object `e` at path `ep`) into its slot.
void extensionTexture(Parser& p, const json& e, const std::string& ep, const char* name,
                      TextureSlot slot, MaterialDesc& md, size_t textureCount) {
  if (const json* t = p.object(e, name, ep)) {
    md.textures[slotIndex(slot)] = parseTextureInfo(p, *t, ep + "." + name, textureCount);
  }
}

// A factor in [0, 1], clamped with a warning naming its path.
float unitFactor(Parser& p, const json& e, const std::string& ep, const char* name, double def,
                 LoadContext& ctx) {
  const double f = p.number(e, name, ep, def);
  if (f < 0.0 || f > 1.0) ctx.warn(ep + "." + name + ": outside [0, 1]; clamped");
  return static_cast<float>(std::clamp(f, 0.0, 1.0));
}

// A colour in [0, 1]^3, clamped with a warning naming its path.
glm::vec3 unitColour(Parser& p, const json& e, const std::string& ep, const char* name,
                     glm::vec3 def, LoadContext& ctx) {
  const glm::vec3 c = p.vec<3>(e, name, ep, def);
  if (glm::any(glm::lessThan(c, glm::vec3(0.0f))) || glm::any(glm::greaterThan(c, glm::vec3(1.0f))))
    ctx.warn(ep + "." + name + ": outside [0, 1]; clamped");
  return glm::clamp(c, glm::vec3(0.0f), glm::vec3(1.0f));
}

// KHR_materials_ior, KHR_materials_specular, KHR_materials_unlit, KHR_materials_clearcoat and
// KHR_materials_sheen: factors and textures. Out-of-range values are clamped with a warning
// naming the path.
void parseMaterialExtensions(Parser& p, const json& ext, const std::string& path, MaterialDesc& md,
                             LoadContext& ctx, size_t textureCount) {
  Material& m = md.material;
  if (const json* e = p.object(ext, "KHR_materials_ior", path)) {
    const std::string ep = path + ".KHR_materials_ior";
    const double ior = p.number(*e, "ior", ep, 1.5);
    // The extension allows 0 (meaning an infinite index: F0 = 1) besides [1, inf).
    if (ior == 0.0) {
      m.ior = 3.4e38f;
    } else if (ior < 1.0) {
      ctx.warn(ep + ".ior: " + std::to_string(ior) + " is below 1; using 1");
      m.ior = 1.0f;
    } else {
      m.ior = static_cast<float>(ior);
    }
  }
  if (const json* e = p.object(ext, "KHR_materials_specular", path)) {
    const std::string ep = path + ".KHR_materials_specular";
    m.specularFactor = unitFactor(p, *e, ep, "specularFactor", 1.0, ctx);
    m.specularColorFactor =
        glm::max(p.vec<3>(*e, "specularColorFactor", ep, glm::vec3(1.0f)), glm::vec3(0.0f));
    extensionTexture(p, *e, ep, "specularTexture", TextureSlot::Specular, md, textureCount);
    extensionTexture(p, *e, ep, "specularColorTexture", TextureSlot::SpecularColor, md,
                     textureCount);
  }
  if (p.object(ext, "KHR_materials_unlit", path)) m.unlit = true;
  if (const json* e = p.object(ext, "KHR_materials_clearcoat", path)) {
    const std::string ep = path + ".KHR_materials_clearcoat";
    m.clearcoat = unitFactor(p, *e, ep, "clearcoatFactor", 0.0, ctx);
    m.clearcoatRoughness = unitFactor(p, *e, ep, "clearcoatRoughnessFactor", 0.0, ctx);
    extensionTexture(p, *e, ep, "clearcoatTexture", TextureSlot::Clearcoat, md, textureCount);
    extensionTexture(p, *e, ep, "clearcoatRoughnessTexture", TextureSlot::ClearcoatRoughness, md,
                     textureCount);
    if (const json* t = p.object(*e, "clearcoatNormalTexture", ep)) {
      md.textures[slotIndex(TextureSlot::ClearcoatNormal)] =
          parseTextureInfo(p, *t, ep + ".clearcoatNormalTexture", textureCount);
      m.clearcoatNormalScale =
          static_cast<float>(p.number(*t, "scale", ep + ".clearcoatNormalTexture", 1.0));
    }
  }
  if (const json* e = p.object(ext, "KHR_materials_sheen", path)) {
    const std::string ep = path + ".KHR_materials_sheen";
    m.sheenColor = unitColour(p, *e, ep, "sheenColorFactor", glm::vec3(0.0f), ctx);
    m.sheenRoughness = unitFactor(p, *e, ep, "sheenRoughnessFactor", 0.0, ctx);
    extensionTexture(p, *e, ep, "sheenColorTexture", TextureSlot::SheenColor, md, textureCount);
    extensionTexture(p, *e, ep, "sheenRoughnessTexture", TextureSlot::SheenRoughness, md,
                     textureCount);
  }
}

// KHR_materials_transmission and KHR_materials_volume (factors and textures). Thickness is in
// the mesh's own units (the renderer scales it by the instance's transform); a missing
// attenuationDistance means none.
void parseTransmission(Parser& p, const json& ext, const std::string& path, MaterialDesc& md,
                       LoadContext& ctx, size_t textureCount) {
  Material& m = md.material;
  if (const json* e = p.object(ext, "KHR_materials_transmission", path)) {
    const std::string ep = path + ".KHR_materials_transmission";
    m.transmission = unitFactor(p, *e, ep, "transmissionFactor", 0.0, ctx);
    extensionTexture(p, *e, ep, "transmissionTexture", TextureSlot::Transmission, md, textureCount);
  }
  if (const json* e = p.object(ext, "KHR_materials_volume", path)) {
    const std::string ep = path + ".KHR_materials_volume";
    const double th = p.number(*e, "thicknessFactor", ep, 0.0);
    if (th < 0.0) ctx.warn(ep + ".thicknessFactor: negative; using 0 (thin-walled)");
    m.thickness = static_cast<float>(std::max(th, 0.0));
    const double d = p.number(*e, "attenuationDistance", ep, 0.0);
    if (e->contains("attenuationDistance") && !(d > 0.0))
      ctx.warn(ep + ".attenuationDistance: not positive; no attenuation");
    m.attenuationDistance = d > 0.0 && std::isfinite(d) ? static_cast<float>(d) : 0.0f;
    m.attenuationColor = unitColour(p, *e, ep, "attenuationColor", glm::vec3(1.0f), ctx);
    extensionTexture(p, *e, ep, "thicknessTexture", TextureSlot::Thickness, md, textureCount);
  }
}

// KHR_materials_dispersion, KHR_materials_iridescence, KHR_materials_anisotropy and
// KHR_materials_diffuse_transmission: factors and textures.
void parseLaterExtensions(Parser& p, const json& ext, const std::string& path, MaterialDesc& md,
                          LoadContext& ctx, size_t textureCount) {
  Material& m = md.material;
  if (const json* e = p.object(ext, "KHR_materials_dispersion", path)) {
    const std::string ep = path + ".KHR_materials_dispersion";
    const double d = p.number(*e, "dispersion", ep, 0.0);
    if (!(d >= 0.0) || !std::isfinite(d)) ctx.warn(ep + ".dispersion: negative; using 0");
    m.dispersion = d >= 0.0 && std::isfinite(d) ? static_cast<float>(d) : 0.0f;
  }
  if (const json* e = p.object(ext, "KHR_materials_iridescence", path)) {
    const std::string ep = path + ".KHR_materials_iridescence";
    m.iridescence = unitFactor(p, *e, ep, "iridescenceFactor", 0.0, ctx);
    const double ior = p.number(*e, "iridescenceIor", ep, 1.3);
    if (!(ior >= 1.0)) ctx.warn(ep + ".iridescenceIor: below 1; using 1");
    m.iridescenceIor = ior >= 1.0 && std::isfinite(ior) ? static_cast<float>(ior) : 1.0f;
    const double lo = p.number(*e, "iridescenceThicknessMinimum", ep, 100.0);
    const double hi = p.number(*e, "iridescenceThicknessMaximum", ep, 400.0);
    if (!(lo >= 0.0) || !(hi >= 0.0)) ctx.warn(ep + ": negative film thickness; using 0");
    m.iridescenceThicknessMin = static_cast<float>(std::max(lo, 0.0));
    m.iridescenceThicknessMax = static_cast<float>(std::max(hi, 0.0));
    extensionTexture(p, *e, ep, "iridescenceTexture", TextureSlot::Iridescence, md, textureCount);
    extensionTexture(p, *e, ep, "iridescenceThicknessTexture", TextureSlot::IridescenceThickness,
                     md, textureCount);
  }
  if (const json* e = p.object(ext, "KHR_materials_anisotropy", path)) {
    const std::string ep = path + ".KHR_materials_anisotropy";
    m.anisotropy = unitFactor(p, *e, ep, "anisotropyStrength", 0.0, ctx);
    m.anisotropyRotation = static_cast<float>(p.number(*e, "anisotropyRotation", ep, 0.0));
    extensionTexture(p, *e, ep, "anisotropyTexture", TextureSlot::Anisotropy, md, textureCount);
  }
  if (const json* e = p.object(ext, "KHR_materials_diffuse_transmission", path)) {
    const std::string ep = path + ".KHR_materials_diffuse_transmission";
    m.diffuseTransmission = unitFactor(p, *e, ep, "diffuseTransmissionFactor", 0.0, ctx);
    m.diffuseTransmissionColor =
        unitColour(p, *e, ep, "diffuseTransmissionColorFactor", glm::vec3(1.0f), ctx);
    extensionTexture(p, *e, ep, "diffuseTransmissionTexture", TextureSlot::DiffuseTransmission, md,
                     textureCount);
    extensionTexture(p, *e, ep, "diffuseTransmissionColorTexture",
                     TextureSlot::DiffuseTransmissionColor, md, textureCount);
  }
}

}  // namespace

// Parses the 'materials' array.
void parseMaterials(Parser& p, const json& root, Document& doc, LoadContext& ctx,
                    size_t textureCount) {
  forEach(p, root, "materials", [&](const json& o, const std::string& path, size_t) {
    MaterialDesc md;
    Material& m = md.material;
    m.name = p.string(o, "name", path);
    if (const json* pbr = p.object(o, "pbrMetallicRoughness", path)) {
      const std::string pp = path + ".pbrMetallicRoughness";
      m.baseColorFactor = p.vec<4>(*pbr, "baseColorFactor", pp, glm::vec4(1.0f));
      m.metallicFactor = static_cast<float>(p.number(*pbr, "metallicFactor", pp, 1.0));
      m.roughnessFactor = static_cast<float>(p.number(*pbr, "roughnessFactor", pp, 1.0));
      if (const json* t = p.object(*pbr, "baseColorTexture", pp)) {
        md.textures[slotIndex(TextureSlot::BaseColor)] =
            parseTextureInfo(p, *t, pp + ".baseColorTexture", textureCount);
      }
      if (const json* t = p.object(*pbr, "metallicRoughnessTexture", pp)) {
        md.textures[slotIndex(TextureSlot::MetallicRoughness)] =
            parseTextureInfo(p, *t, pp + ".metallicRoughnessTexture", textureCount);
      }
    }
    if (const json* t = p.object(o, "normalTexture", path)) {
      md.textures[slotIndex(TextureSlot::Normal)] =
          parseTextureInfo(p, *t, path + ".normalTexture", textureCount);
      m.normalScale = static_cast<float>(p.number(*t, "scale", path + ".normalTexture", 1.0));
    }
    if (const json* t = p.object(o, "occlusionTexture", path)) {
      md.textures[slotIndex(TextureSlot::Occlusion)] =
          parseTextureInfo(p, *t, path + ".occlusionTexture", textureCount);
      m.occlusionStrength =
          static_cast<float>(p.number(*t, "strength", path + ".occlusionTexture", 1.0));
    }
    if (const json* t = p.object(o, "emissiveTexture", path)) {
      md.textures[slotIndex(TextureSlot::Emissive)] =
          parseTextureInfo(p, *t, path + ".emissiveTexture", textureCount);
    }
    m.emissiveFactor = p.vec<3>(o, "emissiveFactor", path, glm::vec3(0.0f));
    const std::string alpha = p.string(o, "alphaMode", path, "OPAQUE");
    if (alpha == "MASK") {
      m.alphaMode = AlphaMode::Mask;
    } else if (alpha == "BLEND") {
      m.alphaMode = AlphaMode::Blend;
    } else if (alpha != "OPAQUE") {
      ctx.warn(path + ".alphaMode: unknown value '" + alpha + "', using OPAQUE");
    }
    m.alphaCutoff = static_cast<float>(p.number(o, "alphaCutoff", path, 0.5));
    m.doubleSided = p.boolean(o, "doubleSided", path, false);
    if (const json* ext = p.object(o, "extensions", path)) {
      if (const json* es =
              p.object(*ext, "KHR_materials_emissive_strength", path + ".extensions")) {
        m.emissiveStrength = static_cast<float>(p.number(
            *es, "emissiveStrength", path + ".extensions.KHR_materials_emissive_strength", 1.0));
      }
      parseMaterialExtensions(p, *ext, path + ".extensions", md, ctx, textureCount);
      parseTransmission(p, *ext, path + ".extensions", md, ctx, textureCount);
      parseLaterExtensions(p, *ext, path + ".extensions", md, ctx, textureCount);
    }
    doc.materials.push_back(std::move(md));
  });
}

}  // namespace penumbra::gltf
