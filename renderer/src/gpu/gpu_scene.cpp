#include "gpu/gpu_scene.h"

#include <algorithm>
#include <map>
#include <span>
#include <string>
#include <tuple>

#include "scene/mesh_lod.h"

namespace penumbra {
namespace {

constexpr int kPosition = 0, kNormal = 1, kTangent = 2, kUv0 = 3, kUv1 = 4, kColor = 5;

template <class T>
Status addAttribute(GpuPrimitive& p, int location, const std::vector<T>& data, int components) {
  // A played primitive's position, normal and tangent are rewritten at every pose.
  const bool posed = p.deformation && location <= kTangent;
  if (posed) p.posedBuffer[location] = static_cast<int>(p.buffers.size());
  auto buf = gl::Buffer::create(posed ? gl::BufferKind::Feedback : gl::BufferKind::Vertex,
                                std::span<const T>(data));
  if (!buf) return buf.error();
  p.vao.setAttribute(location, *buf, components, gl::AttribType::Float, false, 0, 0);
  p.buffers.push_back(std::move(*buf));
  return {};
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
Result<std::unique_ptr<GpuPrimitive>> uploadPrimitive(const Primitive& prim, int mesh,
                                                      float meshScale, float sceneDiagonal) {
  auto p = std::make_unique<GpuPrimitive>();
  p->vao = gl::VertexArray::create();
  p->material = prim.material;
  p->ownMaterial = prim.material;
  p->variantMaterials = prim.variantMaterials;
  p->bounds = prim.bounds;
  p->indexCount = static_cast<int>(prim.indices.size());
  if (prim.deformation && prim.deformation->positions.size() == prim.positions.size()) {
    auto d = GpuDeformation::create(*prim.deformation, mesh);
    if (!d) return d.error();
    p->deformation = std::move(*d);
  }
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
      auto p = uploadPrimitive(prim, static_cast<int>(mi), meshScale[mi], sceneDiagonal);
      if (!p) return p.error();
      prims.push_back(p->get());
      if ((*p)->deformation) deformed_.push_back(p->get());
      primitives_.push_back(std::move(*p));
    }
    meshes_.push_back(std::move(prims));
  }
  return {};
}

Status GpuScene::buildDrawItems() {
  const int defaultMaterial = static_cast<int>(materials_.size()) - 1;
  opaque_.clear();
  blended_.clear();
  transmissive_.clear();
  bounds_ = Bounds();
  // Opaque primitives of one node's copies gather into one item: keyed by the node, the
  // primitive and what changes the draw state (winding, shadow casting).
  using CopyKey = std::tuple<int, const GpuPrimitive*, bool, bool>;
  std::map<CopyKey, size_t> copyItem;                 // -> index in opaque_
  std::vector<std::vector<glm::mat4>> copyWorlds;     // per index in opaque_ (copies only)
  for (const Instance& inst : instances_) {
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
      const Material& m = materials_[static_cast<size_t>(item.material)].source;
      item.castsShadow = inst.castsShadow && !(inst.lampFace && m.emits());
      const Bounds wb = p->bounds.transformed(inst.world);
      if (wb.valid()) {
        bounds_.extend(wb);
        item.center = wb.center();
      }
      const bool blend = m.alphaMode == AlphaMode::Blend;
      const bool transmits = !blend && !m.unlit && m.transmission > 0.0f;
      item.layer = static_cast<int>(opaque_.size() + blended_.size() + transmissive_.size());
      if (inst.copyOf >= 0 && !blend && !transmits) {
        const CopyKey key{inst.copyOf, p, item.mirrored, item.castsShadow};
        auto [it, added] = copyItem.emplace(key, opaque_.size());
        if (added) {
          item.model = glm::mat4(1.0f);
          item.normalMatrix = glm::mat3(1.0f);
          opaque_.push_back(item);
          copyWorlds.resize(opaque_.size());
        } else {
          ++opaque_[it->second].copies;
        }
        copyWorlds[it->second].push_back(inst.world);
        continue;
      }
      (transmits ? transmissive_ : blend ? blended_ : opaque_).push_back(item);
    }
  }
  // The copies' world matrices as rows (x, y and z of the affine transform), item by item.
  std::vector<float> rows;
  for (size_t i = 0; i < copyWorlds.size(); ++i) {
    if (copyWorlds[i].empty()) continue;
    if (copyWorlds[i].size() == 1) {  // a node of one copy: an ordinary item
      opaque_[i].model = copyWorlds[i][0];
      opaque_[i].normalMatrix = glm::transpose(glm::inverse(glm::mat3(copyWorlds[i][0])));
      continue;
    }
    opaque_[i].copyOffset = rows.size() * sizeof(float);
    for (const glm::mat4& w : copyWorlds[i]) {
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 4; ++c) rows.push_back(w[c][r]);
      }
    }
  }
  copyRows_ = gl::Buffer();
  if (!rows.empty()) {
    auto buffer = gl::Buffer::create(gl::BufferKind::Vertex, std::span<const float>(rows));
    if (!buffer) return buffer.error();
    copyRows_ = std::move(*buffer);
  }
  // Grouped by material features: each group is drawn with one specialised program. (BLEND
  // surfaces keep the scene's order; frame 1 sorts them back to front anyway.)
  const auto byFeatures = [this](const DrawItem& a, const DrawItem& b) {
    return material(a.material).features.order() < material(b.material).features.order();
  };
  std::stable_sort(opaque_.begin(), opaque_.end(), byFeatures);
  std::stable_sort(transmissive_.begin(), transmissive_.end(), byFeatures);
  return {};
}

Result<std::unique_ptr<GpuScene>> GpuScene::create(const Scene& scene) {
  auto gs = std::make_unique<GpuScene>();
  PN_TRY(gs->uploadMeshes(scene));
  PN_TRY(gs->uploadMaterials(scene));
  gs->instances_ = scene.instances;
  if (scene.rig) {
    for (const Rig::MeshLink& link : scene.rig->meshes) gs->skinOf_.push_back(link.skin);
  }
  gs->variantCount_ = static_cast<int>(scene.variants.size());
  PN_TRY(gs->buildDrawItems());
  return gs;
}

Status GpuScene::pose(const Pose& pose) {
  for (size_t i = 0; i < instances_.size() && i < pose.instanceWorld.size(); ++i) {
    instances_[i].world = pose.instanceWorld[i];
  }
  jointTextures_.resize(pose.joints.size());
  for (size_t s = 0; s < pose.joints.size(); ++s) {
    const std::vector<glm::mat4>& joints = pose.joints[s];
    if (joints.empty()) continue;
    gl::Texture2D& tex = jointTextures_[s];
    if (!tex || tex.height() != static_cast<int>(joints.size())) {
      gl::TextureDesc desc{.width = 3,
                           .height = static_cast<int>(joints.size()),
                           .format = gl::PixelFormat::RGBA32F};
      desc.sampler.minFilter = desc.sampler.magFilter = gl::Filter::Nearest;
      auto created = gl::Texture2D::create(desc);
      if (!created) return created.error();
      tex = std::move(*created);
    }
    // Rows of the affine part (deform.vert multiplies a row by the point).
    std::vector<glm::vec4> rows;
    rows.reserve(3 * joints.size());
    for (const glm::mat4& m : joints) {
      const glm::mat4 t = glm::transpose(m);
      rows.insert(rows.end(), {t[0], t[1], t[2]});
    }
    tex.upload(0, rows.data(), gl::DataType::Float);
  }
  for (GpuPrimitive* p : deformed_) {
    const GpuDeformation& d = *p->deformation;
    p->bounds = d.posedBounds(pose.weightsOf(d.mesh), pose.jointsOf(skinOf(d.mesh)));
  }
  return buildDrawItems();
}

Status GpuScene::selectVariant(int variant) {
  for (auto& p : primitives_) {
    p->material = variantMaterial(p->ownMaterial, p->variantMaterials, variant);
  }
  return buildDrawItems();
}

void GpuScene::bindTransform(const gl::Program& program, const DrawItem& item,
                             int instancesPerCopy) const {
  item.primitive->vao.setInstanceRows(kCopyRowsLocation, item.copies > 1 ? &copyRows_ : nullptr,
                                      item.copyOffset, instancesPerCopy);
  program.set("uModel", item.model);
  program.set("uNormalMatrix", item.normalMatrix);
  program.set("uLayer", item.layer);
  program.set("uIndirectEmission", item.castsShadow ? 1.0f : 0.0f);  // 0: a lamp's face
}

}  // namespace penumbra
