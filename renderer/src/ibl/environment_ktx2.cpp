// The prefiltered environment as a KTX 2.0 cube map for other engines (three.js's KTX2Loader,
// the glTF Sample Viewer, anything reading KTX2): VK_FORMAT_R16G16B16A16_SFLOAT, every mip of
// the specular chain, the packed manifest as key/value data. Debian has no KTX library (libktx
// is not packaged), so the container is written here, following the KTX 2.0 specification;
// the browser test reads it back with three.js and ktx-parse.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "image/image_internal.h"
#include "penumbra/environment_format.h"

namespace penumbra {
namespace {

constexpr uint8_t kIdentifier[12] = {0xAB, 'K',  'T',  'X',  ' ',  '2',
                                     '0',  0xBB, '\r', '\n', 0x1A, '\n'};
constexpr uint32_t kVkFormatR16G16B16A16Sfloat = 97;
constexpr uint32_t kHeaderBytes = 80;  // identifier, 9 words, the index (2 + 2 words, 2 longs)

struct Bytes {
  std::vector<uint8_t> data;
  void u32(uint32_t v) {
    for (int i = 0; i < 4; ++i) data.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void u64(uint64_t v) {
    for (int i = 0; i < 8; ++i) data.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  void u16(uint16_t v) {
    data.push_back(static_cast<uint8_t>(v));
    data.push_back(static_cast<uint8_t>(v >> 8));
  }
  void pad(size_t alignment) {
    while (data.size() % alignment != 0) data.push_back(0);
  }
  void put32(size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) data[at + i] = static_cast<uint8_t>(v >> (8 * i));
  }
  void put64(size_t at, uint64_t v) {
    for (int i = 0; i < 8; ++i) data[at + i] = static_cast<uint8_t>(v >> (8 * i));
  }
};

// The data format descriptor: one basic block, RGBA linear BT.709, four signed 16-bit float
// samples (KTX 2.0 section 3.10; Khronos Data Format 1.3 sections 5 and 15).
void writeDfd(Bytes& b) {
  constexpr uint32_t kSamples = 4, kBlockBytes = 24 + 16 * kSamples;
  b.u32(4 + kBlockBytes);        // dfdTotalSize
  b.u32(0);                      // vendorId 0 (Khronos), descriptorType 0 (basic)
  b.u32(2 | kBlockBytes << 16);  // versionNumber 2 (KDF 1.3), descriptorBlockSize
  b.u32(1 | 1 << 8 | 1 << 16);   // colorModel RGBSDA, primaries BT709, transfer LINEAR, flags 0
  b.u32(0);                      // texel block 1x1x1x1 (stored minus one)
  b.u32(8);                      // bytesPlane0: 8 bytes a texel
  b.u32(0);                      // bytesPlane4..7
  constexpr uint8_t kChannels[kSamples] = {0, 1, 2, 15};  // R, G, B, alpha
  for (uint32_t s = 0; s < kSamples; ++s) {
    // bitOffset, bitLength - 1, channel | FLOAT (0x80) | SIGNED (0x40).
    b.u32(16 * s | 15u << 16 | static_cast<uint32_t>(kChannels[s] | 0xC0) << 24);
    b.u32(0);           // sample position
    b.u32(0xBF800000);  // sampleLower -1.0f, sampleUpper 1.0f: the float formats' convention
    b.u32(0x3F800000);
  }
}

// Key/value pairs sorted by key, each value NUL-terminated, each entry padded to 4 bytes.
void writeKeyValues(Bytes& b, std::vector<std::pair<std::string, std::string>> kv) {
  std::sort(kv.begin(), kv.end());
  for (const auto& [key, value] : kv) {
    b.u32(static_cast<uint32_t>(key.size() + 1 + value.size() + 1));
    b.data.insert(b.data.end(), key.begin(), key.end());
    b.data.push_back(0);
    b.data.insert(b.data.end(), value.begin(), value.end());
    b.data.push_back(0);
    b.pad(4);
  }
}

}  // namespace

Result<std::vector<uint8_t>> encodeKtx2Environment(const PackedEnvironment& env) {
  auto manifest = packedManifestJson(env);
  if (!manifest) return manifest.error();
  const ibl::Cubemap& cube = env.specular;
  const int levels = cube.mipCount();
  Bytes b;
  b.data.insert(b.data.end(), std::begin(kIdentifier), std::end(kIdentifier));
  b.u32(kVkFormatR16G16B16A16Sfloat);
  b.u32(2);  // typeSize: 16-bit components
  b.u32(static_cast<uint32_t>(cube.size));
  b.u32(static_cast<uint32_t>(cube.size));
  b.u32(0);  // pixelDepth: 2D faces
  b.u32(0);  // layerCount: not an array
  b.u32(6);  // faceCount
  b.u32(static_cast<uint32_t>(levels));
  b.u32(0);  // no supercompression
  const size_t index = b.data.size();
  b.data.resize(kHeaderBytes + 24 * static_cast<size_t>(levels), 0);  // index, level index

  const size_t dfd = b.data.size();
  writeDfd(b);
  b.put32(index, static_cast<uint32_t>(dfd));
  b.put32(index + 4, static_cast<uint32_t>(b.data.size() - dfd));
  const size_t kvd = b.data.size();
  writeKeyValues(b, {{"KTXwriter", env.generator.empty() ? "penumbra" : env.generator},
                     {std::string(kKtx2ManifestKey), *manifest}});
  b.put32(index + 8, static_cast<uint32_t>(kvd));
  b.put32(index + 12, static_cast<uint32_t>(b.data.size() - kvd));
  // (No supercompression global data: its offset and length stay 0.)

  // Levels smallest first, as the specification recommends; each starts on 8 bytes (the texel
  // size). Within a level: faces +X -X +Y -Y +Z -Z, rows from t = 0, as GL and Vulkan upload.
  for (int m = levels - 1; m >= 0; --m) {
    b.pad(8);
    const size_t start = b.data.size();
    for (int f = 0; f < ibl::kFaceCount; ++f) {
      const Image& face = cube.face(m, f);
      for (int i = 0; i < face.width * face.height; ++i) {
        const float* px = &face.pixels[static_cast<size_t>(i) * face.channels];
        for (int c = 0; c < 3; ++c) b.u16(glm::packHalf1x16(face.channels > c ? px[c] : px[0]));
        b.u16(glm::packHalf1x16(1.0f));
      }
    }
    const uint64_t length = b.data.size() - start;
    const size_t entry = kHeaderBytes + 24 * static_cast<size_t>(m);
    b.put64(entry, start);
    b.put64(entry + 8, length);
    b.put64(entry + 16, length);
  }
  return std::move(b.data);
}

Status writeKtx2Environment(const std::string& path, const PackedEnvironment& env) {
  auto bytes = encodeKtx2Environment(env);
  if (!bytes) return makeError("cannot write '" + path + "': " + bytes.message());
  return detail::writeFileAtomic(path, *bytes);
}

}  // namespace penumbra
