// GpuScene: a Scene uploaded to GL — one vertex array per primitive, textures created per
// (image, colour space) on first use, and a flat draw list of instances with their materials.
// Built once per scene; passes only read it.
#pragma once

#include <map>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.h"
#include "gl/program.h"
#include "gl/texture.h"
#include "gpu/gpu_deformation.h"
#include "gpu/material_features.h"
#include "penumbra/animation.h"
#include "penumbra/scene.h"

namespace penumbra {

struct GpuPrimitive {
  gl::VertexArray vao;
  std::vector<gl::Buffer> buffers;
  int indexCount = 0;
  // The probe captures' stand-in (scene/mesh_lod.h), after the primitive's own indices in the
  // same buffer; the primitive itself (offset 0) where it has none.
  int captureIndexCount = 0;
  size_t captureByteOffset = 0;
  int material = -1;  // the one shown: its own or the selected variant's
  int ownMaterial = -1;
  std::vector<int> variantMaterials;  // KHR_materials_variants, per variant
  Bounds bounds;  // at the current pose
  // Playback (Primitive::deformation): its rest data, and which of `buffers` hold the posed
  // position, normal and tangent (-1: none) that passes/deform_pass.cpp rewrites.
  std::unique_ptr<GpuDeformation> deformation;
  int posedBuffer[3] = {-1, -1, -1};
};

// A material's textures. The five core slots (TextureSlot::BaseColor..Emissive) are 2D
// textures, a sampler each, shared between materials and possibly block-compressed. The
// extension slots (clearcoat, sheen, specular, transmission, volume, iridescence,
// anisotropy, diffuse transmission) are layers of one RGBA8 texture array per material
// (uMaterialLayers): all of them cost one texture unit, which is what lets every
// KHR_materials_* texture be sampled within WebGL2's 16 (the environment, shadows, probes and
// caches take the others). Layers share the array's size, the largest
// of the material's extension images (smaller ones are resized on upload), and its sampler,
// the first extension texture's (the loader warns when the others differ); colour layers keep
// their sRGB bytes and are decoded in the shader.
struct GpuMaterial {
  Material source;
  // Core slots' textures; null = none.
  const gl::Texture2D* textures[kCoreTextureSlots] = {};
  // Extension slots' layers in `layers` (-1: none), indexed by TextureSlot.
  int layer[kTextureSlotCount] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1,
                                  -1, -1, -1, -1, -1, -1, -1, -1, -1};
  gl::Texture2DArray layers;
  // What the material uses (materialFeatures): the shading programs are specialised on it.
  MaterialFeatures features;
};

// mesh.vert's and shadow.vert's aCopyRow0..2: a copy's world matrix (DrawItem::copies).
inline constexpr int kCopyRowsLocation = 6;

struct DrawItem {
  const GpuPrimitive* primitive = nullptr;
  int material = 0;  // index into GpuScene::materials (the default material is last)
  glm::mat4 model{1.0f};
  glm::mat3 normalMatrix{1.0f};
  bool mirrored = false;  // negative determinant: front faces wind clockwise
  glm::vec3 center{0.0f};
  int layer = 0;  // index in the scene's draw order: the stochastic-coverage key (uLayer)
  // Instance::castsShadow: false exactly for an area light's visible face
  // (extras.area_light_proxy), whose emission also lights nothing else (the light does).
  bool castsShadow = true;
  // EXT_mesh_gpu_instancing: an opaque primitive of a node's copies is one item drawn `copies`
  // times (model and normalMatrix the identity; each copy's world matrix as three rows at
  // `copyOffset` in GpuScene's copy buffer). BLEND and transmissive copies stay one item each:
  // they are sorted or composed per surface.
  int copies = 1;
  size_t copyOffset = 0;
};

class GpuScene {
 public:
  static Result<std::unique_ptr<GpuScene>> create(const Scene& scene);

  const std::vector<DrawItem>& opaque() const { return opaque_; }
  const std::vector<DrawItem>& blended() const { return blended_; }
  // KHR_materials_transmission surfaces (not BLEND, not unlit): drawn after the opaque scene,
  // which they show through themselves; left out of the prepass and the probe captures.
  const std::vector<DrawItem>& transmissive() const { return transmissive_; }
  const GpuMaterial& material(int i) const { return materials_[static_cast<size_t>(i)]; }
  const Bounds& bounds() const { return bounds_; }
  // KHR_materials_variants: shows the variant's materials (-1: the primitives' own) by
  // rebuilding the draw lists; the buffers and textures stay.
  Status selectVariant(int variant);
  int variantCount() const { return variantCount_; }
  // Playback: moves the instances to the pose, uploads its joint matrices (jointTexture) and
  // takes its bounds; the posed vertices themselves are passes::DeformPass's to write.
  Status pose(const Pose& pose);
  const std::vector<GpuPrimitive*>& deformed() const { return deformed_; }
  // The skin posing Scene mesh `mesh` (-1: none).
  int skinOf(int mesh) const {
    return static_cast<size_t>(mesh) < skinOf_.size() ? skinOf_[static_cast<size_t>(mesh)] : -1;
  }
  // A skin's joint matrices at the pose, three RGBA32F texels (rows) per joint.
  const gl::Texture2D& jointTexture(int skin) const {
    return jointTextures_[static_cast<size_t>(skin)];
  }
  size_t textureCount() const { return textures_.size(); }

  // Sets the material uniforms and binds its textures (its five samplers and its layers' array) on a
  // program in use.
  void bindMaterial(const gl::Program& program, int material) const;
  // True when a material cuts out (MASK), covers partially (BLEND) or transmits light: its
  // depth-only passes need the material's alpha (and the shadow maps its transmission).
  bool needsAlpha(const DrawItem& item) const {
    const Material& m = material(item.material).source;
    return m.alphaMode != AlphaMode::Opaque || m.transmission > 0.0f;
  }
  // Sets uModel, uNormalMatrix, uLayer and uIndirectEmission of a draw item, and its copies'
  // rows (mesh.vert's aCopy*; the identity for an item of one copy). A draw of the item then
  // draws `instancesPerCopy * item.copies` instances, each copy `instancesPerCopy` times (a
  // probe capture's six faces).
  void bindTransform(const gl::Program& program, const DrawItem& item,
                     int instancesPerCopy = 1) const;

 private:
  Result<const gl::Texture2D*> texture(const Scene& scene, const TextureRef& ref, bool srgb);
  // The material's extension textures as layers of its array (gm.layers, gm.layer).
  Status uploadLayers(const Scene& scene, GpuMaterial& gm);
  // The parts of create(): vertex and index buffers, materials and their textures (the glTF
  // default material last), and the draw lists (opaque, BLEND, transmissive).
  Status uploadMeshes(const Scene& scene);
  Status uploadMaterials(const Scene& scene);
  Status buildDrawItems();

  std::vector<std::unique_ptr<GpuPrimitive>> primitives_;  // per mesh, per primitive
  std::vector<std::vector<GpuPrimitive*>> meshes_;
  std::map<std::pair<int, bool>, std::unique_ptr<gl::Texture2D>> textures_;
  std::vector<GpuMaterial> materials_;
  std::vector<DrawItem> opaque_;
  std::vector<DrawItem> blended_;
  std::vector<DrawItem> transmissive_;
  std::vector<Instance> instances_;
  std::vector<GpuPrimitive*> deformed_;   // primitives with a deformation
  std::vector<gl::Texture2D> jointTextures_;  // per skin (Rig::skins)
  std::vector<int> skinOf_;               // per Scene mesh: its skin (Rig::MeshLink), -1: none
  gl::Buffer copyRows_;  // DrawItem::copyOffset: three vec4 rows per copy
  int variantCount_ = 0;
  Bounds bounds_;
  // Bound to the material units a material leaves empty: WebGL rejects a draw whose sampler
  // units still hold a texture attached to the framebuffer being drawn into.
  gl::Texture2D fallback_;
  gl::Texture2DArray fallbackLayers_;
};

}  // namespace penumbra
