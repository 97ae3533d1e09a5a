// Compressed geometry: EXT_meshopt_compression buffer views and KHR_draco_mesh_compression
// primitives. Both libraries exist only natively (Debian packages); the web build reports a
// clear error instead (or reads the uncompressed fallback data where the file has it).
#include <cstring>

#if defined(PENUMBRA_HAS_MESHOPT)
#include <meshoptimizer.h>
#endif
#if defined(PENUMBRA_HAS_DRACO)
#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#endif

#include "scene/gltf_document.h"

namespace penumbra::gltf {

bool hasMeshopt() {
#if defined(PENUMBRA_HAS_MESHOPT)
  return true;
#else
  return false;
#endif
}

bool hasDraco() {
#if defined(PENUMBRA_HAS_DRACO)
  return true;
#else
  return false;
#endif
}

Status decodeMeshopt(const MeshoptDesc& d, std::span<const uint8_t> src, std::vector<uint8_t>& out,
                     const std::string& what, const LoadContext& ctx) {
#if defined(PENUMBRA_HAS_MESHOPT)
  const std::string name = what + " (EXT_meshopt_compression)";
  if (d.count > 0xFFFFFFFFull) return ctx.error(name + ": absurd count " + std::to_string(d.count));
  // The library asserts on these instead of returning an error, so check them first.
  const bool indexMode = d.mode != MeshoptMode::Attributes;
  if (indexMode && d.byteStride != 2 && d.byteStride != 4) {
    return ctx.error(name + ": index byteStride must be 2 or 4, not " +
                     std::to_string(d.byteStride));
  }
  if (!indexMode && (d.byteStride % 4 != 0 || d.byteStride > 256)) {
    return ctx.error(name + ": attribute byteStride must be a multiple of 4 up to 256, not " +
                     std::to_string(d.byteStride));
  }
  if (d.mode == MeshoptMode::Triangles && d.count % 3 != 0) {
    return ctx.error(name + ": TRIANGLES count " + std::to_string(d.count) +
                     " is not a multiple of 3");
  }
  out.assign(static_cast<size_t>(d.count * d.byteStride), 0);
  const auto count = static_cast<size_t>(d.count);
  const auto stride = static_cast<size_t>(d.byteStride);
  int rc = 0;
  switch (d.mode) {
    case MeshoptMode::Attributes:
      rc = meshopt_decodeVertexBuffer(out.data(), count, stride, src.data(), src.size());
      break;
    case MeshoptMode::Triangles:
      rc = meshopt_decodeIndexBuffer(out.data(), count, stride, src.data(), src.size());
      break;
    case MeshoptMode::Indices:
      rc = meshopt_decodeIndexSequence(out.data(), count, stride, src.data(), src.size());
      break;
  }
  if (rc != 0) {
    return ctx.error(name + ": the compressed data is malformed (meshopt error " +
                     std::to_string(rc) + ")");
  }
  switch (d.filter) {
    case MeshoptFilter::None:
      break;
    case MeshoptFilter::Octahedral:
      if (indexMode || (stride != 4 && stride != 8)) {
        return ctx.error(name + ": OCTAHEDRAL filter needs ATTRIBUTES with byteStride 4 or 8");
      }
      meshopt_decodeFilterOct(out.data(), count, stride);
      break;
    case MeshoptFilter::Quaternion:
      if (indexMode || stride != 8) {
        return ctx.error(name + ": QUATERNION filter needs ATTRIBUTES with byteStride 8");
      }
      meshopt_decodeFilterQuat(out.data(), count, stride);
      break;
    case MeshoptFilter::Exponential:
      if (indexMode) return ctx.error(name + ": EXPONENTIAL filter needs ATTRIBUTES");
      meshopt_decodeFilterExp(out.data(), count, stride);
      break;
  }
  return {};
#else
  (void)d;
  (void)src;
  (void)out;
  return ctx.error(what + " uses EXT_meshopt_compression, which is not supported in the web build");
#endif
}

#if defined(PENUMBRA_HAS_DRACO)
namespace {

// Converts a Draco attribute to the accessor's component type first (Draco's own conversion
// to float would apply its normalisation flag, not the accessor's), then to floats by the same
// rules as an uncompressed accessor.
template <class T>
bool fetchAttribute(const draco::Mesh& mesh, const draco::PointAttribute& attr,
                    const AccessorDesc& acc, std::vector<float>& out) {
  const auto points = static_cast<size_t>(mesh.num_points());
  const auto comps = static_cast<size_t>(acc.components);
  std::vector<T> tight(points * comps);
  for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
    if (!attr.ConvertValue<T>(attr.mapped_index(i), static_cast<int8_t>(comps),
                              tight.data() + i.value() * comps)) {
      return false;
    }
  }
  out.resize(points * comps);
  convertToFloat(reinterpret_cast<const uint8_t*>(tight.data()), sizeof(T) * comps, points,
                 acc.componentType, acc.components, acc.normalized, out.data());
  return true;
}

}  // namespace
#endif

Result<DecodedDraco> decodeDraco(Document& doc, const PrimitiveDesc& prim, LoadContext& ctx,
                                 const std::string& what) {
#if defined(PENUMBRA_HAS_DRACO)
  const DracoDesc& d = *prim.draco;
  const std::string name = what + " (KHR_draco_mesh_compression)";
  auto view = viewBytes(doc, d.bufferView, ctx);
  if (!view.ok()) return view.error();
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(view->data), static_cast<size_t>(view->size));
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) {
    return ctx.error(name + ": Draco decoding failed (" + decoded.status().error_msg_string() +
                     ")");
  }
  std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) return ctx.error(name + ": Draco decoding produced no mesh");

  DecodedDraco out;
  out.vertexCount = mesh->num_points();
  uint64_t floatsPerVertex = 0;
  for (const auto& [attrName, id] : d.attributes) {
    auto acc = prim.attributes.find(attrName);
    if (acc != prim.attributes.end()) {
      floatsPerVertex +=
          static_cast<uint64_t>(doc.accessors[static_cast<size_t>(acc->second)].components);
    }
  }
  PN_TRY(ctx.reserve(out.vertexCount * floatsPerVertex * 4 + uint64_t{mesh->num_faces()} * 12,
                     name + " (decoded)"));

  for (const auto& [attrName, id] : d.attributes) {
    auto accIt = prim.attributes.find(attrName);
    if (accIt == prim.attributes.end()) {
      ctx.warn(name + ": attribute " + attrName + " is not in the primitive's attributes; ignored");
      continue;
    }
    const AccessorDesc& acc = doc.accessors[static_cast<size_t>(accIt->second)];
    const draco::PointAttribute* attr = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(id));
    if (!attr) {
      return ctx.error(name + ": attribute " + attrName + " refers to Draco attribute id " +
                       std::to_string(id) + ", which the compressed mesh does not have");
    }
    if (acc.components > 4) {
      return ctx.error(name + ": attribute " + attrName + " has more than 4 components");
    }
    std::vector<float> values;
    bool ok = false;
    switch (acc.componentType) {
      case kByte:
        ok = fetchAttribute<int8_t>(*mesh, *attr, acc, values);
        break;
      case kUnsignedByte:
        ok = fetchAttribute<uint8_t>(*mesh, *attr, acc, values);
        break;
      case kShort:
        ok = fetchAttribute<int16_t>(*mesh, *attr, acc, values);
        break;
      case kUnsignedShort:
        ok = fetchAttribute<uint16_t>(*mesh, *attr, acc, values);
        break;
      case kUnsignedInt:
        ok = fetchAttribute<uint32_t>(*mesh, *attr, acc, values);
        break;
      default:
        ok = fetchAttribute<float>(*mesh, *attr, acc, values);
        break;
    }
    if (!ok) return ctx.error(name + ": cannot convert Draco attribute " + attrName);
    out.attributes[attrName] = std::move(values);
  }

  out.indices.reserve(static_cast<size_t>(mesh->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f) {
    const draco::Mesh::Face& face = mesh->face(f);
    for (int k = 0; k < 3; ++k) out.indices.push_back(face[k].value());
  }
  return out;
#else
  (void)doc;
  (void)prim;
  return ctx.error(what +
                   " uses KHR_draco_mesh_compression, which is not supported in the web "
                   "build");
#endif
}

}  // namespace penumbra::gltf
