// Materials, textures, samplers and images. Images are decoded to RGBA8 with stb_image (whose
// implementation lives in image/stb_impl.cpp), KTX2 images (KHR_texture_basisu) by the
// build's transcoder where it has one (ktx2_backend.h); a missing or undecodable image is a
// warning and a 1x1 placeholder, so a scene with a broken texture still renders.
#include <algorithm>
#include <cstring>

#include <stb_image.h>

#include "scene/gltf_document.h"
#include "scene/ktx2_backend.h"

namespace penumbra {

glm::vec3 Material::dielectricF0() const {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return glm::min(glm::vec3(r * r) * specularColorFactor, glm::vec3(1.0f)) * specularFactor;
}

namespace {
// One table: the slot's field, its glTF path and what it holds.
struct SlotEntry {
  TextureRef Material::*field;
  TextureSlotInfo info;
};
constexpr SlotEntry kSlots[kTextureSlotCount] = {
    {&Material::baseColorTexture, {"pbrMetallicRoughness.baseColorTexture", true, false}},
    {&Material::metallicRoughnessTexture,
     {"pbrMetallicRoughness.metallicRoughnessTexture", false, false}},
    {&Material::normalTexture, {"normalTexture", false, true}},
    {&Material::occlusionTexture, {"occlusionTexture", false, false}},
    {&Material::emissiveTexture, {"emissiveTexture", true, false}},
    {&Material::clearcoatNormalTexture,
     {"extensions.KHR_materials_clearcoat.clearcoatNormalTexture", false, true}},
    {&Material::clearcoatTexture,
     {"extensions.KHR_materials_clearcoat.clearcoatTexture", false, false}},
    {&Material::clearcoatRoughnessTexture,
     {"extensions.KHR_materials_clearcoat.clearcoatRoughnessTexture", false, false}},
    {&Material::sheenColorTexture,
     {"extensions.KHR_materials_sheen.sheenColorTexture", true, false}},
    {&Material::sheenRoughnessTexture,
     {"extensions.KHR_materials_sheen.sheenRoughnessTexture", false, false}},
    {&Material::specularTexture,
     {"extensions.KHR_materials_specular.specularTexture", false, false}},
    {&Material::specularColorTexture,
     {"extensions.KHR_materials_specular.specularColorTexture", true, false}},
    {&Material::transmissionTexture,
     {"extensions.KHR_materials_transmission.transmissionTexture", false, false}},
    {&Material::thicknessTexture,
     {"extensions.KHR_materials_volume.thicknessTexture", false, false}},
    {&Material::iridescenceTexture,
     {"extensions.KHR_materials_iridescence.iridescenceTexture", false, false}},
    {&Material::iridescenceThicknessTexture,
     {"extensions.KHR_materials_iridescence.iridescenceThicknessTexture", false, false}},
    {&Material::anisotropyTexture,
     {"extensions.KHR_materials_anisotropy.anisotropyTexture", false, false}},
    {&Material::diffuseTransmissionTexture,
     {"extensions.KHR_materials_diffuse_transmission.diffuseTransmissionTexture", false, false}},
    {&Material::diffuseTransmissionColorTexture,
     {"extensions.KHR_materials_diffuse_transmission.diffuseTransmissionColorTexture", true,
      false}},
};
}  // namespace

TextureRef& Material::texture(TextureSlot slot) {
  return this->*kSlots[static_cast<size_t>(slot)].field;
}
const TextureRef& Material::texture(TextureSlot slot) const {
  return this->*kSlots[static_cast<size_t>(slot)].field;
}
const TextureSlotInfo& textureSlotInfo(TextureSlot slot) {
  return kSlots[static_cast<size_t>(slot)].info;
}

}  // namespace penumbra

namespace penumbra::gltf {
namespace {

constexpr int kUsedOther = 1;
constexpr int kUsedAsNormal = 2;
constexpr int kUsedLayered = 4;  // by an extension slot: a texture array's layer, so RGBA8

ImageData placeholder(const std::string& name, bool normalMap) {
  ImageData img;
  img.name = name;
  img.width = 1;
  img.height = 1;
  img.placeholder = true;
  // A flat tangent-space normal keeps a broken normal map from bending the shading.
  img.pixels = normalMap ? std::vector<uint8_t>{128, 128, 255, 255}
                         : std::vector<uint8_t>{255, 255, 255, 255};
  return img;
}

// Halves both sides (rounding up) with a box filter. Averaging sRGB-encoded texels is a small
// error for colour textures, accepted here because this only runs for oversized inputs.
void halve(ImageData& img) {
  const int w = img.width, h = img.height;
  const int nw = std::max(1, (w + 1) / 2), nh = std::max(1, (h + 1) / 2);
  std::vector<uint8_t> out(static_cast<size_t>(nw) * static_cast<size_t>(nh) * 4);
  for (int y = 0; y < nh; ++y) {
    const int y0 = std::min(2 * y, h - 1), y1 = std::min(2 * y + 1, h - 1);
    for (int x = 0; x < nw; ++x) {
      const int x0 = std::min(2 * x, w - 1), x1 = std::min(2 * x + 1, w - 1);
      for (int c = 0; c < 4; ++c) {
        auto at = [&](int xx, int yy) {
          return static_cast<int>(img.pixels[(static_cast<size_t>(yy) * static_cast<size_t>(w) +
                                              static_cast<size_t>(xx)) *
                                                 4 +
                                             static_cast<size_t>(c)]);
        };
        const int sum = at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1);
        out[(static_cast<size_t>(y) * static_cast<size_t>(nw) + static_cast<size_t>(x)) * 4 +
            static_cast<size_t>(c)] = static_cast<uint8_t>((sum + 2) / 4);
      }
    }
  }
  img.width = nw;
  img.height = nh;
  img.pixels = std::move(out);
}

// stb_image grows its IDAT buffer to whatever length a PNG chunk header claims before it
// checks that the bytes exist, so a corrupt length would allocate gigabytes. Walk the chunks
// first and refuse any that runs past the end of the data.
bool pngChunksFit(const uint8_t* data, uint64_t size) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < 8 || std::memcmp(data, kSignature, 8) != 0) return true;  // not a PNG
  uint64_t pos = 8;
  while (pos + 12 <= size) {
    const uint64_t length = (uint64_t{data[pos]} << 24) | (uint64_t{data[pos + 1]} << 16) |
                            (uint64_t{data[pos + 2]} << 8) | data[pos + 3];
    if (length > size - pos - 12) return false;
    if (std::memcmp(data + pos + 4, "IEND", 4) == 0) return true;
    pos += 12 + length;
  }
  return false;  // no IEND
}

// The size a PNG's IHDR declares (0 x 0 when it is not a PNG with an IHDR first): stb_image
// refuses very large PNGs as an "unknown image type", which hides the real problem.
std::pair<uint32_t, uint32_t> pngDeclaredSize(const uint8_t* data, uint64_t size) {
  static const uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size < 24 || std::memcmp(data, kSignature, 8) != 0 || std::memcmp(data + 12, "IHDR", 4)) {
    return {0, 0};
  }
  auto be32 = [&](uint64_t at) {
    return (uint32_t{data[at]} << 24) | (uint32_t{data[at + 1]} << 16) |
           (uint32_t{data[at + 2]} << 8) | data[at + 3];
  };
  return {be32(16), be32(20)};
}

// Halves an image until it fits the maximum texture size (a warning says so).
ImageData fitToMaxSize(ImageData img, const std::string& what, LoadContext& ctx) {
  const int maxSize = std::max(1, ctx.options.maxTextureSize);
  const int dw = img.width, dh = img.height;
  if (img.width > maxSize || img.height > maxSize) {
    while (img.width > maxSize || img.height > maxSize) halve(img);
    ctx.warn(what + ": " + std::to_string(dw) + "x" + std::to_string(dh) +
             " is larger than the maximum texture size " + std::to_string(maxSize) +
             "; downscaled to " + std::to_string(img.width) + "x" + std::to_string(img.height));
  }
  return img;
}

Result<ImageData> decodeImage(Document& doc, int index, bool normalOnly, bool blocks,
                              LoadContext& ctx) {
  const ImageDesc& desc = doc.images[static_cast<size_t>(index)];
  std::string label = desc.name;
  if (label.empty() && !desc.uri.empty() && !isDataUri(desc.uri)) label = desc.uri;
  if (label.empty()) label = "image " + std::to_string(index);
  std::string what = "image " + std::to_string(index);
  if (!desc.uri.empty() && !isDataUri(desc.uri)) {
    what += " ('" + desc.uri + "')";
  } else if (!desc.name.empty()) {
    what += " ('" + desc.name + "')";
  }

  std::vector<uint8_t> owned;
  const uint8_t* data = nullptr;
  uint64_t size = 0;
  if (desc.bufferView >= 0) {
    auto view = viewBytes(doc, desc.bufferView, ctx);
    if (!view.ok()) return view.error();
    data = view->data;
    size = view->size;
  } else {
    const uint64_t left = static_cast<uint64_t>(
        std::max<int64_t>(ctx.options.memoryBudgetBytes - ctx.bytesReserved, 0));
    auto bytes = readUri(desc.uri, what, ctx, left);
    if (!bytes.ok()) {
      // The message already names the file; keep only the reason after "<file>: ".
      std::string reason = bytes.message();
      if (reason.rfind(ctx.name + ": ", 0) == 0) reason = reason.substr(ctx.name.size() + 2);
      ctx.warn(reason + "; using a 1x1 placeholder");
      return placeholder(label, normalOnly);
    }
    owned = std::move(bytes).value();
    data = owned.data();
    size = owned.size();
  }

  if (backend::isKtx2({data, static_cast<size_t>(size)})) {
    // KHR_texture_basisu: transcoded where the build can (the browser), to a GPU block format
    // (kept as it is: compressed data cannot be halved) or to RGBA8.
    ImageData img;
    img.name = label;
    const std::string why =
        backend::ktx2Available()
            ? backend::ktx2Transcode({data, static_cast<size_t>(size)}, uint64_t{1} << 28,
                                     std::max(1, ctx.options.maxTextureSize), blocks, img)
            : "this build has no KTX2 transcoder";
    if (!why.empty()) {
      ctx.warn(what + ": cannot decode KTX2 (" + why + "); using a 1x1 placeholder");
      return placeholder(label, normalOnly);
    }
    uint64_t bytes = img.pixels.size();
    for (const auto& level : img.compressedLevels) bytes += level.size();
    PN_TRY(ctx.reserve(bytes, what + " (" + std::to_string(img.width) + "x" +
                                  std::to_string(img.height) +
                                  (img.compressedFormat ? " compressed)" : " RGBA8)")));
    if (img.compressedFormat != 0) return img;
    return fitToMaxSize(std::move(img), what, ctx);
  }
  if (!pngChunksFit(data, size)) {
    ctx.warn(what +
             ": cannot decode (corrupt PNG: a chunk runs past the end of the data); "
             "using a 1x1 placeholder");
    return placeholder(label, normalOnly);
  }
  int w = 0, h = 0, comp = 0;
  if (const auto [pw, ph] = pngDeclaredSize(data, size); uint64_t{pw} * ph > (uint64_t{1} << 28)) {
    ctx.warn(what + ": a " + std::to_string(pw) + "x" + std::to_string(ph) +
             " PNG is too large to decode (more than 2^28 pixels); using a 1x1 placeholder");
    return placeholder(label, normalOnly);
  }
  if (size == 0 || size > 0x7FFFFFFF ||
      !stbi_info_from_memory(data, static_cast<int>(size), &w, &h, &comp)) {
    ctx.warn(what + ": cannot decode (" + std::string(size == 0 ? "empty" : stbi_failure_reason()) +
             "); using a 1x1 placeholder");
    return placeholder(label, normalOnly);
  }
  PN_TRY(ctx.reserve(uint64_t(w) * uint64_t(h) * 4,
                     what + " (" + std::to_string(w) + "x" + std::to_string(h) + " RGBA8)"));
  int dw = 0, dh = 0;
  stbi_uc* pixels = stbi_load_from_memory(data, static_cast<int>(size), &dw, &dh, &comp, 4);
  if (!pixels) {
    ctx.warn(what + ": cannot decode (" + std::string(stbi_failure_reason()) +
             "); using a 1x1 placeholder");
    return placeholder(label, normalOnly);
  }
  ImageData img;
  img.name = label;
  img.width = dw;
  img.height = dh;
  img.pixels.assign(pixels, pixels + static_cast<size_t>(dw) * static_cast<size_t>(dh) * 4);
  stbi_image_free(pixels);

  return fitToMaxSize(std::move(img), what, ctx);
}

}  // namespace

Status convertMaterials(Document& doc, Scene& scene, LoadContext& ctx) {
  scene.samplers = doc.samplers;

  // KHR_texture_basisu: a texture's KTX2 image where this build transcodes it, else its
  // fallback `source` (a warning says which, once per texture).
  const bool ktx2 = backend::ktx2Available();
  for (size_t t = 0; t < doc.textures.size(); ++t) {
    TextureDesc& tex = doc.textures[t];
    if (tex.basisuSource < 0) continue;
    if (ktx2) {
      tex.source = tex.basisuSource;
    } else {
      ctx.warn("textures[" + std::to_string(t) +
               "]: KHR_texture_basisu (KTX2) is transcoded only by the browser build (Debian "
               "has no Basis Universal transcoder); " +
               (tex.source >= 0 ? "using its fallback image" : "it has no fallback image"));
    }
  }

  // Which images the materials use, and whether only as normal maps (for the placeholder).
  std::vector<int> use(doc.images.size(), 0);
  for (const MaterialDesc& md : doc.materials) {
    for (int slot = 0; slot < kTextureSlotCount; ++slot) {
      const int tex = md.textures[static_cast<size_t>(slot)].texture;
      if (tex < 0) continue;
      const int source = doc.textures[static_cast<size_t>(tex)].source;
      if (source < 0) continue;
      int& u = use[static_cast<size_t>(source)];
      u |= textureSlotInfo(static_cast<TextureSlot>(slot)).normalMap ? kUsedAsNormal : kUsedOther;
      if (slot >= kCoreTextureSlots) u |= kUsedLayered;
    }
  }
  std::vector<int> remap(doc.images.size(), -1);
  for (size_t i = 0; i < doc.images.size(); ++i) {
    if (!use[i]) continue;
    auto img = decodeImage(doc, static_cast<int>(i), (use[i] & kUsedOther) == 0,
                           (use[i] & kUsedLayered) == 0, ctx);
    if (!img.ok()) return img.error();
    remap[i] = static_cast<int>(scene.images.size());
    scene.images.push_back(std::move(img).value());
  }

  for (size_t mi = 0; mi < doc.materials.size(); ++mi) {
    const MaterialDesc& md = doc.materials[mi];
    Material m = md.material;
    for (int slot = 0; slot < kTextureSlotCount; ++slot) {
      const TextureInfoDesc& info = md.textures[static_cast<size_t>(slot)];
      if (info.texture < 0) continue;
      const std::string where = "materials[" + std::to_string(mi) + "]." +
                                textureSlotInfo(static_cast<TextureSlot>(slot)).path;
      const TextureDesc& tex = doc.textures[static_cast<size_t>(info.texture)];
      if (tex.source < 0) {
        ctx.warn(where + ": texture " + std::to_string(info.texture) +
                 " has no source this loader can decode; ignored");
        continue;
      }
      TextureRef& ref = m.texture(static_cast<TextureSlot>(slot));
      ref.image = remap[static_cast<size_t>(tex.source)];
      ref.sampler = tex.sampler;
      ref.texCoord = info.texCoord;
      ref.transform = info.transform;
      if (ref.texCoord > 1) {
        ctx.warn(where + ": TEXCOORD_" + std::to_string(ref.texCoord) +
                 " is not supported (only 0 and 1); using TEXCOORD_0");
        ref.texCoord = 0;
      }
    }
    // The extension textures share one texture array, so one sampler (gpu/gpu_scene.h).
    int firstSampler = -2;
    for (int slot = kCoreTextureSlots; slot < kTextureSlotCount; ++slot) {
      const TextureRef& ref = m.texture(static_cast<TextureSlot>(slot));
      if (!ref.valid()) continue;
      if (firstSampler == -2) {
        firstSampler = ref.sampler;
      } else if (ref.sampler != firstSampler) {
        ctx.warn("materials[" + std::to_string(mi) +
                 "]: its extension textures use different samplers; the first one's applies "
                 "to all");
        break;
      }
    }
    scene.materials.push_back(std::move(m));
  }
  return {};
}

}  // namespace penumbra::gltf
