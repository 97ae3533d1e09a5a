// JSON -> Document. Every property is read through typed getters that record the first error
// with its JSON path ("accessors[3].bufferView: ..."), and every index is checked against the
// array it refers to here, so the later stages can index without further checks.
#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/quaternion.hpp>

#include "scene/gltf_document.h"
#include "scene/gltf_json.h"
#include "scene/light_kinds.h"

namespace penumbra::gltf {
namespace {

// A mesh's or node's morph "weights" (finite numbers; empty when absent).
std::vector<float> weightsOf(Parser& p, const json& o, const std::string& path) {
  std::vector<float> w;
  if (const json* a = p.array(o, "weights", path)) {
    for (size_t i = 0; i < a->size(); ++i) {
      const json& v = (*a)[i];
      const double x = v.is_number() ? v.get<double>() : 0.0;
      if (!v.is_number() || !std::isfinite(x)) {
        p.fail(path + ".weights[" + std::to_string(i) + "]", "must be a number");
      }
      w.push_back(static_cast<float>(x));
    }
  }
  return w;
}

// The sizes of the top-level arrays, which every index is checked against.
struct Counts {
  size_t buffers, views, accessors, meshes, nodes, materials, textures, images, samplers, cameras,
      skins;
};

// Parses the 'buffers' array.
void parseBuffers(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                  [[maybe_unused]] const Counts& count) {
  forEach(p, root, "buffers", [&](const json& o, const std::string& path, size_t) {
    BufferDesc b;
    b.byteLength = static_cast<uint64_t>(p.integer(o, "byteLength", path, 0, true));
    if (Parser::find(o, "uri")) {
      b.hasUri = true;
      b.uri = p.string(o, "uri", path);
    }
    if (const json* ext = p.object(o, "extensions", path)) {
      if (const json* m = p.object(*ext, "EXT_meshopt_compression", path + ".extensions")) {
        b.meshoptFallback = p.boolean(*m, "fallback", path, false);
      }
    }
    doc.buffers.push_back(b);
  });
}

// Parses the 'bufferViews' array.
void parseBufferViews(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                      [[maybe_unused]] const Counts& count) {
  forEach(p, root, "bufferViews", [&](const json& o, const std::string& path, size_t) {
    BufferViewDesc v;
    v.buffer = p.index(o, "buffer", path, count.buffers, "buffers", true);
    v.byteOffset = static_cast<uint64_t>(p.integer(o, "byteOffset", path, 0));
    v.byteLength = static_cast<uint64_t>(p.integer(o, "byteLength", path, 0, true));
    v.byteStride = static_cast<uint64_t>(p.integer(o, "byteStride", path, 0, false, 0, 252));
    if (const json* ext = p.object(o, "extensions", path)) {
      if (const json* m = p.object(*ext, "EXT_meshopt_compression", path + ".extensions")) {
        const std::string mp = path + ".extensions.EXT_meshopt_compression";
        MeshoptDesc d;
        d.buffer = p.index(*m, "buffer", mp, count.buffers, "buffers", true);
        d.byteOffset = static_cast<uint64_t>(p.integer(*m, "byteOffset", mp, 0));
        d.byteLength = static_cast<uint64_t>(p.integer(*m, "byteLength", mp, 0, true));
        d.byteStride = static_cast<uint64_t>(p.integer(*m, "byteStride", mp, 0, true, 1, 256));
        d.count = static_cast<uint64_t>(p.integer(*m, "count", mp, 0, true));
        const std::string mode = p.string(*m, "mode", mp, "", true);
        const std::string filter = p.string(*m, "filter", mp, "NONE");
        if (mode == "ATTRIBUTES") {
          d.mode = MeshoptMode::Attributes;
        } else if (mode == "TRIANGLES") {
          d.mode = MeshoptMode::Triangles;
        } else if (mode == "INDICES") {
          d.mode = MeshoptMode::Indices;
        } else if (!p.failed()) {
          p.fail(mp + ".mode", "unknown mode '" + mode + "'");
        }
        if (filter == "NONE") {
          d.filter = MeshoptFilter::None;
        } else if (filter == "OCTAHEDRAL") {
          d.filter = MeshoptFilter::Octahedral;
        } else if (filter == "QUATERNION") {
          d.filter = MeshoptFilter::Quaternion;
        } else if (filter == "EXPONENTIAL") {
          d.filter = MeshoptFilter::Exponential;
        } else {
          p.fail(mp + ".filter", "unknown filter '" + filter + "'");
        }
        v.meshopt = d;
      }
    }
    doc.bufferViews.push_back(v);
  });
}

// Parses the 'accessors' array.
void parseAccessors(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                    [[maybe_unused]] const Counts& count) {
  forEach(p, root, "accessors", [&](const json& o, const std::string& path, size_t) {
    AccessorDesc a;
    a.bufferView = p.index(o, "bufferView", path, count.views, "bufferViews");
    a.byteOffset = static_cast<uint64_t>(p.integer(o, "byteOffset", path, 0));
    a.componentType = static_cast<int>(p.integer(o, "componentType", path, 0, true));
    if (!p.failed() && componentSize(a.componentType) == 0) {
      p.fail(path + ".componentType",
             "unsupported component type " + std::to_string(a.componentType));
    }
    a.normalized = p.boolean(o, "normalized", path, false);
    a.count = static_cast<uint64_t>(p.integer(o, "count", path, 0, true));
    a.type = p.string(o, "type", path, "", true);
    a.components = componentsOf(a.type);
    if (!p.failed() && a.components == 0) p.fail(path + ".type", "unknown type '" + a.type + "'");
    if (const json* s = p.object(o, "sparse", path)) {
      const std::string sp = path + ".sparse";
      SparseDesc d;
      d.count = static_cast<uint64_t>(p.integer(*s, "count", sp, 0, true));
      const json* idx = p.object(*s, "indices", sp);
      const json* val = p.object(*s, "values", sp);
      if (!idx || !val) {
        p.fail(sp, "needs 'indices' and 'values' objects");
      } else {
        d.indicesView =
            p.index(*idx, "bufferView", sp + ".indices", count.views, "bufferViews", true);
        d.indicesOffset = static_cast<uint64_t>(p.integer(*idx, "byteOffset", sp + ".indices", 0));
        d.indicesComponentType =
            static_cast<int>(p.integer(*idx, "componentType", sp + ".indices", 0, true));
        d.valuesView =
            p.index(*val, "bufferView", sp + ".values", count.views, "bufferViews", true);
        d.valuesOffset = static_cast<uint64_t>(p.integer(*val, "byteOffset", sp + ".values", 0));
      }
      a.sparse = d;
    }
    doc.accessors.push_back(a);
  });
}

// KHR_materials_variants' root list of variant names (before the meshes that map them).
void parseVariants(Parser& p, const json& root, Document& doc) {
  const json* rootExt = p.object(root, "extensions", "glTF");
  const json* ext = rootExt ? p.object(*rootExt, "KHR_materials_variants", "extensions") : nullptr;
  const std::string vp = "extensions.KHR_materials_variants";
  const json* variants = ext ? p.array(*ext, "variants", vp) : nullptr;
  for (size_t i = 0; variants && i < variants->size() && !p.failed(); ++i) {
    const std::string path = vp + ".variants[" + std::to_string(i) + "]";
    if (!(*variants)[i].is_object()) {
      p.fail(path, "must be an object");
      break;
    }
    std::string name = p.string((*variants)[i], "name", path, "", true);
    doc.variants.push_back(std::move(name));
  }
}

// A primitive's KHR_materials_variants mappings: which material each variant selects.
void parseVariantMappings(Parser& p, const json& ext, const std::string& path, const Document& doc,
                          const Counts& count, PrimitiveDesc& prim) {
  const json* v = p.object(ext, "KHR_materials_variants", path);
  const std::string vp = path + ".KHR_materials_variants";
  const json* maps = v ? p.array(*v, "mappings", vp) : nullptr;
  for (size_t k = 0; maps && k < maps->size() && !p.failed(); ++k) {
    const std::string mp = vp + ".mappings[" + std::to_string(k) + "]";
    const json& mo = (*maps)[k];
    if (!mo.is_object()) {
      p.fail(mp, "must be an object");
      break;
    }
    std::pair<int, std::vector<int>> mapping;
    mapping.first = p.index(mo, "material", mp, count.materials, "materials", true);
    const json* vs = p.array(mo, "variants", mp);
    if (!vs) p.fail(mp, "missing required 'variants'");
    for (size_t i = 0; vs && i < vs->size() && !p.failed(); ++i) {
      mapping.second.push_back(p.checkIndex((*vs)[i], mp + ".variants[" + std::to_string(i) + "]",
                                            doc.variants.size(),
                                            "KHR_materials_variants variants"));
    }
    prim.variantMappings.push_back(std::move(mapping));
  }
}

// Parses the 'meshes' array.
void parseMeshes(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                 [[maybe_unused]] const Counts& count) {
  forEach(p, root, "meshes", [&](const json& o, const std::string& path, size_t) {
    MeshDesc m;
    m.name = p.string(o, "name", path);
    const json* prims = p.array(o, "primitives", path);
    if (!prims) p.fail(path, "missing required 'primitives'");
    for (size_t i = 0; prims && i < prims->size() && !p.failed(); ++i) {
      const json& po = (*prims)[i];
      const std::string pp = path + ".primitives[" + std::to_string(i) + "]";
      PrimitiveDesc prim;
      const json* attrs = p.object(po, "attributes", pp);
      if (!attrs) {
        p.fail(pp, "missing required 'attributes'");
        break;
      }
      for (auto it = attrs->begin(); it != attrs->end(); ++it) {
        prim.attributes[it.key()] =
            p.checkIndex(it.value(), pp + ".attributes." + it.key(), count.accessors, "accessors");
      }
      prim.indices = p.index(po, "indices", pp, count.accessors, "accessors");
      prim.material = p.index(po, "material", pp, count.materials, "materials");
      prim.mode = static_cast<int>(p.integer(po, "mode", pp, 4, false, 0, 6));
      if (const json* targets = p.array(po, "targets", pp)) {
        for (size_t t = 0; t < targets->size() && !p.failed(); ++t) {
          const std::string tp = pp + ".targets[" + std::to_string(t) + "]";
          std::map<std::string, int> target;
          if ((*targets)[t].is_object()) {
            for (auto it = (*targets)[t].begin(); it != (*targets)[t].end(); ++it) {
              target[it.key()] =
                  p.checkIndex(it.value(), tp + "." + it.key(), count.accessors, "accessors");
            }
          } else {
            p.fail(tp, "must be an object");
          }
          prim.targets.push_back(std::move(target));
        }
      }
      if (const json* ext = p.object(po, "extensions", pp)) {
        if (const json* d = p.object(*ext, "KHR_draco_mesh_compression", pp + ".extensions")) {
          const std::string dp = pp + ".extensions.KHR_draco_mesh_compression";
          DracoDesc draco;
          draco.bufferView = p.index(*d, "bufferView", dp, count.views, "bufferViews", true);
          if (const json* da = p.object(*d, "attributes", dp)) {
            for (auto it = da->begin(); it != da->end(); ++it) {
              int64_t id = 0;
              if (!p.asInteger(it.value(), 0, std::numeric_limits<int32_t>::max(), id)) {
                p.fail(dp + ".attributes." + it.key(), "must be a non-negative integer");
              }
              draco.attributes[it.key()] = static_cast<int>(id);
            }
          }
          prim.draco = draco;
        }
        parseVariantMappings(p, *ext, pp + ".extensions", doc, count, prim);
      }
      m.primitives.push_back(std::move(prim));
    }
    m.weights = weightsOf(p, o, path);
    doc.meshes.push_back(std::move(m));
  });
}

// Parses EXT_lights_area and KHR_lights_punctual (root extensions; before the nodes that refer to
// them).
void parseLights(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                 [[maybe_unused]] const Counts& count) {
  // Lights live in root extensions; parse them before the nodes that refer to them.
  const json* rootExt = p.object(root, "extensions", "glTF");
  if (const json* area = rootExt ? p.object(*rootExt, "EXT_lights_area", "extensions") : nullptr) {
    if (const json* lights = p.array(*area, "lights", "extensions.EXT_lights_area")) {
      for (size_t i = 0; i < lights->size() && !p.failed(); ++i) {
        const json& l = (*lights)[i];
        const std::string lp = "extensions.EXT_lights_area.lights[" + std::to_string(i) + "]";
        LightDesc d;
        d.name = p.string(l, "name", lp);
        const std::string type = p.string(l, "type", lp, "rect");
        const LightKind* kind = lightKindNamed(type, true);
        if (!kind) ctx.warn(lp + ": unknown area light type '" + type + "', treated as 'rect'");
        d.type = kind ? kind->type : LightType::Rect;
        d.color = p.vec<3>(l, "color", lp, glm::vec3(1.0f));
        // NaN cannot be written in JSON; a negative intensity is dropped later with a warning.
        d.intensity = static_cast<float>(p.number(l, "intensity", lp, 1000.0));
        d.size = static_cast<float>(p.number(l, "size", lp, 1.0));
        if (const json* rect = p.object(l, "rect", lp)) {
          d.aspect = static_cast<float>(p.number(*rect, "aspect", lp + ".rect", 1.0));
        }
        doc.areaLights.push_back(d);
      }
    }
  }
  if (const json* punctual =
          rootExt ? p.object(*rootExt, "KHR_lights_punctual", "extensions") : nullptr) {
    if (const json* lights = p.array(*punctual, "lights", "extensions.KHR_lights_punctual")) {
      for (size_t i = 0; i < lights->size() && !p.failed(); ++i) {
        const json& l = (*lights)[i];
        const std::string lp = "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]";
        LightDesc d;
        d.name = p.string(l, "name", lp);
        const std::string type = p.string(l, "type", lp, "", true);
        if (const LightKind* kind = lightKindNamed(type, false)) {
          d.type = kind->type;
        } else if (!p.failed()) {
          p.fail(lp + ".type", "unknown punctual light type '" + type + "'");
        }
        d.color = p.vec<3>(l, "color", lp, glm::vec3(1.0f));
        d.intensity = static_cast<float>(p.number(l, "intensity", lp, 1.0));
        d.range = static_cast<float>(p.number(l, "range", lp, 0.0));
        if (const json* spot = p.object(l, "spot", lp)) {
          d.innerConeAngle =
              static_cast<float>(p.number(*spot, "innerConeAngle", lp + ".spot", 0.0));
          d.outerConeAngle =
              static_cast<float>(p.number(*spot, "outerConeAngle", lp + ".spot", 0.785398163));
        }
        doc.punctualLights.push_back(d);
      }
    }
  }
}

// Parses the 'nodes' array.
void parseNodes(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                [[maybe_unused]] const Counts& count) {
  forEach(p, root, "nodes", [&](const json& o, const std::string& path, size_t) {
    NodeDesc n;
    n.name = p.string(o, "name", path);
    if (const json* children = p.array(o, "children", path)) {
      for (size_t i = 0; i < children->size(); ++i) {
        n.children.push_back(p.checkIndex(
            (*children)[i], path + ".children[" + std::to_string(i) + "]", count.nodes, "nodes"));
      }
    }
    n.mesh = p.index(o, "mesh", path, count.meshes, "meshes");
    if (o.contains("weights")) n.weights = weightsOf(p, o, path);
    n.skin = p.index(o, "skin", path, count.skins, "skins");
    n.camera = p.index(o, "camera", path, count.cameras, "cameras");
    if (const auto e = o.find("extras"); e != o.end() && e->is_object()) {
      n.lightProxy = e->contains("area_light_proxy");
    }
    float m[16];
    if (p.numbers<16>(o, "matrix", path, m)) {
      n.hasMatrix = true;
      n.local = glm::mat4(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8], m[9], m[10], m[11],
                          m[12], m[13], m[14], m[15]);
    } else {
      n.translation = p.vec<3>(o, "translation", path, glm::vec3(0.0f));
      const glm::vec4 r = p.vec<4>(o, "rotation", path, glm::vec4(0, 0, 0, 1));
      n.scale = p.vec<3>(o, "scale", path, glm::vec3(1.0f));
      // glTF stores quaternions as (x, y, z, w); glm::quat's constructor takes w first.
      glm::quat q(r.w, r.x, r.y, r.z);
      const float len = glm::length(q);
      n.rotation = len > 0.0f ? q / len : glm::quat(1, 0, 0, 0);
      n.local = composeTrs(n);
    }
    if (const json* ext = p.object(o, "extensions", path)) {
      if (const json* a = p.object(*ext, "EXT_lights_area", path + ".extensions")) {
        n.areaLight = p.index(*a, "light", path + ".extensions.EXT_lights_area",
                              doc.areaLights.size(), "EXT_lights_area lights", true);
      }
      if (const json* l = p.object(*ext, "KHR_lights_punctual", path + ".extensions")) {
        n.punctualLight = p.index(*l, "light", path + ".extensions.KHR_lights_punctual",
                                  doc.punctualLights.size(), "KHR_lights_punctual lights", true);
      }
      const std::string ip = path + ".extensions.EXT_mesh_gpu_instancing";
      if (const json* in = p.object(*ext, "EXT_mesh_gpu_instancing", path + ".extensions")) {
        n.instanced = true;
        if (const json* at = p.object(*in, "attributes", ip)) {
          const std::string ap = ip + ".attributes";
          n.instanceTranslation = p.index(*at, "TRANSLATION", ap, count.accessors, "accessors");
          n.instanceRotation = p.index(*at, "ROTATION", ap, count.accessors, "accessors");
          n.instanceScale = p.index(*at, "SCALE", ap, count.accessors, "accessors");
        }
      }
    }
    doc.nodes.push_back(std::move(n));
  });
}

// Parses the 'skins' array (joints, inverseBindMatrices; the skeleton root is not needed).
void parseSkins(Parser& p, const json& root, Document& doc, const Counts& count) {
  forEach(p, root, "skins", [&](const json& o, const std::string& path, size_t) {
    SkinDesc s;
    const json* joints = p.array(o, "joints", path);
    if (!joints) p.fail(path, "missing required 'joints'");
    for (size_t i = 0; joints && i < joints->size(); ++i) {
      s.joints.push_back(p.checkIndex((*joints)[i], path + ".joints[" + std::to_string(i) + "]",
                                      count.nodes, "nodes"));
    }
    s.inverseBindMatrices = p.index(o, "inverseBindMatrices", path, count.accessors, "accessors");
    doc.skins.push_back(std::move(s));
  });
}

// Parses the 'scenes' array.
void parseScenes(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                 [[maybe_unused]] const Counts& count) {
  forEach(p, root, "scenes", [&](const json& o, const std::string& path, size_t) {
    SceneDesc s;
    s.name = p.string(o, "name", path);
    if (const json* nodes = p.array(o, "nodes", path)) {
      for (size_t i = 0; i < nodes->size(); ++i) {
        s.nodes.push_back(p.checkIndex((*nodes)[i], path + ".nodes[" + std::to_string(i) + "]",
                                       count.nodes, "nodes"));
      }
    }
    doc.scenes.push_back(std::move(s));
  });
}

// Parses the 'textures' array.
void parseTextures(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                   [[maybe_unused]] const Counts& count) {
  forEach(p, root, "textures", [&](const json& o, const std::string& path, size_t) {
    TextureDesc t;
    t.source = p.index(o, "source", path, count.images, "images");
    t.sampler = p.index(o, "sampler", path, count.samplers, "samplers");
    if (const json* ext = p.object(o, "extensions", path)) {
      const std::string ep = path + ".extensions.KHR_texture_basisu";
      if (const json* b = p.object(*ext, "KHR_texture_basisu", path + ".extensions"))
        t.basisuSource = p.index(*b, "source", ep, count.images, "images", true);
    }
    doc.textures.push_back(t);
  });
}

// Parses the 'images' array.
void parseImages(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                 [[maybe_unused]] const Counts& count) {
  forEach(p, root, "images", [&](const json& o, const std::string& path, size_t) {
    ImageDesc im;
    im.name = p.string(o, "name", path);
    im.uri = p.string(o, "uri", path);
    im.mimeType = p.string(o, "mimeType", path);
    im.bufferView = p.index(o, "bufferView", path, count.views, "bufferViews");
    if (!p.failed() && im.uri.empty() && im.bufferView < 0) {
      p.fail(path, "needs a 'uri' or a 'bufferView'");
    }
    doc.images.push_back(std::move(im));
  });
}

// Parses the 'samplers' array.
void parseSamplers(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                   [[maybe_unused]] const Counts& count) {
  forEach(p, root, "samplers", [&](const json& o, const std::string& path, size_t) {
    SamplerDesc s;
    s.magFilter = static_cast<int>(p.integer(o, "magFilter", path, s.magFilter));
    s.minFilter = static_cast<int>(p.integer(o, "minFilter", path, s.minFilter));
    s.wrapS = static_cast<int>(p.integer(o, "wrapS", path, s.wrapS));
    s.wrapT = static_cast<int>(p.integer(o, "wrapT", path, s.wrapT));
    doc.samplers.push_back(s);
  });
}

// Parses the 'cameras' array.
void parseCameras(Parser& p, const json& root, Document& doc, [[maybe_unused]] LoadContext& ctx,
                  [[maybe_unused]] const Counts& count) {
  forEach(p, root, "cameras", [&](const json& o, const std::string& path, size_t) {
    CameraDesc c;
    c.name = p.string(o, "name", path);
    const std::string type = p.string(o, "type", path, "", true);
    if (type == "perspective") {
      const json* persp = p.object(o, "perspective", path);
      if (!persp) {
        p.fail(path, "missing 'perspective'");
      } else {
        const std::string pp = path + ".perspective";
        c.yfov = static_cast<float>(p.number(*persp, "yfov", pp, 0.8, true));
        c.aspect = static_cast<float>(p.number(*persp, "aspectRatio", pp, 0.0));
        c.znear = static_cast<float>(p.number(*persp, "znear", pp, 0.05, true));
        c.zfar = static_cast<float>(p.number(*persp, "zfar", pp, 0.0));
        if (!p.failed() && (c.yfov <= 0.0f || c.yfov >= 3.14159f || c.znear <= 0.0f ||
                            (c.zfar != 0.0f && c.zfar <= c.znear))) {
          p.fail(pp, "needs 0 < yfov < pi and 0 < znear < zfar");
        }
      }
    } else if (type == "orthographic") {
      c.perspective = false;
      const json* ortho = p.object(o, "orthographic", path);
      if (!ortho) {
        p.fail(path, "missing 'orthographic'");
      } else {
        const std::string op = path + ".orthographic";
        c.xmag = static_cast<float>(p.number(*ortho, "xmag", op, 1.0, true));
        c.ymag = static_cast<float>(p.number(*ortho, "ymag", op, 1.0, true));
        c.znear = static_cast<float>(p.number(*ortho, "znear", op, 0.0, true));
        c.zfar = static_cast<float>(p.number(*ortho, "zfar", op, 1.0, true));
        if (!p.failed() && (!(c.xmag != 0.0f) || !(c.ymag > 0.0f) || !(c.znear >= 0.0f) ||
                            !(c.zfar > c.znear) || !std::isfinite(c.zfar))) {
          p.fail(op, "needs xmag != 0, ymag > 0 and 0 <= znear < zfar");
        }
      }
    } else if (!p.failed()) {
      p.fail(path + ".type", "unknown camera type '" + type + "'");
    }
    doc.cameras.push_back(std::move(c));
  });
}

}  // namespace

Result<Document> parseDocument(std::string_view text, LoadContext& ctx) {
  // Some writers pad the GLB JSON chunk with NULs instead of spaces.
  while (!text.empty() && (text.back() == '\0' || text.back() == ' ')) text.remove_suffix(1);
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {
    // nlohmann's message is one line: "[json.exception.parse_error.101] parse error at ...".
    std::string what = e.what();
    const size_t bracket = what.find("] ");
    if (bracket != std::string::npos) what = what.substr(bracket + 2);
    return ctx.error("bad JSON: " + what);
  }
  if (!root.is_object()) return ctx.error("bad JSON: the top level is not an object");

  Parser p;
  Document doc;
  const json* asset = p.object(root, "asset", "glTF");
  if (!asset) return ctx.error("not a glTF file (no 'asset' object)");
  const std::string version = p.string(*asset, "version", "asset");
  if (!version.empty() && version[0] != '2') {
    return ctx.error("unsupported glTF version '" + version + "' (only 2.x is supported)");
  }

  auto strings = [&](const char* key, std::vector<std::string>& out) {
    if (const json* arr = p.array(root, key, "glTF")) {
      for (const json& e : *arr) {
        if (e.is_string()) out.push_back(e.get<std::string>());
      }
    }
  };
  strings("extensionsUsed", doc.extensionsUsed);
  strings("extensionsRequired", doc.extensionsRequired);

  const Counts count{.buffers = arraySize(root, "buffers"),
                     .views = arraySize(root, "bufferViews"),
                     .accessors = arraySize(root, "accessors"),
                     .meshes = arraySize(root, "meshes"),
                     .nodes = arraySize(root, "nodes"),
                     .materials = arraySize(root, "materials"),
                     .textures = arraySize(root, "textures"),
                     .images = arraySize(root, "images"),
                     .samplers = arraySize(root, "samplers"),
                     .cameras = arraySize(root, "cameras"),
                     .skins = arraySize(root, "skins")};

  parseBuffers(p, root, doc, ctx, count);

  parseBufferViews(p, root, doc, ctx, count);

  parseAccessors(p, root, doc, ctx, count);

  parseVariants(p, root, doc);
  parseMeshes(p, root, doc, ctx, count);

  parseLights(p, root, doc, ctx, count);
  parseNodes(p, root, doc, ctx, count);

  parseScenes(p, root, doc, ctx, count);
  parseSkins(p, root, doc, count);
  doc.scene = p.index(root, "scene", "glTF", doc.scenes.size(), "scenes");

  parseMaterials(p, root, doc, ctx, count.textures);

  parseTextures(p, root, doc, ctx, count);

  parseImages(p, root, doc, ctx, count);

  parseSamplers(p, root, doc, ctx, count);

  parseCameras(p, root, doc, ctx, count);
  parseAnimations(p, root, doc, count.accessors, count.nodes);

  if (p.failed()) return ctx.error(p.error());
  return doc;
}

}  // namespace penumbra::gltf
