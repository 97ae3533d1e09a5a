#include "gpu/gpu_scene.h"

#include <algorithm>
#include <string>

#include "scene/mesh_lod.h"

namespace penumbra {
namespace {

constexpr int kPosition = 0, kNormal = 1, kTangent = 2, kUv0 = 3, kUv1 = 4, kColor = 5;

template <class T>
Status addAttribute(GpuPrimitive& p, int location, const std::vector<T>& data, int components) {
  auto buf = gl::Buffer::create(gl::BufferKind::Vertex, std::span<const T>(data));
  if (!buf) return buf.error();
  p.vao.setAttribute(location, *buf, components, gl::AttribType::Float, false, 0, 0);
  p.buffers.push_back(std::move(*buf));
  return {};
}

gl::Filter minFilter(int f) {
  switch (f) {
    case 9728:
      return gl::Filter::Nearest;  // NEAREST
    case 9729:
      return gl::Filter::Linear;  // LINEAR
    case 9984:
      return gl::Filter::NearestMipNearest;  // NEAREST_MIPMAP_NEAREST
    default:
      return gl::Filter::LinearMipLinear;  // the mipmapped ones
  }
}

// The sRGB twin of a compressed format the KTX2 transcoder targets (ASTC 4x4, BC7, ETC2 RGBA).
uint32_t srgbVariant(uint32_t format) {
  switch (format) {
    case 0x93B0:  // COMPRESSED_RGBA_ASTC_4x4_KHR
      return 0x93D0;
    case 0x8E8C:  // COMPRESSED_RGBA_BPTC_UNORM_EXT
      return 0x8E8D;
    case 0x9278:  // COMPRESSED_RGBA8_ETC2_EAC
      return 0x9279;
    default:
      return format;
  }
}

gl::Wrap wrap(int w) {
  switch (w) {
    case 33071:
      return gl::Wrap::ClampToEdge;
    case 33648:
      return gl::Wrap::MirroredRepeat;
    default:
      return gl::Wrap::Repeat;
  }
}

// The attribute from `data`, or where the primitive has none, a constant.
template <class T>
Status attributeOr(GpuPrimitive& p, int location, const std::vector<T>& data, int components,
                   glm::vec4 constant) {
  if (!data.empty()) return addAttribute(p, location, data, components);
  p.vao.setConstant(location, constant.x, constant.y, constant.z, constant.w);
  return {};
}

// One primitive's vertex arrays (constants for missing attributes) and index buffer, with its
// capture stand-in's indices after its own.
Result<std::unique_ptr<GpuPrimitive>> uploadPrimitive(const Primitive& prim, float meshScale,
                                                      float sceneDiagonal) {
  auto p = std::make_unique<GpuPrimitive>();
  p->vao = gl::VertexArray::create();
  p->material = prim.material;
  p->bounds = prim.bounds;
  p->indexCount = static_cast<int>(prim.indices.size());
  PN_TRY(addAttribute(*p, kPosition, prim.positions, 3));
  PN_TRY(attributeOr(*p, kNormal, prim.normals, 3, {0, 0, 1, 0}));
  PN_TRY(attributeOr(*p, kTangent, prim.tangents, 4, {0, 0, 0, 1}));
  PN_TRY(attributeOr(*p, kUv0, prim.uv0, 2, {0, 0, 0, 1}));
  // (Without a second UV set, the first stands in for it.)
  PN_TRY(attributeOr(*p, kUv1, prim.uv1.empty() ? prim.uv0 : prim.uv1, 2, {0, 0, 0, 1}));
  PN_TRY(attributeOr(*p, kColor, prim.colors, 4, {1, 1, 1, 1}));
  // The capture stand-in goes after the primitive's own indices, in the same buffer.
  const std::vector<uint32_t> lod = captureLod(prim, meshScale, sceneDiagonal);
  p->captureIndexCount = static_cast<int>(lod.empty() ? prim.indices.size() : lod.size());
  p->captureByteOffset = lod.empty() ? 0 : prim.indices.size() * sizeof(uint32_t);
  std::vector<uint32_t> indices;
  if (!lod.empty()) {
    indices.reserve(prim.indices.size() + lod.size());
    indices.insert(indices.end(), prim.indices.begin(), prim.indices.end());
    indices.insert(indices.end(), lod.begin(), lod.end());
  }
  auto ib = gl::Buffer::create(gl::BufferKind::Index,
                               std::span<const uint32_t>(lod.empty() ? prim.indices : indices));
  if (!ib) return ib.error();
  p->vao.setIndexBuffer(*ib, gl::IndexType::UInt32);
  p->buffers.push_back(std::move(*ib));
  return p;
}

}  // namespace

Status GpuScene::uploadMeshes(const Scene& scene) {
  // Each mesh's largest scale over its instances, for its capture stand-in's error bound.
  std::vector<float> meshScale(scene.meshes.size(), 0.0f);
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(scene.meshes.size())) continue;
    const glm::mat3 m(inst.world);
    const float s = std::max(glm::length(m[0]), std::max(glm::length(m[1]), glm::length(m[2])));
    float& scale = meshScale[static_cast<size_t>(inst.mesh)];
    scale = std::max(scale, s);
  }
  const float sceneDiagonal =
      scene.bounds.valid() ? glm::length(scene.bounds.max - scene.bounds.min) : 0.0f;
  for (size_t mi = 0; mi < scene.meshes.size(); ++mi) {
    std::vector<GpuPrimitive*> prims;
    for (const Primitive& prim : scene.meshes[mi].primitives) {
      auto p = uploadPrimitive(prim, meshScale[mi], sceneDiagonal);
      if (!p) return p.error();
      prims.push_back(p->get());
      primitives_.push_back(std::move(*p));
    }
    meshes_.push_back(std::move(prims));
  }
  return {};
}

Status GpuScene::uploadMaterials(const Scene& scene) {
  // Materials, then the glTF default material (white, metallic 1, roughness 1) last.
  for (const Material& m : scene.materials) {
    GpuMaterial gm;
    gm.source = m;
    const TextureRef* refs[kMaterialSlots] = {&m.baseColorTexture, &m.metallicRoughnessTexture,
                                              &m.normalTexture,    &m.occlusionTexture,
                                              &m.emissiveTexture,  &m.clearcoatNormalTexture};
    bool has[kMaterialSlots] = {};
    for (int slot = 0; slot < kMaterialSlots; ++slot) {
      if (!refs[slot]->valid()) continue;
      const bool srgb = slot == 0 || slot == 4;  // base colour and emissive are sRGB
      auto tex = texture(scene, *refs[slot], srgb);
      if (!tex) return tex.error();
      gm.textures[slot] = *tex;
      has[slot] = true;
    }
    gm.features = materialFeatures(m, has);
    materials_.push_back(std::move(gm));
  }
  GpuMaterial fallbackMaterial;
  const bool none[kMaterialSlots] = {};
  fallbackMaterial.features = materialFeatures(fallbackMaterial.source, none);
  materials_.push_back(std::move(fallbackMaterial));
  auto fallback =
      gl::Texture2D::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8});
  if (!fallback) return fallback.error();
  const uint8_t white[4] = {255, 255, 255, 255};
  fallback->upload(0, white, gl::DataType::UInt8);
  fallback_ = std::move(*fallback);
  return {};
}

void GpuScene::buildDrawItems(const Scene& scene) {
  const int defaultMaterial = static_cast<int>(materials_.size()) - 1;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh < 0 || inst.mesh >= static_cast<int>(meshes_.size())) continue;
    const glm::mat3 upper(inst.world);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(upper));
    for (GpuPrimitive* p : meshes_[static_cast<size_t>(inst.mesh)]) {
      DrawItem item;
      item.primitive = p;
      item.material =
          p->material >= 0 && p->material < defaultMaterial ? p->material : defaultMaterial;
      item.model = inst.world;
      item.normalMatrix = normalMatrix;
      item.mirrored = glm::determinant(upper) < 0.0f;
      item.castsShadow = inst.castsShadow;
      Bounds wb;
      if (p->bounds.valid()) {
        for (int c = 0; c < 8; ++c) {
          glm::vec3 corner((c & 1) ? p->bounds.max.x : p->bounds.min.x,
                           (c & 2) ? p->bounds.max.y : p->bounds.min.y,
                           (c & 4) ? p->bounds.max.z : p->bounds.min.z);
          wb.extend(glm::vec3(inst.world * glm::vec4(corner, 1.0f)));
        }
        bounds_.extend(wb);
        item.center = wb.center();
      }
      const Material& m = materials_[static_cast<size_t>(item.material)].source;
      const bool blend = m.alphaMode == AlphaMode::Blend;
      const bool transmits = !blend && !m.unlit && m.transmission > 0.0f;
      item.layer = static_cast<int>(opaque_.size() + blended_.size() + transmissive_.size());
      (transmits ? transmissive_ : blend ? blended_ : opaque_).push_back(item);
    }
  }
  // Grouped by material features: each group is drawn with one specialised program. (BLEND
  // surfaces keep the scene's order; frame 1 sorts them back to front anyway.)
  const auto byFeatures = [this](const DrawItem& a, const DrawItem& b) {
    return material(a.material).features < material(b.material).features;
  };
  std::stable_sort(opaque_.begin(), opaque_.end(), byFeatures);
  std::stable_sort(transmissive_.begin(), transmissive_.end(), byFeatures);
}

Result<std::unique_ptr<GpuScene>> GpuScene::create(const Scene& scene) {
  auto gs = std::make_unique<GpuScene>();
  PN_TRY(gs->uploadMeshes(scene));
  PN_TRY(gs->uploadMaterials(scene));
  gs->buildDrawItems(scene);
  return gs;
}

uint32_t materialFeatures(const Material& m, const bool (&hasTexture)[kMaterialSlots]) {
  uint32_t f = 0;
  for (int slot = 0; slot < kMaterialSlots; ++slot) {
    if (hasTexture[slot]) f |= 1u << slot;
  }
  if (m.clearcoat > 0.0f) f |= kFeatureClearcoat;
  if (glm::max(m.sheenColor.r, glm::max(m.sheenColor.g, m.sheenColor.b)) > 0.0f) {
    f |= kFeatureSheen;
  }
  if (m.unlit) f |= kFeatureUnlit;
  f |= static_cast<uint32_t>(m.alphaMode) << kFeatureAlphaShift;
  // A broad specular lobe on a dielectric (its share of the light is a few per cent): the
  // occlusion march of its diffuse lobe stands for both.
  if (!hasTexture[1] && m.metallicFactor < 0.5f && m.roughnessFactor >= 0.75f) {
    f |= kFeatureBroadLobe;
  }
  // Lobes broad enough for the area lights' per-view cache (a light's reflection in a smooth
  // surface is under a pixel: a cache of a few sub-pixel positions would lose it).
  if (!hasTexture[1] && m.roughnessFactor >= kLightCacheMinRoughness &&
      (m.clearcoat <= 0.0f || m.clearcoatRoughness >= kLightCacheMinRoughness)) {
    f |= kFeatureLightCacheable;
  }
  return f;
}

gl::Defines materialDefines(uint32_t features) {
  const auto flag = [features](uint32_t bit) { return std::string(features & bit ? "1" : "0"); };
  return {{"PN_MATERIAL_KEYED", "1"},
          {"PN_TEXTURES", std::to_string(features & kFeatureTextures)},
          {"PN_CLEARCOAT", flag(kFeatureClearcoat)},
          {"PN_SHEEN", flag(kFeatureSheen)},
          {"PN_UNLIT", flag(kFeatureUnlit)},
          {"PN_ALPHA_MODE", std::to_string((features >> kFeatureAlphaShift) & 3u)},
          {"PN_BROAD_LOBE", flag(kFeatureBroadLobe)}};
}

Result<const gl::Texture2D*> GpuScene::texture(const Scene& scene, const TextureRef& ref,
                                               bool srgb) {
  auto key = std::make_pair(ref.image * 64 + std::max(ref.sampler + 1, 0), srgb);
  if (auto it = textures_.find(key); it != textures_.end()) return it->second.get();
  if (ref.image < 0 || ref.image >= static_cast<int>(scene.images.size())) {
    return makeError("texture refers to missing image " + std::to_string(ref.image));
  }
  const ImageData& img = scene.images[static_cast<size_t>(ref.image)];
  SamplerDesc sd;
  if (ref.sampler >= 0 && ref.sampler < static_cast<int>(scene.samplers.size())) {
    sd = scene.samplers[static_cast<size_t>(ref.sampler)];
  }
  const gl::Filter minF = minFilter(sd.minFilter);
  const bool mips = minF == gl::Filter::LinearMipLinear || minF == gl::Filter::NearestMipNearest;
  if (img.compressedFormat != 0) {
    // The levels the file has: no mipmaps can be generated for compressed data.
    gl::SamplerState sampler{
        .minFilter = minF,
        .magFilter = sd.magFilter == 9728 ? gl::Filter::Nearest : gl::Filter::Linear,
        .wrapS = wrap(sd.wrapS),
        .wrapT = wrap(sd.wrapT)};
    const bool full = img.compressedLevels.size() > 1;
    if (!full && sampler.minFilter == gl::Filter::LinearMipLinear)
      sampler.minFilter = gl::Filter::Linear;
    if (!full && sampler.minFilter == gl::Filter::NearestMipNearest)
      sampler.minFilter = gl::Filter::Nearest;
    auto tex = gl::Texture2D::createCompressed(
        img.width, img.height, srgb ? srgbVariant(img.compressedFormat) : img.compressedFormat,
        srgb ? gl::PixelFormat::SRGB8_ALPHA8 : gl::PixelFormat::RGBA8, img.compressedLevels,
        sampler);
    if (!tex) return makeError("image '" + img.name + "': " + tex.message());
    auto owned = std::make_unique<gl::Texture2D>(std::move(*tex));
    const gl::Texture2D* raw = owned.get();
    textures_.emplace(key, std::move(owned));
    return raw;
  }
  gl::TextureDesc desc;
  desc.width = std::max(img.width, 1);
  desc.height = std::max(img.height, 1);
  desc.format = srgb ? gl::PixelFormat::SRGB8_ALPHA8 : gl::PixelFormat::RGBA8;
  desc.levels = mips ? gl::fullMipCount(desc.width, desc.height) : 1;
  desc.sampler = {.minFilter = minF,
                  .magFilter = sd.magFilter == 9728 ? gl::Filter::Nearest : gl::Filter::Linear,
                  .wrapS = wrap(sd.wrapS),
                  .wrapT = wrap(sd.wrapT)};
  auto tex = gl::Texture2D::create(desc);
  if (!tex) return makeError("image '" + img.name + "': " + tex.message());
  const uint8_t white[4] = {255, 255, 255, 255};
  const bool usable = img.pixels.size() >= static_cast<size_t>(desc.width) * desc.height * 4;
  tex->upload(0, usable ? img.pixels.data() : white, gl::DataType::UInt8);
  if (mips) tex->generateMipmaps();
  auto owned = std::make_unique<gl::Texture2D>(std::move(*tex));
  const gl::Texture2D* raw = owned.get();
  textures_.emplace(key, std::move(owned));
  return raw;
}

void GpuScene::bindMaterial(const gl::Program& program, int index) const {
  const GpuMaterial& gm = materials_[static_cast<size_t>(index)];
  const Material& m = gm.source;
  program.set("uBaseColorFactor", m.baseColorFactor);
  program.set("uMetallicFactor", m.metallicFactor);
  program.set("uRoughnessFactor", m.roughnessFactor);
  program.set("uEmissive", m.emissiveFactor * m.emissiveStrength);
  program.set("uNormalScale", m.normalScale);
  program.set("uOcclusionStrength", m.occlusionStrength);
  program.set("uAlphaMode", static_cast<int>(m.alphaMode));
  program.set("uAlphaCutoff", m.alphaCutoff);
  program.set("uDielectricF0", m.dielectricF0());
  program.set("uDielectricF90", m.specularFactor);
  program.set("uUnlit", m.unlit ? 1 : 0);
  program.set("uClearcoat", m.clearcoat);
  program.set("uClearcoatRoughness", m.clearcoatRoughness);
  program.set("uSheenColor", m.sheenColor);
  program.set("uSheenRoughness", m.sheenRoughness);
  program.set("uTransmission", m.transmission);
  program.set("uThickness", m.thickness);
  program.set("uIor", m.ior);
  program.set("uAttenuationDistance", m.attenuationDistance);
  program.set("uAttenuationColor", m.attenuationColor);
  program.set("uClearcoatNormalScale", m.clearcoatNormalScale);
  const TextureRef* refs[kMaterialSlots] = {&m.baseColorTexture, &m.metallicRoughnessTexture,
                                            &m.normalTexture,    &m.occlusionTexture,
                                            &m.emissiveTexture,  &m.clearcoatNormalTexture};
  static const char* const kSamplers[kMaterialSlots] = {"uBaseColorTex", "uMetallicRoughnessTex",
                                                        "uNormalTex",    "uOcclusionTex",
                                                        "uEmissiveTex",  "uClearcoatNormalTex"};
  int textureMask = 0, texCoordMask = 0;
  glm::mat3 transforms[kMaterialSlots];
  for (int slot = 0; slot < kMaterialSlots; ++slot) {
    const int unit = slot == kMaterialSlots - 1 ? kClearcoatNormalUnit : slot;
    transforms[slot] = refs[slot]->transform;
    program.set(kSamplers[slot], unit);
    if (gm.textures[slot]) {
      textureMask |= 1 << slot;
      if (refs[slot]->texCoord == 1) texCoordMask |= 1 << slot;
      gm.textures[slot]->bind(unit);
    } else {
      fallback_.bind(unit);
    }
  }
  program.set("uTextureMask", textureMask);
  program.set("uTexCoordMask", texCoordMask);
  program.set("uUvTransform", std::span<const glm::mat3>(transforms));
}

void GpuScene::bindTransform(const gl::Program& program, const DrawItem& item) {
  program.set("uModel", item.model);
  program.set("uNormalMatrix", item.normalMatrix);
  program.set("uLayer", item.layer);
  program.set("uIndirectEmission", item.castsShadow ? 1.0f : 0.0f);  // 0: a lamp's face
}

}  // namespace penumbra
