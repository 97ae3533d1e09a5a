// Scene: the CPU-side description of what Penumbra renders, produced by the glTF loader and
// consumed by the renderer (which uploads it to GL). Units: metres, +Y up, right-handed, as
// in glTF. Light units (see docs/scene-format.md): area lights carry their surface luminance
// in nits, which the renderer uses directly as linear radiance; environment texels are
// radiance in the same unit (times the environment intensity); punctual lights follow
// KHR_lights_punctual (candela for point/spot, lux for directional).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "penumbra/error.h"

namespace penumbra {

struct Rig;  // penumbra/animation.h

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (b.valid()) {
      extend(b.min);
      extend(b.max);
    }
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  // The box around these bounds' eight corners under m (invalid stays invalid).
  Bounds transformed(const glm::mat4& m) const {
    Bounds b;
    if (!valid()) return b;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 p((c & 1) ? max.x : min.x, (c & 2) ? max.y : min.y, (c & 4) ? max.z : min.z);
      b.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
    }
    return b;
  }
  float radius() const { return glm::length(max - min) * 0.5f; }
};

// glTF sampler values (GL enums as numbers, so the loader stays GL-free).
struct SamplerDesc {
  int magFilter = 9729;  // LINEAR
  int minFilter = 9987;  // LINEAR_MIPMAP_LINEAR
  int wrapS = 10497;     // REPEAT
  int wrapT = 10497;
};

// Decoded image, always RGBA8 (row 0 = top). Whether it is sRGB depends on the slot that uses
// it (base colour and emissive are sRGB), so the renderer decides at upload.
struct ImageData {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // RGBA8, row 0 at the top (empty when compressed)
  bool placeholder = false;     // a missing or undecodable image replaced by a 1x1 texel
  // A GPU-compressed image (a KTX2 texture the browser build transcoded to a format the device
  // samples): the GL internal format of its linear variant (the renderer takes the sRGB one
  // for colour slots), and each mip level's blocks from level 0. 0: `pixels` holds RGBA8.
  uint32_t compressedFormat = 0;
  std::vector<std::vector<uint8_t>> compressedLevels;
};

struct TextureRef {
  int image = -1;    // index into Scene::images; -1 = no texture
  int sampler = -1;  // index into Scene::samplers; -1 = default sampler
  int texCoord = 0;  // 0 or 1
  // KHR_texture_transform as a 3x3 UV matrix (translation * rotation * scale).
  glm::mat3 transform{1.0f};
  bool valid() const { return image >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// Every texture a material samples, in the shaders' slot order (glsl/chunks/material.glsl).
// The first five are glTF's core textures; the others are the KHR_materials_* extensions'
// (gpu/gpu_scene.h puts those in one texture array per material, so all fit WebGL2's units).
enum class TextureSlot : int {
  BaseColor,
  MetallicRoughness,
  Normal,
  Occlusion,
  Emissive,
  ClearcoatNormal,           // KHR_materials_clearcoat: the coat's own normal map
  Clearcoat,                 // .r scales clearcoatFactor
  ClearcoatRoughness,        // .g scales clearcoatRoughnessFactor
  SheenColor,                // KHR_materials_sheen: .rgb (sRGB) scales sheenColorFactor
  SheenRoughness,            // .a scales sheenRoughnessFactor
  Specular,                  // KHR_materials_specular: .a scales specularFactor
  SpecularColor,             // .rgb (sRGB) scales specularColorFactor
  Transmission,              // KHR_materials_transmission: .r scales transmissionFactor
  Thickness,                 // KHR_materials_volume: .g scales thicknessFactor
  Iridescence,               // KHR_materials_iridescence: .r scales iridescenceFactor
  IridescenceThickness,      // .g: thickness from minimum (0) to maximum (1)
  Anisotropy,                // KHR_materials_anisotropy: .rg direction, .b scales the strength
  DiffuseTransmission,       // KHR_materials_diffuse_transmission: .a scales the factor
  DiffuseTransmissionColor,  // .rgb (sRGB) scales the colour factor
};
inline constexpr int kTextureSlotCount = 19;
inline constexpr int kCoreTextureSlots = 5;  // BaseColor..Emissive: a texture unit each

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  glm::vec3 emissiveFactor{0.0f};
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  TextureRef baseColorTexture;
  TextureRef metallicRoughnessTexture;
  TextureRef normalTexture;
  TextureRef occlusionTexture;
  TextureRef emissiveTexture;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  float ior = 1.5f;                     // KHR_materials_ior
  float specularFactor = 1.0f;          // KHR_materials_specular
  glm::vec3 specularColorFactor{1.0f};  // KHR_materials_specular
  bool unlit = false;                   // KHR_materials_unlit
  float clearcoat = 0.0f;               // KHR_materials_clearcoat
  float clearcoatRoughness = 0.0f;
  TextureRef clearcoatNormalTexture;  // the coat's own normal map (tangent space)
  float clearcoatNormalScale = 1.0f;
  glm::vec3 sheenColor{0.0f};  // KHR_materials_sheen: 0 = no sheen
  float sheenRoughness = 0.0f;
  // KHR_materials_transmission (factor): the share of the dielectric base's light that passes
  // through the surface instead of being diffused. Such surfaces are drawn after the opaque
  // ones and show what is behind them (renderer: "Transmission").
  float transmission = 0.0f;
  // KHR_materials_volume (factors): thickness in the mesh's units (0: thin-walled, no
  // refraction), Beer-Lambert attenuation: attenuationColor is what remains after
  // attenuationDistance (0: no attenuation).
  float thickness = 0.0f;
  float attenuationDistance = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  // KHR_materials_dispersion: 20 / Abbe number (0: none); spreads the volume's refraction over
  // three indices, (ior - 1) * 0.025 * dispersion either side of ior for red and blue.
  float dispersion = 0.0f;
  // KHR_materials_iridescence: a thin film over the base (strength; the film's index; its
  // thickness in nanometres, from the texture's .g between minimum and maximum, else maximum).
  float iridescence = 0.0f;
  float iridescenceIor = 1.3f;
  float iridescenceThicknessMin = 100.0f;
  float iridescenceThicknessMax = 400.0f;
  // KHR_materials_anisotropy: strength in [0, 1] (stretches the specular lobe along the
  // direction), and the direction's rotation from the tangent (radians, counter-clockwise).
  float anisotropy = 0.0f;
  float anisotropyRotation = 0.0f;
  // KHR_materials_diffuse_transmission: the share of the diffuse base's light that leaves
  // through the other side (Lambertian), and the colour it takes on.
  float diffuseTransmission = 0.0f;
  glm::vec3 diffuseTransmissionColor{1.0f};
  // The KHR_materials_* extensions' textures (TextureSlot::ClearcoatNormal and after but the
  // normal map, which has its own field above), each scaling its factor.
  TextureRef clearcoatTexture;
  TextureRef clearcoatRoughnessTexture;
  TextureRef sheenColorTexture;
  TextureRef sheenRoughnessTexture;
  TextureRef specularTexture;
  TextureRef specularColorTexture;
  TextureRef transmissionTexture;
  TextureRef thicknessTexture;
  TextureRef iridescenceTexture;
  TextureRef iridescenceThicknessTexture;
  TextureRef anisotropyTexture;
  TextureRef diffuseTransmissionTexture;
  TextureRef diffuseTransmissionColorTexture;
  // The dielectric reflectance at normal incidence the shader uses:
  // min(((ior - 1) / (ior + 1))^2 specularColor, 1) specular (0.04 by default).
  glm::vec3 dielectricF0() const;
  // Whether it emits light (emissiveFactor times emissive_strength above 0).
  bool emits() const {
    return glm::max(emissiveFactor.r, glm::max(emissiveFactor.g, emissiveFactor.b)) *
               emissiveStrength >
           0.0f;
  }
  // The texture of a slot (one of the fields above).
  TextureRef& texture(TextureSlot slot);
  const TextureRef& texture(TextureSlot slot) const;
};

// What a slot is: its glTF path inside a material, whether it holds sRGB colour and whether it
// is a tangent-space normal map.
struct TextureSlotInfo {
  const char* path;
  bool srgb;
  bool normalMap;
};
const TextureSlotInfo& textureSlotInfo(TextureSlot slot);

// Playback (LoadOptions::playback): a morphed or skinned primitive as the file has it, before its
// morph targets and skin, and what poses it (Renderer::setPose, on the GPU). Normals and
// tangents the file lacks are generated from these positions as for the still.
struct Deformation {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec4> joints;   // JOINTS_0 as floats; empty: not skinned
  std::vector<glm::vec4> weights;  // WEIGHTS_0
  // Morph targets' displacements (an array is empty where the target does not move it).
  struct Target {
    std::vector<glm::vec3> positions, normals, tangents;
  };
  std::vector<Target> targets;
};

// One drawable primitive, de-indexed into separate attribute arrays. Optional arrays are
// empty when absent (normals and, for normal-mapped materials, tangents are generated).
struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> tangents;  // xyz tangent, w bitangent sign (MikkTSpace convention)
  std::vector<glm::vec2> uv0;
  std::vector<glm::vec2> uv1;
  std::vector<glm::vec4> colors;  // COLOR_0, linear RGBA
  std::vector<uint32_t> indices;  // always present (generated 0..n-1 for non-indexed input)
  int material = -1;              // -1 = the glTF default material
  // KHR_materials_variants: the material of each of Scene::variants (`material` where a variant
  // does not map this primitive); empty when the scene has no variants.
  std::vector<int> variantMaterials;
  Bounds bounds;  // object space
  std::shared_ptr<const Deformation> deformation;  // null: still (or loaded without playback)
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
};

// A mesh placed in the world (the node hierarchy flattened).
struct Instance {
  int mesh = -1;
  glm::mat4 world{1.0f};
  std::string nodeName;
  // False for the visible face of an area light (a node with extras.area_light_proxy): the
  // light itself is not geometry, so its stand-in blocks no other light (as path tracers treat
  // lamp proxies). It is still seen by the camera.
  bool castsShadow = true;
  // Its emissive primitives sit on an area light (a lamp mesh, found by the loader without
  // markup): those primitives are treated as the light's visible face, as castsShadow false
  // treats the whole node; the rest of the mesh (a lamp's shade) stays ordinary geometry.
  bool lampFace = false;
  // EXT_mesh_gpu_instancing: the index of the node whose copies this is (-1: not a copy). The
  // copies of one node share their mesh and are drawn together, one instanced draw per primitive.
  int copyOf = -1;
};

struct Camera {
  std::string name;
  glm::mat4 world{1.0f};  // camera-to-world; the camera looks down its local -Z
  float yfov = 0.8f;      // radians (perspective)
  float aspect = 0.0f;    // 0 = take the viewport's
  float znear = 0.05f;
  float zfar = 0.0f;  // 0 = infinite (perspective only)
  // glTF orthographic camera: ymag is half the view's height in world units; the width follows
  // the viewport's aspect ratio (as for perspective cameras, the viewport wins over xmag).
  bool orthographic = false;
  float ymag = 1.0f;
};

enum class LightType { Rect, Disk, Point, Spot, Directional };

struct Light {
  std::string name;
  LightType type = LightType::Rect;
  glm::vec3 color{1.0f};
  // Rect/disk: luminance in nits. Point/spot: candela. Directional: lux.
  float intensity = 1.0f;
  glm::vec3 position{0.0f};       // world centre
  glm::vec3 direction{0, 0, -1};  // world direction of emission (area, spot, directional)
  glm::vec3 right{1, 0, 0};       // world unit vector along the rect's width (local +X)
  glm::vec3 up{0, 1, 0};          // world unit vector along the rect's height (local +Y)
  float width = 1.0f;             // rect width; disk diameter
  float height = 1.0f;            // rect height; disk diameter
  float range = 0.0f;             // punctual range (0 = infinite)
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.785398f;
  // Directional: angular diameter in radians over which its shadow samples spread; 0 takes
  // progressive.directionalAngle (an environment's sun carries its own).
  float angularDiameter = 0.0f;

  // An emitting surface (rect, disk), and its area (0 for the others).
  bool isArea() const;
  float area() const;
};

struct Scene {
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<ImageData> images;
  std::vector<SamplerDesc> samplers;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;
  std::vector<Light> lights;
  Bounds bounds;  // world space, of all instances
  // The probe volume's box and probes per axis, from a scene file (an invalid box: the
  // bounds; a count of 0: from the density setting).
  Bounds probeBox;
  glm::ivec3 probeCounts{0};
  std::vector<std::string> warnings;  // non-fatal problems (unknown optional extension, ...)
  // KHR_materials_variants: the variants' names, in the file's order (a product in several
  // fabrics, say). Loading shows the primitives' own materials; selectVariant switches.
  std::vector<std::string> variants;
  // The file's animations (name, possibly empty, and end time in seconds), in its order. The
  // scene is posed at LoadOptions::animationTime of LoadOptions::animation, else at rest.
  struct Animation {
    std::string name;
    float duration = 0.0f;
  };
  std::vector<Animation> animations;
  // What poses the scene at any time of its animations (LoadOptions::playback; null without).
  std::shared_ptr<const Rig> rig;
  size_t triangleCount() const;
};

struct LoadOptions {
  // Refuse a scene whose decoded geometry and textures would exceed this many bytes.
  int64_t memoryBudgetBytes = int64_t{2} << 30;
  // Textures larger than this on either side are downscaled (by halving) on load.
  int maxTextureSize = 4096;
  // Pose the scene at `animationTime` seconds of this animation (a name, or an index when a
  // number; empty: the rest pose). Before its first key and after its last it holds its ends.
  std::string animation;
  float animationTime = 0.0f;
  // Keep what plays the animations back (Scene::rig, Primitive::deformation) for a viewer
  // that poses the scene over time; a still needs neither.
  bool playback = false;
};

// Loads a .gltf (with external or embedded buffers and images) or .glb file.
Result<Scene> loadGltf(const std::string& path, const LoadOptions& options = {});
// Loads from memory; `baseDir` resolves relative URIs (may be empty), `name` is for messages.
Result<Scene> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& baseDir,
                                 const std::string& name, const LoadOptions& options = {});

// A camera framing the scene from the front (+Z toward -Z), slightly above: its vertices fill
// 92 % of a view of `aspect` (width / height) along the binding axis, centred in it.
Camera defaultCamera(const Scene& scene, float aspect = 1.0f);
// Finds a camera by name, or by index when `nameOrIndex` is a number.
Result<int> findCamera(const Scene& scene, const std::string& nameOrIndex);
// Finds a KHR_materials_variants variant by name, or by index when `nameOrIndex` is a number;
// "" or "default" is -1, the primitives' own materials.
Result<int> findVariant(const Scene& scene, const std::string& nameOrIndex);
// The material shown under `variant` (-1: `own`) given the materials per variant.
inline int variantMaterial(int own, const std::vector<int>& perVariant, int variant) {
  return variant >= 0 && variant < static_cast<int>(perVariant.size())
             ? perVariant[static_cast<size_t>(variant)]
             : own;
}
inline int variantMaterial(const Primitive& p, int variant) {
  return variantMaterial(p.material, p.variantMaterials, variant);
}

}  // namespace penumbra
