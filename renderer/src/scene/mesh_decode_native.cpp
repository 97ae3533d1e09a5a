// The native decoders behind mesh_decode.cpp: Debian's meshoptimizer and libdraco.
#include <meshoptimizer.h>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>

#include "scene/mesh_decode_backend.h"

namespace penumbra::gltf {

bool hasMeshopt() {
  return true;
}
bool hasDraco() {
  return true;
}

namespace backend {

std::string meshoptDecode(const MeshoptDesc& d, std::span<const uint8_t> src, uint8_t* out) {
  const auto count = static_cast<size_t>(d.count);
  const auto stride = static_cast<size_t>(d.byteStride);
  int rc = 0;
  switch (d.mode) {
    case MeshoptMode::Attributes:
      rc = meshopt_decodeVertexBuffer(out, count, stride, src.data(), src.size());
      break;
    case MeshoptMode::Triangles:
      rc = meshopt_decodeIndexBuffer(out, count, stride, src.data(), src.size());
      break;
    case MeshoptMode::Indices:
      rc = meshopt_decodeIndexSequence(out, count, stride, src.data(), src.size());
      break;
  }
  if (rc != 0) return "meshopt error " + std::to_string(rc);
  // mesh_decode.cpp has checked that the filter fits the mode and stride.
  switch (d.filter) {
    case MeshoptFilter::None:
      break;
    case MeshoptFilter::Octahedral:
      meshopt_decodeFilterOct(out, count, stride);
      break;
    case MeshoptFilter::Quaternion:
      meshopt_decodeFilterQuat(out, count, stride);
      break;
    case MeshoptFilter::Exponential:
      meshopt_decodeFilterExp(out, count, stride);
      break;
  }
  return {};
}

namespace {

class NativeDracoMesh final : public DracoMesh {
 public:
  explicit NativeDracoMesh(std::unique_ptr<draco::Mesh> mesh) : mesh_(std::move(mesh)) {}
  uint64_t points() const override { return mesh_->num_points(); }
  uint64_t faces() const override { return mesh_->num_faces(); }
  bool hasAttribute(int uniqueId) const override { return attribute(uniqueId) != nullptr; }
  bool fetch(int uniqueId, int componentType, int components, void* out) override {
    const draco::PointAttribute& attr = *attribute(uniqueId);
    switch (componentType) {
      case kByte:
        return fetchAs(attr, components, static_cast<int8_t*>(out));
      case kUnsignedByte:
        return fetchAs(attr, components, static_cast<uint8_t*>(out));
      case kShort:
        return fetchAs(attr, components, static_cast<int16_t*>(out));
      case kUnsignedShort:
        return fetchAs(attr, components, static_cast<uint16_t*>(out));
      case kUnsignedInt:
        return fetchAs(attr, components, static_cast<uint32_t*>(out));
      default:
        return fetchAs(attr, components, static_cast<float*>(out));
    }
  }
  void triangles(uint32_t* out) override {
    for (draco::FaceIndex f(0); f < mesh_->num_faces(); ++f) {
      const draco::Mesh::Face& face = mesh_->face(f);
      for (int k = 0; k < 3; ++k) *out++ = face[k].value();
    }
  }

 private:
  const draco::PointAttribute* attribute(int uniqueId) const {
    return mesh_->GetAttributeByUniqueId(static_cast<uint32_t>(uniqueId));
  }
  template <class T>
  bool fetchAs(const draco::PointAttribute& attr, int components, T* out) const {
    const auto comps = static_cast<size_t>(components);
    for (draco::PointIndex i(0); i < mesh_->num_points(); ++i) {
      if (!attr.ConvertValue<T>(attr.mapped_index(i), static_cast<int8_t>(comps),
                                out + i.value() * comps)) {
        return false;
      }
    }
    return true;
  }

  std::unique_ptr<draco::Mesh> mesh_;
};

}  // namespace

std::unique_ptr<DracoMesh> dracoDecode(std::span<const uint8_t> src, std::string& error) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(src.data()), src.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    error = decoded.status().error_msg_string();
    return nullptr;
  }
  std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) {
    error = "no mesh";
    return nullptr;
  }
  return std::make_unique<NativeDracoMesh>(std::move(mesh));
}

}  // namespace backend
}  // namespace penumbra::gltf
