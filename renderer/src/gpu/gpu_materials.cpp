// GpuScene's materials: their core textures (a GL texture per image, sampler and colour space,
// shared between materials), their extension textures as one texture array per material
// (gpu_scene.h says why), the features the shading programs are specialised on, and binding.
#include <algorithm>
#include <cmath>
#include <string>

#include "gpu/gpu_scene.h"
#include "image/resize.h"

namespace penumbra {
namespace {

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

// The image's RGBA8 pixels at w x h (resampled where its size differs); white where it has
// none to give (a compressed image: the loader decodes the layers' images to RGBA8).
std::vector<uint8_t> layerPixels(const ImageData& img, int w, int h) {
  const size_t bytes = static_cast<size_t>(w) * static_cast<size_t>(h) * 4;
  const bool usable = img.compressedFormat == 0 && img.width > 0 && img.height > 0 &&
                      img.pixels.size() >= static_cast<size_t>(img.width) * img.height * 4;
  if (!usable) return std::vector<uint8_t>(bytes, 255);
  if (img.width == w && img.height == h) return img.pixels;
  return resizeRgba8(img.pixels, img.width, img.height, w, h);
}

}  // namespace

Status GpuScene::uploadMaterials(const Scene& scene) {
  // Materials, then the glTF default material (white, metallic 1, roughness 1) last.
  for (const Material& m : scene.materials) {
    GpuMaterial gm;
    gm.source = m;
    bool has[kTextureSlotCount] = {};
    for (int slot = 0; slot < kCoreTextureSlots; ++slot) {
      const TextureRef& ref = m.texture(static_cast<TextureSlot>(slot));
      if (!ref.valid()) continue;
      auto tex = texture(scene, ref, textureSlotInfo(static_cast<TextureSlot>(slot)).srgb);
      if (!tex) return tex.error();
      gm.textures[slot] = *tex;
      has[slot] = true;
    }
    PN_TRY(uploadLayers(scene, gm));
    for (int slot = kCoreTextureSlots; slot < kTextureSlotCount; ++slot)
      has[slot] = gm.layer[slot] >= 0;
    gm.features = materialFeatures(m, has);
    materials_.push_back(std::move(gm));
  }
  GpuMaterial fallbackMaterial;
  const bool none[kTextureSlotCount] = {};
  fallbackMaterial.features = materialFeatures(fallbackMaterial.source, none);
  materials_.push_back(std::move(fallbackMaterial));
  const uint8_t white[4] = {255, 255, 255, 255};
  auto fallback =
      gl::Texture2D::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8});
  if (!fallback) return fallback.error();
  fallback->upload(0, white, gl::DataType::UInt8);
  fallback_ = std::move(*fallback);
  auto layers =
      gl::Texture2DArray::create({.width = 1, .height = 1, .format = gl::PixelFormat::RGBA8}, 1);
  if (!layers) return layers.error();
  layers->upload(0, white, gl::DataType::UInt8);
  fallbackLayers_ = std::move(*layers);
  return {};
}

Status GpuScene::uploadLayers(const Scene& scene, GpuMaterial& gm) {
  std::vector<int> images;  // a layer each
  int w = 1, h = 1, first = -1;
  for (int slot = kCoreTextureSlots; slot < kTextureSlotCount; ++slot) {
    const TextureRef& ref = gm.source.texture(static_cast<TextureSlot>(slot));
    if (!ref.valid()) continue;
    if (ref.image >= static_cast<int>(scene.images.size())) {
      return makeError("texture refers to missing image " + std::to_string(ref.image));
    }
    if (first < 0) first = slot;
    auto it = std::find(images.begin(), images.end(), ref.image);
    gm.layer[slot] = static_cast<int>(it - images.begin());
    if (it != images.end()) continue;
    images.push_back(ref.image);
    const ImageData& img = scene.images[static_cast<size_t>(ref.image)];
    w = std::max(w, img.width);
    h = std::max(h, img.height);
  }
  if (images.empty()) return {};
  const TextureRef& ref = gm.source.texture(static_cast<TextureSlot>(first));
  SamplerDesc sd;
  if (ref.sampler >= 0 && ref.sampler < static_cast<int>(scene.samplers.size())) {
    sd = scene.samplers[static_cast<size_t>(ref.sampler)];
  }
  const gl::Filter minF = minFilter(sd.minFilter);
  const bool mips = minF == gl::Filter::LinearMipLinear || minF == gl::Filter::NearestMipNearest;
  gl::TextureDesc desc{
      .width = w,
      .height = h,
      .format = gl::PixelFormat::RGBA8,
      .levels = mips ? gl::fullMipCount(w, h) : 1,
      .sampler = {.minFilter = minF,
                  .magFilter = sd.magFilter == 9728 ? gl::Filter::Nearest : gl::Filter::Linear,
                  .wrapS = wrap(sd.wrapS),
                  .wrapT = wrap(sd.wrapT)}};
  auto array = gl::Texture2DArray::create(desc, static_cast<int>(images.size()));
  if (!array) return makeError("material '" + gm.source.name + "': " + array.message());
  for (size_t i = 0; i < images.size(); ++i) {
    array->upload(static_cast<int>(i),
                  layerPixels(scene.images[static_cast<size_t>(images[i])], w, h).data(),
                  gl::DataType::UInt8);
  }
  if (mips) array->generateMipmaps();
  gm.layers = std::move(*array);
  return {};
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
  const float r = (m.ior - 1.0f) / (m.ior + 1.0f);
  program.set("uSpecularColorF0", glm::vec3(r * r) * m.specularColorFactor);
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
  program.set("uDispersion", m.dispersion);
  program.set("uIridescence", glm::vec4(m.iridescence, m.iridescenceIor, m.iridescenceThicknessMin,
                                        m.iridescenceThicknessMax));
  program.set("uAnisotropy", glm::vec3(m.anisotropy, std::cos(m.anisotropyRotation),
                                       std::sin(m.anisotropyRotation)));
  program.set("uDiffuseTransmission", glm::vec4(m.diffuseTransmissionColor, m.diffuseTransmission));
  static const char* const kSamplers[kCoreTextureSlots] = {
      "uBaseColorTex", "uMetallicRoughnessTex", "uNormalTex", "uOcclusionTex", "uEmissiveTex"};
  int textureMask = 0;
  // Per slot the rows of its UV transform, with its UV set and its layer in their w.
  glm::vec4 rowS[kTextureSlotCount], rowT[kTextureSlotCount];
  for (int slot = 0; slot < kTextureSlotCount; ++slot) {
    const TextureRef& ref = m.texture(static_cast<TextureSlot>(slot));
    const glm::mat3& t = ref.transform;
    rowS[slot] = glm::vec4(t[0][0], t[1][0], t[2][0], ref.texCoord == 1 ? 1.0f : 0.0f);
    rowT[slot] =
        glm::vec4(t[0][1], t[1][1], t[2][1], static_cast<float>(std::max(gm.layer[slot], 0)));
    const bool has = slot < kCoreTextureSlots ? gm.textures[slot] != nullptr : gm.layer[slot] >= 0;
    if (has) textureMask |= 1 << slot;
    if (slot >= kCoreTextureSlots) continue;
    program.bind(kSamplers[slot], has ? *gm.textures[slot] : fallback_);
  }
  program.bind("uMaterialLayers", gm.layers ? gm.layers : fallbackLayers_);
  program.set("uTextureMask", textureMask);
  program.set("uSlotUvS", std::span<const glm::vec4>(rowS));
  program.set("uSlotUvT", std::span<const glm::vec4>(rowT));
}

MaterialFeatures materialFeatures(const Material& m,
                                  const bool (&hasTexture)[kTextureSlotCount]) {
  MaterialFeatures f;
  for (int slot = 0; slot < kTextureSlotCount; ++slot) {
    if (hasTexture[slot]) f.textures |= 1u << slot;
  }
  f.clearcoat = m.clearcoat > 0.0f;
  f.sheen = glm::max(m.sheenColor.r, glm::max(m.sheenColor.g, m.sheenColor.b)) > 0.0f;
  f.unlit = m.unlit;
  // The later extensions (their textures only scale their factors: a factor of 0 is off).
  f.iridescence = m.iridescence > 0.0f;
  f.anisotropy = m.anisotropy > 0.0f;
  f.diffuseTransmission = m.diffuseTransmission > 0.0f && m.transmission <= 0.0f;
  f.dispersion = m.dispersion > 0.0f && m.transmission > 0.0f && m.thickness > 0.0f;
  f.alphaMode = static_cast<uint32_t>(m.alphaMode);
  const bool mrTexture = hasTexture[static_cast<int>(TextureSlot::MetallicRoughness)];
  // A broad specular lobe on a dielectric (its share of the light is a few per cent): the
  // occlusion march of its diffuse lobe stands for both.
  f.broadLobe = !mrTexture && m.metallicFactor < 0.5f && m.roughnessFactor >= 0.75f;
  // Lobes broad enough for the area lights' per-view cache (a light's reflection in a smooth
  // surface is under a pixel: a cache of a few sub-pixel positions would lose it). Textures
  // scale roughness down, so a textured roughness is not known to be broad.
  const bool coatRoughnessTexture = hasTexture[static_cast<int>(TextureSlot::ClearcoatRoughness)];
  f.lightCacheable = !mrTexture && m.roughnessFactor >= kLightCacheMinRoughness &&
                     (m.clearcoat <= 0.0f ||
                      (!coatRoughnessTexture && m.clearcoatRoughness >= kLightCacheMinRoughness));
  return f;
}

}  // namespace penumbra
