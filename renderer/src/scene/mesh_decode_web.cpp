// The browser's decoders behind mesh_decode.cpp: the meshoptimizer decoder and Google's Draco
// glTF decoder, both from npm. web/lib/decoders.mjs loads them (only for a file that uses the
// extensions) and sets Module.penumbraDecoders = {meshopt, draco} before the load runs; the
// calls below are synchronous, so the C++ loader decodes exactly where it does natively.
#include <emscripten/emscripten.h>

#include <vector>

#include "scene/mesh_decode_backend.h"

// clang-format off
EM_JS(int, pn_decoder_loaded, (int draco), {
  const d = Module["penumbraDecoders"];
  return d && d[draco ? "draco" : "meshopt"] ? 1 : 0;
});

EM_JS(int, pn_meshopt_decode, (uint8_t* out, double count, int stride, const uint8_t* src,
                               double srcLen, int mode, int filter, char* err, int cap), {
  try {
    const target = HEAPU8.subarray(out >>> 0, (out >>> 0) + count * stride);
    const source = HEAPU8.subarray(src >>> 0, (src >>> 0) + srcLen);
    Module["penumbraDecoders"]["meshopt"].decodeGltfBuffer(
        target, count, stride, source, ["ATTRIBUTES", "TRIANGLES", "INDICES"][mode],
        ["NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"][filter]);
    return 1;
  } catch (e) {
    stringToUTF8(String(e && e.message ? e.message : e).split("\n")[0], err, cap);
    return 0;
  }
});

// Decodes a Draco mesh and keeps it (with its decoder) under a handle > 0; 0 on failure.
EM_JS(int, pn_draco_open, (const uint8_t* src, double len, char* err, int cap), {
  const draco = Module["penumbraDecoders"]["draco"];
  const decoder = new draco.Decoder();
  const mesh = new draco.Mesh();
  let failed = "";
  try {
    const data = new Int8Array(HEAPU8.buffer, src >>> 0, len).slice();
    const status = decoder.DecodeArrayToMesh(data, len, mesh);
    if (!status.ok()) failed = status.error_msg();
    else if (mesh.ptr === 0) failed = "no mesh";
    draco.destroy(status);
  } catch (e) {
    failed = e;
  }
  if (failed) {
    draco.destroy(mesh);
    draco.destroy(decoder);
    stringToUTF8(String(failed && failed.message ? failed.message : failed).split("\n")[0], err,
                 cap);
    return 0;
  }
  const meshes = Module["penumbraDracoMeshes"] || (Module["penumbraDracoMeshes"] = new Map());
  const id = (Module["penumbraDracoNext"] = (Module["penumbraDracoNext"] || 0) + 1);
  meshes.set(id, { decoder, mesh });
  return id;
});

EM_JS(double, pn_draco_count, (int id, int faces), {
  const m = Module["penumbraDracoMeshes"].get(id);
  return faces ? m.mesh.num_faces() : m.mesh.num_points();
});

EM_JS(int, pn_draco_has_attribute, (int id, int uniqueId), {
  const m = Module["penumbraDracoMeshes"].get(id);
  return m.decoder.GetAttributeByUniqueId(m.mesh, uniqueId).ptr !== 0 ? 1 : 0;
});

// Every point's value as `comps` components of Draco data type `type` (size bytes each).
EM_JS(int, pn_draco_fetch, (int id, int uniqueId, int type, int size, int comps, uint8_t* out), {
  const draco = Module["penumbraDecoders"]["draco"];
  const m = Module["penumbraDracoMeshes"].get(id);
  const attr = m.decoder.GetAttributeByUniqueId(m.mesh, uniqueId);
  const types = [draco.DT_INT8, draco.DT_UINT8, draco.DT_INT16, draco.DT_UINT16, draco.DT_UINT32,
                 draco.DT_FLOAT32];
  const points = m.mesh.num_points();
  const have = attr.num_components();
  const bytes = points * have * size;
  const ptr = draco._malloc(bytes);
  try {
    if (!m.decoder.GetAttributeDataArrayForAllPoints(m.mesh, attr, types[type], bytes, ptr)) {
      return 0;
    }
    const values = new Uint8Array(draco.HEAPU8.buffer, ptr, bytes);
    const dst = out >>> 0;
    if (have === comps) {
      HEAPU8.set(values, dst);
    } else {
      // As PointAttribute::ConvertValue: missing components are 0, extra ones dropped.
      const keep = Math.min(have, comps) * size;
      HEAPU8.fill(0, dst, dst + points * comps * size);
      for (let i = 0; i < points; i++) {
        HEAPU8.set(values.subarray(i * have * size, i * have * size + keep), dst + i * comps * size);
      }
    }
    return 1;
  } finally {
    draco._free(ptr);
  }
});

EM_JS(void, pn_draco_triangles, (int id, uint32_t* out), {
  const draco = Module["penumbraDecoders"]["draco"];
  const m = Module["penumbraDracoMeshes"].get(id);
  const bytes = m.mesh.num_faces() * 12;
  const ptr = draco._malloc(bytes);
  m.decoder.GetTrianglesUInt32Array(m.mesh, bytes, ptr);
  HEAPU8.set(new Uint8Array(draco.HEAPU8.buffer, ptr, bytes), out >>> 0);
  draco._free(ptr);
});

EM_JS(void, pn_draco_close, (int id), {
  const draco = Module["penumbraDecoders"]["draco"];
  const m = Module["penumbraDracoMeshes"].get(id);
  Module["penumbraDracoMeshes"].delete(id);
  draco.destroy(m.mesh);
  draco.destroy(m.decoder);
});
// clang-format on

namespace penumbra::gltf {

bool hasMeshopt() {
  return pn_decoder_loaded(0) != 0;
}
bool hasDraco() {
  return pn_decoder_loaded(1) != 0;
}

namespace backend {
namespace {

constexpr int kErrorBytes = 256;

class WebDracoMesh final : public DracoMesh {
 public:
  explicit WebDracoMesh(int id)
      : id_(id),
        points_(static_cast<uint64_t>(pn_draco_count(id, 0))),
        faces_(static_cast<uint64_t>(pn_draco_count(id, 1))) {}
  ~WebDracoMesh() override { pn_draco_close(id_); }
  WebDracoMesh(const WebDracoMesh&) = delete;
  WebDracoMesh& operator=(const WebDracoMesh&) = delete;
  uint64_t points() const override { return points_; }
  uint64_t faces() const override { return faces_; }
  bool hasAttribute(int uniqueId) const override {
    return pn_draco_has_attribute(id_, uniqueId) != 0;
  }
  bool fetch(int uniqueId, int componentType, int components, void* out) override {
    int type = 5;  // DT_FLOAT32
    int size = 4;
    switch (componentType) {
      case kByte:
        type = 0, size = 1;
        break;
      case kUnsignedByte:
        type = 1, size = 1;
        break;
      case kShort:
        type = 2, size = 2;
        break;
      case kUnsignedShort:
        type = 3, size = 2;
        break;
      case kUnsignedInt:
        type = 4, size = 4;
        break;
      default:
        break;
    }
    return pn_draco_fetch(id_, uniqueId, type, size, components, static_cast<uint8_t*>(out)) != 0;
  }
  void triangles(uint32_t* out) override { pn_draco_triangles(id_, out); }

 private:
  int id_;
  uint64_t points_;
  uint64_t faces_;
};

}  // namespace

std::string meshoptDecode(const MeshoptDesc& d, std::span<const uint8_t> src, uint8_t* out) {
  char err[kErrorBytes] = {};
  if (pn_meshopt_decode(out, static_cast<double>(d.count), static_cast<int>(d.byteStride),
                        src.data(), static_cast<double>(src.size()), static_cast<int>(d.mode),
                        static_cast<int>(d.filter), err, kErrorBytes) == 0) {
    return err[0] ? err : "meshopt decoder error";
  }
  return {};
}

std::unique_ptr<DracoMesh> dracoDecode(std::span<const uint8_t> src, std::string& error) {
  char err[kErrorBytes] = {};
  const int id = pn_draco_open(src.data(), static_cast<double>(src.size()), err, kErrorBytes);
  if (id == 0) {
    error = err[0] ? err : "Draco decoder error";
    return nullptr;
  }
  return std::make_unique<WebDracoMesh>(id);
}

}  // namespace backend
}  // namespace penumbra::gltf
