// Bytes in: the GLB container, files and data: URIs, buffers and buffer views. Every length
// that comes from the file is checked before it is used to index or allocate anything.
#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "scene/gltf_document.h"

namespace penumbra::gltf {

size_t componentSize(int componentType) {
  switch (componentType) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    case kUnsignedInt:
    case kFloat:
      return 4;
    default:
      return 0;
  }
}

Status LoadContext::reserve(uint64_t bytes, const std::string& what) {
  const uint64_t budget = static_cast<uint64_t>(std::max<int64_t>(options.memoryBudgetBytes, 0));
  const uint64_t used = static_cast<uint64_t>(bytesReserved);
  if (bytes > budget || used + bytes > budget) {
    return error(what + " needs " + std::to_string(bytes) + " bytes, over the memory budget (" +
                 std::to_string(budget) + " bytes, " + std::to_string(used) + " already used)");
  }
  bytesReserved += static_cast<int64_t>(bytes);
  return {};
}

void LoadContext::warn(const std::string& message) {
  warnings.push_back(name + ": " + message);
}

Error LoadContext::error(const std::string& message) const {
  return makeError(name + ": " + message);
}

namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;
constexpr uint32_t kChunkBin = 0x004E4942;

uint32_t readU32(const uint8_t* p) {
  // GLB is little-endian; assemble explicitly so big-endian hosts would read it right too.
  return uint32_t{p[0]} | (uint32_t{p[1]} << 8) | (uint32_t{p[2]} << 16) | (uint32_t{p[3]} << 24);
}

bool endsWithGlb(const std::string& name) {
  if (name.size() < 4) return false;
  std::string ext = name.substr(name.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".glb";
}

int base64Value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;  // '-' and '_': the URL-safe alphabet
  if (c == '/' || c == '_') return 63;
  return -1;
}

bool decodeBase64(std::string_view in, std::vector<uint8_t>& out) {
  out.clear();
  out.reserve(in.size() / 4 * 3 + 3);
  uint32_t acc = 0;
  int bits = 0;
  for (char c : in) {
    if (c == '=') break;
    if (c == '\r' || c == '\n' || c == ' ') continue;
    const int v = base64Value(c);
    if (v < 0) return false;
    acc = (acc << 6) | static_cast<uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<uint8_t>((acc >> bits) & 0xFF));
    }
  }
  return true;
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// URIs in glTF are percent-encoded ("my%20texture.png").
std::string percentDecode(const std::string& uri) {
  std::string out;
  out.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hexValue(uri[i + 1]) >= 0 &&
        hexValue(uri[i + 2]) >= 0) {
      out.push_back(static_cast<char>(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2])));
      i += 2;
    } else {
      out.push_back(uri[i]);
    }
  }
  return out;
}

}  // namespace

Result<Container> splitContainer(std::span<const uint8_t> bytes, const LoadContext& ctx) {
  Container c;
  const bool magic = bytes.size() >= 4 && readU32(bytes.data()) == kGlbMagic;
  if (!magic) {
    if (endsWithGlb(ctx.name)) {
      if (bytes.size() < 4) {
        return ctx.error("truncated .glb (" + std::to_string(bytes.size()) + " bytes)");
      }
      return ctx.error("not a binary glTF file (wrong magic; expected 'glTF')");
    }
    c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return c;
  }
  c.binary = true;
  if (bytes.size() < 12) {
    return ctx.error("truncated .glb (" + std::to_string(bytes.size()) +
                     " bytes, the header alone needs 12)");
  }
  const uint32_t version = readU32(bytes.data() + 4);
  const uint32_t length = readU32(bytes.data() + 8);
  if (version != 2) {
    return ctx.error("unsupported .glb container version " + std::to_string(version) +
                     " (only 2 is supported)");
  }
  if (length > bytes.size()) {
    return ctx.error("truncated .glb: the header declares " + std::to_string(length) +
                     " bytes but there are only " + std::to_string(bytes.size()));
  }
  uint64_t offset = 12;
  bool first = true;
  while (offset < length) {
    if (offset + 8 > length) return ctx.error("truncated .glb: incomplete chunk header");
    const uint32_t chunkLength = readU32(bytes.data() + offset);
    const uint32_t chunkType = readU32(bytes.data() + offset + 4);
    const uint64_t dataStart = offset + 8;
    if (dataStart + chunkLength > length) {
      return ctx.error("truncated .glb: a chunk of " + std::to_string(chunkLength) +
                       " bytes runs past the end of the file");
    }
    const uint8_t* data = bytes.data() + dataStart;
    if (first) {
      if (chunkType != kChunkJson) return ctx.error("malformed .glb: the first chunk is not JSON");
      c.json = std::string_view(reinterpret_cast<const char*>(data), chunkLength);
      first = false;
    } else if (chunkType == kChunkBin && c.bin.empty()) {
      c.bin = std::span<const uint8_t>(data, chunkLength);
    }
    // Unknown chunk types are skipped, as the specification asks.
    offset = dataStart + ((uint64_t{chunkLength} + 3) & ~uint64_t{3});
  }
  if (first) return ctx.error("malformed .glb: no JSON chunk");
  return c;
}

Result<std::vector<uint8_t>> readFileBytes(const std::string& path, const std::string& what,
                                           const LoadContext& ctx, uint64_t maxBytes) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || std::filesystem::is_directory(path, ec)) {
    return ctx.error(what + ": cannot open '" + path + "'");
  }
  if (size > maxBytes) {
    return ctx.error(what + ": '" + path + "' has " + std::to_string(size) +
                     " bytes, more than the memory budget allows");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return ctx.error(what + ": cannot open '" + path + "'");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0 &&
      !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size))) {
    return ctx.error(what + ": cannot read '" + path + "'");
  }
  return bytes;
}

bool isDataUri(const std::string& uri) {
  return uri.rfind("data:", 0) == 0;
}

Result<std::vector<uint8_t>> readUri(const std::string& uri, const std::string& what,
                                     LoadContext& ctx, uint64_t maxFileBytes) {
  if (isDataUri(uri)) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos) return ctx.error(what + ": malformed data: URI (no comma)");
    const std::string_view header(uri.data() + 5, comma - 5);
    const std::string_view payload(uri.data() + comma + 1, uri.size() - comma - 1);
    std::vector<uint8_t> out;
    if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
      if (!decodeBase64(payload, out)) return ctx.error(what + ": malformed base64 in data: URI");
    } else {
      const std::string text = percentDecode(std::string(payload));
      out.assign(text.begin(), text.end());
    }
    return out;
  }
  if (uri.find("://") != std::string::npos) {
    return ctx.error(what + ": cannot load remote URI '" + uri + "' (only files and data: URIs)");
  }
  const std::string decoded = percentDecode(uri);
  const std::filesystem::path path =
      ctx.baseDir.empty() ? std::filesystem::path(decoded)
                          : std::filesystem::path(ctx.baseDir) / std::filesystem::path(decoded);
  return readFileBytes(path.string(), what, ctx, maxFileBytes);
}

Status loadBuffers(Document& doc, std::span<const uint8_t> glbBin, LoadContext& ctx) {
  doc.bufferData.assign(doc.buffers.size(), {});
  doc.ownedBuffers.assign(doc.buffers.size(), {});
  for (size_t i = 0; i < doc.buffers.size(); ++i) {
    const BufferDesc& b = doc.buffers[i];
    const std::string what = "buffer " + std::to_string(i);
    if (!b.hasUri) {
      if (i == 0 && !glbBin.empty()) {
        if (b.byteLength > glbBin.size()) {
          return ctx.error(what + " declares " + std::to_string(b.byteLength) +
                           " bytes but the .glb BIN chunk has only " +
                           std::to_string(glbBin.size()));
        }
        // Already in memory (the caller's bytes): account for it, but do not copy.
        PN_TRY(ctx.reserve(b.byteLength, what));
        doc.bufferData[i] = glbBin.first(static_cast<size_t>(b.byteLength));
        continue;
      }
      if (b.meshoptFallback) continue;  // its views are all meshopt-compressed
      return ctx.error(what + " has no uri" + (i == 0 ? " and there is no .glb BIN chunk" : ""));
    }
    // Checked before anything is read, so a declared length in the gigabytes fails cleanly.
    PN_TRY(ctx.reserve(b.byteLength, what + " (byteLength)"));
    const uint64_t left = static_cast<uint64_t>(
        std::max<int64_t>(ctx.options.memoryBudgetBytes - ctx.bytesReserved, 0));
    auto data = readUri(b.uri, what, ctx, b.byteLength + left);
    if (!data.ok()) {
      if (b.meshoptFallback) continue;  // optional: the compressed views carry the data
      return data.error();
    }
    if (data->size() < b.byteLength) {
      return ctx.error(what + " ('" + (isDataUri(b.uri) ? std::string("data: URI") : b.uri) +
                       "') has " + std::to_string(data->size()) +
                       " bytes but declares byteLength " + std::to_string(b.byteLength));
    }
    data->resize(static_cast<size_t>(b.byteLength));
    doc.ownedBuffers[i] = std::move(data).value();
    doc.bufferData[i] = doc.ownedBuffers[i];
  }

  for (size_t v = 0; v < doc.bufferViews.size(); ++v) {
    const BufferViewDesc& view = doc.bufferViews[v];
    const std::string what = "bufferView " + std::to_string(v);
    if (view.meshopt) {
      const MeshoptDesc& m = *view.meshopt;
      const uint64_t size = doc.bufferData[static_cast<size_t>(m.buffer)].size();
      if (m.byteOffset > size || m.byteLength > size - m.byteOffset) {
        return ctx.error(what + " (EXT_meshopt_compression, offset " +
                         std::to_string(m.byteOffset) + ", length " + std::to_string(m.byteLength) +
                         ") is out of range of buffer " + std::to_string(m.buffer) + " (" +
                         std::to_string(size) + " bytes)");
      }
      continue;  // the fallback range may point at a buffer without data
    }
    const uint64_t size = doc.bufferData[static_cast<size_t>(view.buffer)].size();
    if (view.byteOffset > size || view.byteLength > size - view.byteOffset) {
      return ctx.error(what + " (offset " + std::to_string(view.byteOffset) + ", length " +
                       std::to_string(view.byteLength) + ") is out of range of buffer " +
                       std::to_string(view.buffer) + " (" + std::to_string(size) + " bytes)");
    }
  }
  return {};
}

Result<ViewBytes> viewBytes(Document& doc, int viewIndex, LoadContext& ctx) {
  const BufferViewDesc& view = doc.bufferViews[static_cast<size_t>(viewIndex)];
  const std::string what = "bufferView " + std::to_string(viewIndex);
  ViewBytes out;
  out.stride = view.byteStride;
  if (view.meshopt && hasMeshopt()) {
    auto it = doc.decodedViews.find(viewIndex);
    if (it == doc.decodedViews.end()) {
      const MeshoptDesc& m = *view.meshopt;
      PN_TRY(ctx.reserve(m.count * m.byteStride, what + " (decoded)"));
      std::vector<uint8_t> decoded;
      const auto& buffer = doc.bufferData[static_cast<size_t>(m.buffer)];
      PN_TRY(decodeMeshopt(
          m, buffer.subspan(static_cast<size_t>(m.byteOffset), static_cast<size_t>(m.byteLength)),
          decoded, what, ctx));
      it = doc.decodedViews.emplace(viewIndex, std::move(decoded)).first;
    }
    out.data = it->second.data();
    // The decoded data stands in for the view's byteLength bytes.
    out.size = std::min<uint64_t>(it->second.size(), view.byteLength);
    return out;
  }
  const auto& buffer = doc.bufferData[static_cast<size_t>(view.buffer)];
  if (view.meshopt && buffer.empty()) {
    return ctx.error(what +
                     " is EXT_meshopt_compression-compressed, the meshopt decoder is not "
                     "loaded, and its fallback buffer has no data");
  }
  if (view.meshopt &&
      (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset)) {
    return ctx.error(what + " is out of range of its fallback buffer " +
                     std::to_string(view.buffer));
  }
  out.data = buffer.data() + view.byteOffset;
  out.size = view.byteLength;
  return out;
}

}  // namespace penumbra::gltf
