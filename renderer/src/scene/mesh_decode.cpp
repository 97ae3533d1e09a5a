// Compressed geometry: EXT_meshopt_compression buffer views and KHR_draco_mesh_compression
// primitives. The checks, the conversions and the messages are here, shared by both builds;
// the decoding itself is behind mesh_decode_backend.h (libraries natively, the npm decoders
// in the browser).
#include <cstring>

#include "scene/gltf_document.h"
#include "scene/mesh_decode_backend.h"

namespace penumbra::gltf {

Status decodeMeshopt(const MeshoptDesc& d, std::span<const uint8_t> src, std::vector<uint8_t>& out,
                     const std::string& what, const LoadContext& ctx) {
  if (!hasMeshopt()) {
    return ctx.error(what + " uses EXT_meshopt_compression, and the meshopt decoder is not loaded");
  }
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
  switch (d.filter) {
    case MeshoptFilter::None:
      break;
    case MeshoptFilter::Octahedral:
      if (indexMode || (d.byteStride != 4 && d.byteStride != 8)) {
        return ctx.error(name + ": OCTAHEDRAL filter needs ATTRIBUTES with byteStride 4 or 8");
      }
      break;
    case MeshoptFilter::Quaternion:
      if (indexMode || d.byteStride != 8) {
        return ctx.error(name + ": QUATERNION filter needs ATTRIBUTES with byteStride 8");
      }
      break;
    case MeshoptFilter::Exponential:
      if (indexMode) return ctx.error(name + ": EXPONENTIAL filter needs ATTRIBUTES");
      break;
  }
  out.assign(static_cast<size_t>(d.count * d.byteStride), 0);
  const std::string failed = backend::meshoptDecode(d, src, out.data());
  if (!failed.empty()) {
    return ctx.error(name + ": the compressed data is malformed (" + failed + ")");
  }
  return {};
}

Result<DecodedDraco> decodeDraco(Document& doc, const PrimitiveDesc& prim, LoadContext& ctx,
                                 const std::string& what) {
  if (!hasDraco()) {
    return ctx.error(what +
                     " uses KHR_draco_mesh_compression, and the Draco decoder is not loaded");
  }
  const DracoDesc& d = *prim.draco;
  const std::string name = what + " (KHR_draco_mesh_compression)";
  auto view = viewBytes(doc, d.bufferView, ctx);
  if (!view.ok()) return view.error();
  std::string failed;
  std::unique_ptr<backend::DracoMesh> mesh =
      backend::dracoDecode({view->data, static_cast<size_t>(view->size)}, failed);
  if (!mesh) return ctx.error(name + ": Draco decoding failed (" + failed + ")");

  DecodedDraco out;
  out.vertexCount = mesh->points();
  uint64_t floatsPerVertex = 0;
  for (const auto& [attrName, id] : d.attributes) {
    auto acc = prim.attributes.find(attrName);
    if (acc != prim.attributes.end()) {
      floatsPerVertex +=
          static_cast<uint64_t>(doc.accessors[static_cast<size_t>(acc->second)].components);
    }
  }
  PN_TRY(
      ctx.reserve(out.vertexCount * floatsPerVertex * 4 + mesh->faces() * 12, name + " (decoded)"));

  for (const auto& [attrName, id] : d.attributes) {
    auto accIt = prim.attributes.find(attrName);
    if (accIt == prim.attributes.end()) {
      ctx.warn(name + ": attribute " + attrName + " is not in the primitive's attributes; ignored");
      continue;
    }
    const AccessorDesc& acc = doc.accessors[static_cast<size_t>(accIt->second)];
    if (!mesh->hasAttribute(id)) {
      return ctx.error(name + ": attribute " + attrName + " refers to Draco attribute id " +
                       std::to_string(id) + ", which the compressed mesh does not have");
    }
    if (acc.components > 4) {
      return ctx.error(name + ": attribute " + attrName + " has more than 4 components");
    }
    // Converted to the accessor's component type first (Draco's own conversion to float would
    // apply its normalisation flag, not the accessor's), then to floats by the same rules as an
    // uncompressed accessor.
    const size_t size = acc.componentType == kByte || acc.componentType == kUnsignedByte     ? 1
                        : acc.componentType == kShort || acc.componentType == kUnsignedShort ? 2
                                                                                             : 4;
    const auto points = static_cast<size_t>(out.vertexCount);
    const auto comps = static_cast<size_t>(acc.components);
    std::vector<uint8_t> tight(points * comps * size);
    if (!mesh->fetch(id, acc.componentType, acc.components, tight.data())) {
      return ctx.error(name + ": cannot convert Draco attribute " + attrName);
    }
    std::vector<float> values(points * comps);
    convertToFloat(tight.data(), size * comps, points, acc.componentType, acc.components,
                   acc.normalized, values.data());
    out.attributes[attrName] = std::move(values);
  }

  out.indices.resize(static_cast<size_t>(mesh->faces()) * 3);
  mesh->triangles(out.indices.data());
  return out;
}

}  // namespace penumbra::gltf
