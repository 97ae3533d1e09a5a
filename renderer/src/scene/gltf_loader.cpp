// loadGltf / loadGltfFromMemory: container -> JSON -> extension checks -> buffers -> node
// hierarchy (flattened into instances, with cycle and shared-node detection) -> meshes ->
// materials and images. Nothing throws out of here: the stages return Results, and anything a
// library throws (nlohmann, bad_alloc) is caught at this boundary.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string_view>
#include <tuple>

#include "scene/gltf_document.h"

namespace penumbra {
namespace {

using gltf::Document;
using gltf::LoadContext;

constexpr std::array<std::string_view, 21> kSupportedExtensions = {
    "KHR_texture_transform",
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
    "EXT_lights_area",
    "KHR_mesh_quantization",
    "KHR_draco_mesh_compression",
    "EXT_meshopt_compression",
    "KHR_materials_ior",
    "KHR_materials_specular",
    "KHR_materials_unlit",
    "KHR_materials_clearcoat",
    "KHR_materials_sheen",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_texture_basisu",
    "EXT_mesh_gpu_instancing",
    "KHR_materials_variants",
    "KHR_materials_dispersion",
    "KHR_materials_iridescence",
    "KHR_materials_anisotropy",
    "KHR_materials_diffuse_transmission",
};

bool isSupported(const std::string& ext) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), ext) !=
         kSupportedExtensions.end();
}

Status checkExtensions(const Document& doc, LoadContext& ctx) {
  for (const std::string& ext : doc.extensionsRequired) {
    if (!isSupported(ext)) return ctx.error("requires unsupported extension " + ext);
    if ((ext == "KHR_draco_mesh_compression" && !gltf::hasDraco()) ||
        (ext == "EXT_meshopt_compression" && !gltf::hasMeshopt())) {
      return ctx.error("requires " + ext + ", and its decoder is not loaded");
    }
  }
  for (const std::string& ext : doc.extensionsUsed) {
    if (isSupported(ext)) continue;
    if (ext.rfind("KHR_materials_", 0) == 0) {
      ctx.warn("uses " + ext +
               ", which is ignored (the metallic-roughness model with emissive_strength, ior, "
               "specular, clearcoat, sheen, transmission, volume, unlit, iridescence, "
               "anisotropy, diffuse_transmission and dispersion is supported)");
    } else {
      ctx.warn("uses unsupported extension " + ext + " (ignored)");
    }
  }
  return {};
}

// Every node has at most one parent and the parent links have no cycle. Iterative, so a deep
// or hostile hierarchy cannot overflow the stack.
Status checkNodeGraph(const Document& doc, std::vector<int>& parent, LoadContext& ctx) {
  const size_t n = doc.nodes.size();
  parent.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    for (int c : doc.nodes[i].children) {
      if (static_cast<size_t>(c) == i) {
        return ctx.error("node " + std::to_string(i) + " lists itself as a child (cycle)");
      }
      if (parent[static_cast<size_t>(c)] >= 0) {
        return ctx.error("node " + std::to_string(c) + " has more than one parent (nodes " +
                         std::to_string(parent[static_cast<size_t>(c)]) + " and " +
                         std::to_string(i) + ")");
      }
      parent[static_cast<size_t>(c)] = static_cast<int>(i);
    }
  }
  enum : uint8_t { kUnknown, kOnPath, kRooted };
  std::vector<uint8_t> state(n, kUnknown);
  std::vector<int> path;
  for (size_t i = 0; i < n; ++i) {
    path.clear();
    int v = static_cast<int>(i);
    while (v >= 0 && state[static_cast<size_t>(v)] == kUnknown) {
      state[static_cast<size_t>(v)] = kOnPath;
      path.push_back(v);
      v = parent[static_cast<size_t>(v)];
    }
    if (v >= 0 && state[static_cast<size_t>(v)] == kOnPath) {
      return ctx.error("the node hierarchy has a cycle through node " + std::to_string(v));
    }
    for (int p : path) state[static_cast<size_t>(p)] = kRooted;
  }
  return {};
}

// Every node's world transform (the parent links are checked acyclic), for skins' joints,
// which need not lie under the scene's roots.
std::vector<glm::mat4> worldTransforms(const Document& doc, const std::vector<int>& parent) {
  const size_t n = doc.nodes.size();
  std::vector<glm::mat4> world(n);
  std::vector<bool> done(n, false);
  std::vector<int> chain;
  for (size_t i = 0; i < n; ++i) {
    chain.clear();
    for (int v = static_cast<int>(i); v >= 0 && !done[static_cast<size_t>(v)];
         v = parent[static_cast<size_t>(v)]) {
      chain.push_back(v);
    }
    for (auto c = chain.rbegin(); c != chain.rend(); ++c) {
      const int up = parent[static_cast<size_t>(*c)];
      const glm::mat4 base = up >= 0 ? world[static_cast<size_t>(up)] : glm::mat4(1.0f);
      world[static_cast<size_t>(*c)] = base * doc.nodes[static_cast<size_t>(*c)].local;
      done[static_cast<size_t>(*c)] = true;
    }
  }
  return world;
}

// The animation named `nameOrIndex` (a name first, then an index); the error lists them.
Result<int> findAnimation(const std::vector<Scene::Animation>& animations,
                          const std::string& nameOrIndex, const LoadContext& ctx) {
  for (size_t i = 0; i < animations.size(); ++i) {
    if (animations[i].name == nameOrIndex) return static_cast<int>(i);
  }
  char* end = nullptr;
  const long index = std::strtol(nameOrIndex.c_str(), &end, 10);
  if (end && *end == '\0' && index >= 0 && static_cast<size_t>(index) < animations.size()) {
    return static_cast<int>(index);
  }
  if (animations.empty()) return ctx.error("no animation '" + nameOrIndex + "': the file has none");
  std::string list;
  for (size_t i = 0; i < animations.size(); ++i) {
    list += (i ? ", " : "") + std::to_string(i) + ": '" + animations[i].name + "'";
  }
  return ctx.error("no animation '" + nameOrIndex + "'; available: " + list);
}

// The nodes shown: the scene's (the default one, else the first), else every root node.
std::vector<int> sceneRoots(const Document& doc, const std::vector<int>& parent,
                            LoadContext& ctx) {
  if (doc.scene >= 0 || !doc.scenes.empty()) {
    return doc.scenes[static_cast<size_t>(std::max(doc.scene, 0))].nodes;
  }
  std::vector<int> roots;
  for (size_t i = 0; i < doc.nodes.size(); ++i) {
    if (parent[i] < 0) roots.push_back(static_cast<int>(i));
  }
  if (!roots.empty()) ctx.warn("the file has no scenes; showing every root node");
  return roots;
}

// The file's animations (names, end times), their curves where playback or a still pose needs
// them, playback's rig with the nodes at rest (before any still pose), and the document posed
// at LoadOptions' time of its animation.
struct PreparedAnimations {
  std::vector<Scene::Animation> list;
  std::vector<std::vector<AnimationCurve>> clips;
  std::shared_ptr<Rig> rig;
};
Result<PreparedAnimations> prepareAnimations(Document& doc, const std::vector<int>& parent,
                                             const LoadOptions& options, LoadContext& ctx) {
  PreparedAnimations out;
  for (size_t a = 0; a < doc.animations.size(); ++a) {
    out.list.push_back(
        {doc.animations[a].name, gltf::animationDuration(doc, static_cast<int>(a), ctx)});
  }
  if (options.playback || !options.animation.empty()) {
    for (size_t a = 0; a < doc.animations.size(); ++a) {
      auto clip = gltf::readClip(doc, static_cast<int>(a), ctx);
      if (!clip.ok()) return clip.error();
      out.clips.push_back(std::move(clip).value());
    }
  }
  if (options.playback) {
    out.rig = std::make_shared<Rig>();
    out.rig->nodes = gltf::rigNodes(doc, parent);
  }
  if (!options.animation.empty()) {
    auto index = findAnimation(out.list, options.animation, ctx);
    if (!index.ok()) return index.error();
    if (!std::isfinite(options.animationTime)) {
      return ctx.error("animation time must be a finite number of seconds");
    }
    gltf::poseAnimation(doc, out.clips[static_cast<size_t>(*index)], options.animationTime);
  }
  return out;
}

Result<Scene> load(std::span<const uint8_t> bytes, const std::string& baseDir,
                   const std::string& name, const LoadOptions& options) {
  LoadContext ctx;
  ctx.name = name.empty() ? std::string("<memory>") : name;
  ctx.baseDir = baseDir;
  ctx.options = options;
  if (bytes.empty()) return ctx.error("empty file");

  auto container = gltf::splitContainer(bytes, ctx);
  if (!container.ok()) return container.error();
  auto parsed = gltf::parseDocument(container->json, ctx);
  if (!parsed.ok()) return parsed.error();
  Document& doc = *parsed;
  PN_TRY(checkExtensions(doc, ctx));
  PN_TRY(gltf::loadBuffers(doc, container->bin, ctx));
  std::vector<int> parent;
  PN_TRY(checkNodeGraph(doc, parent, ctx));
  auto prepared = prepareAnimations(doc, parent, options, ctx);
  if (!prepared.ok()) return prepared.error();
  auto& [animations, clips, rig] = *prepared;

  const std::vector<int> roots = sceneRoots(doc, parent, ctx);

  Scene scene;
  // A scene mesh per (glTF mesh, morph weights, skin): a node's own weights pose its own copy,
  // and a skinned node's mesh is posed by its skin's joints. For playback a morphed mesh is its
  // node's own (the last part of the key), since nodes animate their weights apart.
  using MeshKey = std::tuple<int, std::vector<float>, int, int>;
  std::map<MeshKey, int> meshRemap;
  std::vector<MeshKey> meshOrder;
  const std::vector<glm::mat4> nodeWorld = worldTransforms(doc, parent);
  std::vector<bool> visited(doc.nodes.size(), false);
  std::vector<std::pair<int, glm::mat4>> stack;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.emplace_back(*it, glm::mat4(1.0f));
  while (!stack.empty()) {
    const auto [index, parentWorld] = stack.back();
    stack.pop_back();
    if (visited[static_cast<size_t>(index)]) {
      return ctx.error("node " + std::to_string(index) +
                       " is reached twice from the scene (listed as a root and as a child, or "
                       "twice as a root)");
    }
    visited[static_cast<size_t>(index)] = true;
    const gltf::NodeDesc& node = doc.nodes[static_cast<size_t>(index)];
    const glm::mat4 world = parentWorld * node.local;
    if (node.mesh >= 0) {
      const auto& prims = doc.meshes[static_cast<size_t>(node.mesh)].primitives;
      const bool ownMorph = rig && std::any_of(prims.begin(), prims.end(), [](const auto& pd) {
                              return !pd.targets.empty();
                            });
      MeshKey key{node.mesh, node.weights.value_or(std::vector<float>{}), node.skin,
                  ownMorph ? index : -1};
      auto [it, added] = meshRemap.emplace(key, static_cast<int>(meshOrder.size()));
      if (added) meshOrder.push_back(std::move(key));
      const int m = it->second;
      if (node.instanced) {
        // EXT_mesh_gpu_instancing: one scene instance per copy (gltf_instancing.cpp).
        auto copies = gltf::instanceTransforms(doc, node, index, ctx);
        if (!copies.ok()) return copies.error();
        for (const glm::mat4& local : *copies) {
          Instance copy{m, world * local, node.name, !node.lightProxy};
          copy.copyOf = index;
          scene.instances.push_back(std::move(copy));
          if (rig) gltf::rigInstance(*rig, index, local, false);
        }
      } else {
        // A skinned mesh is posed in world space by its joints (gltf_skin.cpp).
        scene.instances.push_back(
            Instance{m, node.skin >= 0 ? glm::mat4(1.0f) : world, node.name, !node.lightProxy});
        if (rig) gltf::rigInstance(*rig, index, glm::mat4(1.0f), node.skin >= 0);
      }
    }
    if (node.camera >= 0) gltf::addNodeCamera(doc, node, world, scene, ctx);
    gltf::addNodeLights(doc, node, world, scene, ctx);
    for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) {
      stack.emplace_back(*c, world);
    }
  }

  for (const auto& [m, weights, skin, owner] : meshOrder) {
    if (rig) rig->meshes.push_back({skin, owner});
    std::vector<glm::mat4> joints;
    if (skin >= 0) {
      auto jm = gltf::jointMatrices(doc, skin, nodeWorld, ctx);
      if (!jm.ok()) return jm.error();
      joints = std::move(jm).value();
    }
    auto mesh = gltf::convertMesh(doc, m, weights, joints, ctx);
    if (!mesh.ok()) return mesh.error();
    scene.meshes.push_back(std::move(mesh).value());
  }
  PN_TRY(gltf::convertMaterials(doc, scene, ctx));

  for (const Instance& inst : scene.instances) {
    for (const Primitive& p : scene.meshes[static_cast<size_t>(inst.mesh)].primitives) {
      scene.bounds.extend(p.bounds.transformed(inst.world));
    }
  }
  gltf::markLampFaces(scene, ctx);
  if (scene.instances.empty()) {
    ctx.warn("the scene has no meshes; only the environment will be visible");
  } else if (scene.triangleCount() == 0 || !scene.bounds.valid() ||
             !(scene.bounds.radius() > 0.0f)) {
    ctx.warn(
        "the scene's meshes draw nothing (no triangles with area); only the environment "
        "will be visible");
  }
  scene.variants = doc.variants;
  scene.animations = std::move(animations);
  if (rig) {
    PN_TRY(gltf::rigSkins(doc, *rig, ctx));
    rig->clips = std::move(clips);
    scene.rig = std::move(rig);
  }
  scene.warnings = std::move(ctx.warnings);
  return scene;
}

}  // namespace

Result<Scene> loadGltfFromMemory(std::span<const uint8_t> bytes, const std::string& baseDir,
                                 const std::string& name, const LoadOptions& options) {
  try {
    return load(bytes, baseDir, name, options);
  } catch (const std::bad_alloc&) {
    return makeError(name + ": out of memory while loading");
  } catch (const std::exception& e) {
    return makeError(name + ": " + e.what());
  }
}

Result<Scene> loadGltf(const std::string& path, const LoadOptions& options) {
  try {
    LoadContext ctx;
    ctx.name = path;
    ctx.options = options;
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return ctx.error("no such file");
    auto bytes =
        gltf::readFileBytes(path, "the file", ctx,
                            static_cast<uint64_t>(std::max<int64_t>(options.memoryBudgetBytes, 0)));
    if (!bytes.ok()) return bytes.error();
    const std::string baseDir = std::filesystem::path(path).parent_path().string();
    return loadGltfFromMemory(*bytes, baseDir, path, options);
  } catch (const std::exception& e) {
    return makeError(path + ": " + e.what());
  }
}

}  // namespace penumbra
