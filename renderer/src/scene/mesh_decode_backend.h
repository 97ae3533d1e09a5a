// The decoders behind mesh_decode.cpp, one implementation per build: natively Debian's
// libdraco and meshoptimizer (mesh_decode_native.cpp); in the browser the decoders their
// authors publish on npm (Google's Draco glTF decoder and the meshoptimizer decoder), which
// web/lib/decoders.mjs loads only when a file needs them and mesh_decode_web.cpp calls. The
// checks, conversions and messages around them are shared, so both builds read a compressed
// file the same way.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "scene/gltf_document.h"

namespace penumbra::gltf::backend {

// Decodes `d.count` elements of `d.byteStride` bytes into `out` (already that size) and applies
// d.filter. Returns an empty string, or the library's words for malformed data.
std::string meshoptDecode(const MeshoptDesc& d, std::span<const uint8_t> src, uint8_t* out);

// One decoded Draco mesh.
class DracoMesh {
 public:
  virtual ~DracoMesh() = default;
  virtual uint64_t points() const = 0;
  virtual uint64_t faces() const = 0;
  virtual bool hasAttribute(int uniqueId) const = 0;
  // Every point's value of attribute `uniqueId` as `components` values of the C type of
  // `componentType` (float for kFloat and anything unknown), converted by Draco
  // (PointAttribute::ConvertValue: missing components are 0, extra ones dropped). `out` holds
  // points() * components values.
  virtual bool fetch(int uniqueId, int componentType, int components, void* out) = 0;
  // faces() * 3 vertex indices.
  virtual void triangles(uint32_t* out) = 0;
};

// Decodes a Draco mesh; null with `error` set (the library's words) when it does not decode.
std::unique_ptr<DracoMesh> dracoDecode(std::span<const uint8_t> src, std::string& error);

}  // namespace penumbra::gltf::backend
