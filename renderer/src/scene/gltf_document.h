// Internal to the glTF loader: the parsed glTF document (every index already validated against
// the array it refers to), the per-load context (file name for messages, warnings, memory
// budget), and the stages that turn bytes into a penumbra::Scene.
//
// Why not tinygltf: the Debian tinygltf 2.7.0 rejects Draco primitives unless its own Draco path
// is compiled in, and that path indexes buffer views and Draco attributes without checking them
// (a malformed file crashes); it rejects EXT_meshopt_compression fallback buffers (no uri); it
// reads a whole external buffer before comparing it with the declared length; and libdraco.so
// exports its own copy of the tinygltf symbols, which a second definition in our library would
// silently interpose. Parsing the JSON here (with nlohmann, which tinygltf uses too) keeps every
// check, message and allocation under our control.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "penumbra/animation.h"
#include "penumbra/error.h"
#include "penumbra/scene.h"

namespace penumbra::gltf {

// Accessor component types (the GL enums glTF uses).
enum ComponentType : int {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
};
// Bytes per component; 0 for an unknown type.
size_t componentSize(int componentType);

// State shared by all stages of one load.
struct LoadContext {
  std::string name;     // the file as the caller named it; prefixes every message
  std::string baseDir;  // resolves relative URIs
  LoadOptions options;
  std::vector<std::string> warnings;
  int64_t bytesReserved = 0;

  // Accounts `bytes` against LoadOptions::memoryBudgetBytes before they are allocated, so an
  // absurd declared size becomes an error instead of a bad_alloc.
  Status reserve(uint64_t bytes, const std::string& what);
  void warn(const std::string& message);
  Error error(const std::string& message) const;
};

enum class MeshoptMode { Attributes, Triangles, Indices };
enum class MeshoptFilter { None, Octahedral, Quaternion, Exponential };

struct MeshoptDesc {
  int buffer = -1;
  uint64_t byteOffset = 0;
  uint64_t byteLength = 0;
  uint64_t byteStride = 0;
  uint64_t count = 0;
  MeshoptMode mode = MeshoptMode::Attributes;
  MeshoptFilter filter = MeshoptFilter::None;
};

struct BufferDesc {
  uint64_t byteLength = 0;
  bool hasUri = false;
  std::string uri;
  // EXT_meshopt_compression fallback buffer: may have no data at all.
  bool meshoptFallback = false;
};

struct BufferViewDesc {
  int buffer = -1;
  uint64_t byteOffset = 0;
  uint64_t byteLength = 0;
  uint64_t byteStride = 0;  // 0 = tightly packed
  std::optional<MeshoptDesc> meshopt;
};

struct SparseDesc {
  uint64_t count = 0;
  int indicesView = -1;
  uint64_t indicesOffset = 0;
  int indicesComponentType = 0;
  int valuesView = -1;
  uint64_t valuesOffset = 0;
};

struct AccessorDesc {
  int bufferView = -1;  // -1: all zeros (before sparse substitution)
  uint64_t byteOffset = 0;
  int componentType = 0;
  int components = 0;  // 1 (SCALAR) .. 16 (MAT4)
  std::string type;
  bool normalized = false;
  uint64_t count = 0;
  std::optional<SparseDesc> sparse;
};

struct DracoDesc {
  int bufferView = -1;
  std::map<std::string, int> attributes;  // glTF attribute name -> Draco unique id
};

struct PrimitiveDesc {
  std::map<std::string, int> attributes;  // name -> accessor
  int indices = -1;
  int material = -1;
  int mode = 4;
  std::optional<DracoDesc> draco;
  // Morph targets: per target, attribute name (POSITION, NORMAL, TANGENT) -> accessor.
  std::vector<std::map<std::string, int>> targets;
  // KHR_materials_variants mappings: (material, the variants that select it).
  std::vector<std::pair<int, std::vector<int>>> variantMappings;
};

struct MeshDesc {
  std::string name;
  std::vector<PrimitiveDesc> primitives;
  std::vector<float> weights;  // the morph targets' default weights
};

struct NodeDesc {
  std::string name;
  std::vector<int> children;
  int mesh = -1;
  int camera = -1;
  int areaLight = -1;       // EXT_lights_area
  int punctualLight = -1;   // KHR_lights_punctual
  bool lightProxy = false;  // extras.area_light_proxy: the visible face of an area light
  glm::mat4 local{1.0f};
  // The parts `local` is made of (an animation replaces them): or a matrix, which animations
  // may not target.
  bool hasMatrix = false;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  // EXT_mesh_gpu_instancing: accessors of the instances' TRANSLATION, ROTATION and SCALE
  // (-1: none); `instanced` when the node has the extension at all.
  bool instanced = false;
  int instanceTranslation = -1, instanceRotation = -1, instanceScale = -1;
  // The morph weights of this node's mesh (replacing the mesh's own when present).
  std::optional<std::vector<float>> weights;
  int skin = -1;
};

struct AnimationDesc {
  using Interpolation = AnimationCurve::Interpolation;
  using Path = AnimationCurve::Path;
  struct Sampler {
    int input = -1, output = -1;  // accessors: key times (s), values
    Interpolation interpolation = Interpolation::Linear;
  };
  struct Channel {
    int sampler = -1;
    int node = -1;  // -1: no node (KHR_animation_pointer): ignored
    Path path = Path::Translation;
    bool known = true;  // a path other than the four above: ignored
  };
  std::string name;
  std::vector<Sampler> samplers;
  std::vector<Channel> channels;
};

struct SkinDesc {
  std::vector<int> joints;       // node indices
  int inverseBindMatrices = -1;  // MAT4 accessor; -1: identities
};

struct SceneDesc {
  std::string name;
  std::vector<int> nodes;
};

// A material's texture infos, indexed by penumbra::TextureSlot (penumbra/scene.h).
constexpr size_t slotIndex(TextureSlot slot) {
  return static_cast<size_t>(slot);
}

struct TextureInfoDesc {
  int texture = -1;  // glTF texture index; -1 = none
  int texCoord = 0;  // after the KHR_texture_transform override
  glm::mat3 transform{1.0f};
};

struct MaterialDesc {
  Material material;  // factors filled in; TextureRef image/sampler resolved later
  std::array<TextureInfoDesc, kTextureSlotCount> textures;
};

struct TextureDesc {
  int source = -1;
  int sampler = -1;
  int basisuSource = -1;  // KHR_texture_basisu: a KTX2 image (preferred where it transcodes)
};

struct ImageDesc {
  std::string name;
  std::string uri;  // empty when bufferView is used
  std::string mimeType;
  int bufferView = -1;
};

struct CameraDesc {
  std::string name;
  bool perspective = true;
  float yfov = 0.8f;
  float aspect = 0.0f;
  float znear = 0.05f;
  float zfar = 0.0f;
  float xmag = 1.0f, ymag = 1.0f;  // orthographic
};

struct LightDesc {
  std::string name;
  LightType type = LightType::Rect;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float size = 1.0f;    // area: rect height / disk diameter
  float aspect = 1.0f;  // rect: width / height
  float range = 0.0f;   // punctual
  float innerConeAngle = 0.0f;
  float outerConeAngle = 0.785398163f;
};

struct Document {
  std::vector<std::string> extensionsUsed;
  std::vector<std::string> extensionsRequired;
  std::vector<BufferDesc> buffers;
  std::vector<BufferViewDesc> bufferViews;
  std::vector<AccessorDesc> accessors;
  std::vector<MeshDesc> meshes;
  std::vector<NodeDesc> nodes;
  std::vector<SceneDesc> scenes;
  int scene = -1;
  std::vector<MaterialDesc> materials;
  std::vector<TextureDesc> textures;
  std::vector<ImageDesc> images;
  std::vector<SamplerDesc> samplers;
  std::vector<CameraDesc> cameras;
  std::vector<LightDesc> areaLights;
  std::vector<LightDesc> punctualLights;
  std::vector<SkinDesc> skins;
  std::vector<AnimationDesc> animations;
  std::vector<std::string> variants;  // KHR_materials_variants (root extension)

  // Buffer contents (after loadBuffers): spans into `ownedBuffers` or into the caller's GLB
  // bytes (which outlive the load). A meshopt fallback buffer without data has an empty span.
  std::vector<std::span<const uint8_t>> bufferData;
  std::vector<std::vector<uint8_t>> ownedBuffers;
  // EXT_meshopt_compression views, decoded on first use.
  std::map<int, std::vector<uint8_t>> decodedViews;
};

// ---- gltf_buffers.cpp ----
// The JSON text and the BIN chunk of a .glb, or the whole input as JSON for a .gltf.
struct Container {
  std::string_view json;
  std::span<const uint8_t> bin;
  bool binary = false;
};
Result<Container> splitContainer(std::span<const uint8_t> bytes, const LoadContext& ctx);
// Reads a whole file; `what` names it in the error ("buffer 0", "image 3").
Result<std::vector<uint8_t>> readFileBytes(const std::string& path, const std::string& what,
                                           const LoadContext& ctx, uint64_t maxBytes);
// Resolves a data: URI or a path relative to ctx.baseDir (percent-decoded). A file larger than
// `maxFileBytes` is refused before it is read.
Result<std::vector<uint8_t>> readUri(const std::string& uri, const std::string& what,
                                     LoadContext& ctx, uint64_t maxFileBytes);
bool isDataUri(const std::string& uri);
// Loads every buffer (after the budget check of the declared lengths) and validates every
// buffer view against its buffer.
Status loadBuffers(Document& doc, std::span<const uint8_t> glbBin, LoadContext& ctx);

// The bytes of one buffer view, decoded first when it is EXT_meshopt_compression-compressed.
struct ViewBytes {
  const uint8_t* data = nullptr;
  uint64_t size = 0;
  uint64_t stride = 0;  // the view's byteStride (0 = tightly packed)
};
Result<ViewBytes> viewBytes(Document& doc, int view, LoadContext& ctx);

// ---- gltf_morph.cpp ----
// Applies a primitive's morph targets with `weights` (a still renderer shows the model at
// rest: the file's default weights) to its positions, and to its normals and tangents where
// the targets carry them. Extra weights or targets beyond the shorter list are ignored.
Status applyMorphTargets(Document& doc, const PrimitiveDesc& pd, const std::vector<float>& weights,
                         Primitive& prim, LoadContext& ctx, const std::string& what);

// Every morph target's POSITION, NORMAL and TANGENT displacements, for playback.
Result<std::vector<Deformation::Target>> readMorphTargets(Document& doc, const PrimitiveDesc& pd,
                                                         size_t vertexCount, LoadContext& ctx,
                                                         const std::string& what);

// ---- gltf_animation.cpp ----
// The end of animation `animation` (its last key time), in seconds.
float animationDuration(Document& doc, int animation, LoadContext& ctx);
// Animation `animation`'s channels as curves (those without a node, or on a matrix node, are
// left out with a warning); a sampler whose input and output disagree is an error.
Result<std::vector<AnimationCurve>> readClip(Document& doc, int animation, LoadContext& ctx);
// Poses the document at `time` seconds of `clip`: its curves replace their nodes' translation,
// rotation and scale (and `local`) or morph weights.
void poseAnimation(Document& doc, const std::vector<AnimationCurve>& clip, float time);
glm::mat4 composeTrs(const NodeDesc& node);

// ---- gltf_skin.cpp ----
// Each joint's matrix of skin `skin` (its node's world transform times its inverse bind
// matrix): what applySkin poses a mesh with.
Result<std::vector<glm::mat4>> jointMatrices(Document& doc, int skin,
                                             const std::vector<glm::mat4>& nodeWorld,
                                             LoadContext& ctx);
// Poses a primitive by its JOINTS_0 and WEIGHTS_0 values (as floats, 4 per vertex, read from
// plain or Draco-compressed data) with `joints` (from jointMatrices): its positions, normals and
// tangents end up in world space, as glTF defines for skinned meshes.
Status applySkin(const std::vector<float>& jointIndices, const std::vector<float>& weights,
                 const std::vector<glm::mat4>& joints, Primitive& prim, LoadContext& ctx,
                 const std::string& what);

// Playback's rig (penumbra/animation.h): the nodes at rest with their parents, an instance at
// its node (a copy's own transform under it), and every skin's joints and inverse binds.
std::vector<Rig::Node> rigNodes(const Document& doc, const std::vector<int>& parent);
void rigInstance(Rig& rig, int node, const glm::mat4& local, bool skinned);
Status rigSkins(Document& doc, Rig& rig, LoadContext& ctx);

// ---- lamp_faces.cpp ----
// Marks instances whose emissive primitives sit on an area light as that light's visible face
// (Instance::lampFace), with a warning each.
void markLampFaces(Scene& scene, LoadContext& ctx);

// ---- gltf_instancing.cpp ----
// EXT_mesh_gpu_instancing: each instance's transform relative to the node (T * R * S from its
// TRANSLATION, ROTATION and SCALE accessors), in instance order. Errors on accessors of the
// wrong type or of different counts; at most kMaxInstances per node, and the instances' memory
// is reserved from the budget.
inline constexpr uint64_t kMaxInstances = uint64_t{1} << 20;
Result<std::vector<glm::mat4>> instanceTransforms(Document& doc, const NodeDesc& node,
                                                  int nodeIndex, LoadContext& ctx);

// ---- gltf_parse.cpp (with gltf_json.h) ----
Result<Document> parseDocument(std::string_view json, LoadContext& ctx);

// ---- gltf_accessors.cpp ----
// Converts `count` elements of `components` components each (source stride `stride` bytes) to
// floats, applying the glTF normalisation rules when `normalized`.
void convertToFloat(const uint8_t* src, uint64_t stride, uint64_t count, int componentType,
                    int components, bool normalized, float* out);
// Reads an accessor as floats (count * components values), with bounds checks and sparse
// substitution. `what` names the use in messages ("mesh 0 primitive 1 POSITION").
Result<std::vector<float>> readFloats(Document& doc, int accessor, LoadContext& ctx,
                                      const std::string& what);
// Reads an index accessor (unsigned byte/short/int scalars).
Result<std::vector<uint32_t>> readIndices(Document& doc, int accessor, LoadContext& ctx,
                                          const std::string& what);

// ---- mesh_decode.cpp ----
// Decodes one EXT_meshopt_compression buffer view into `out` (count * byteStride bytes).
Status decodeMeshopt(const MeshoptDesc& desc, std::span<const uint8_t> src,
                     std::vector<uint8_t>& out, const std::string& what, const LoadContext& ctx);
// A Draco-compressed primitive after decoding: every attribute named in the extension, as
// floats in its accessor's component count, plus triangle indices.
struct DecodedDraco {
  std::map<std::string, std::vector<float>> attributes;
  std::vector<uint32_t> indices;
  uint64_t vertexCount = 0;
};
Result<DecodedDraco> decodeDraco(Document& doc, const PrimitiveDesc& primitive, LoadContext& ctx,
                                 const std::string& what);
// Whether the compression extensions can be decoded: natively always; in the web build once
// web/lib/decoders.mjs has given the module the decoder (it does for every file that names
// the extension).
bool hasDraco();
bool hasMeshopt();

// ---- gltf_meshes.cpp ----
// Converts one glTF mesh (doc.materials tells which primitives need generated tangents).
// `weights`: the morph weights to pose it with (empty: the mesh's own defaults); `joints`:
// the skin's joint matrices to pose it with (empty: not skinned).
Result<Mesh> convertMesh(Document& doc, int meshIndex, const std::vector<float>& weights,
                         const std::vector<glm::mat4>& joints, LoadContext& ctx);

// ---- tangents.cpp ----
// Area-weighted smooth vertex normals over the triangles of `prim` (flat where the caller
// unwelded the vertices first).
void generateNormals(Primitive& prim);
// Gives every triangle its own three vertices (copies all attributes), so that generated
// normals come out flat.
void unweldVertices(Primitive& prim);
// MikkTSpace-style tangents from the UV set `uv`; see tangents.cpp for how close it is.
void generateTangents(Primitive& prim, int uvSet);

// ---- gltf_materials.cpp ----
// Materials, textures, samplers and the images the materials use (decoded to RGBA8).
Status convertMaterials(Document& doc, Scene& scene, LoadContext& ctx);

// ---- gltf_lights.cpp ----
// Lights and cameras attached to one node with world matrix `world`.
void addNodeCamera(const Document& doc, const NodeDesc& node, const glm::mat4& world, Scene& scene,
                   LoadContext& ctx);
void addNodeLights(const Document& doc, const NodeDesc& node, const glm::mat4& world, Scene& scene,
                   LoadContext& ctx);

}  // namespace penumbra::gltf
