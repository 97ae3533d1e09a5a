// glTF mesh primitives -> Primitive: attribute arrays from plain, sparse, quantized, meshopt or
// Draco sources; strips and fans turned into triangle lists; indices checked; triangles with
// non-finite positions dropped; normals and tangents generated where the renderer needs them.
#include <cmath>
#include <optional>

#include "scene/gltf_document.h"

namespace penumbra::gltf {
namespace {

struct AttributeSource {
  Document& doc;
  const PrimitiveDesc& prim;
  LoadContext& ctx;
  const std::string& what;
  DecodedDraco* draco;  // null when the primitive is not Draco-compressed (or uses its fallback)

  // The attribute as floats, or nullopt when the primitive does not have it. `allowed` lists
  // the accepted component counts (e.g. {3} for POSITION, {3, 4} for COLOR_0).
  Result<std::optional<std::vector<float>>> get(const std::string& name,
                                                std::initializer_list<int> allowed,
                                                int& components) {
    auto it = prim.attributes.find(name);
    if (it == prim.attributes.end()) return std::optional<std::vector<float>>{};
    const AccessorDesc& acc = doc.accessors[static_cast<size_t>(it->second)];
    bool ok = false;
    for (int n : allowed) ok = ok || acc.components == n;
    if (!ok || acc.type.rfind("MAT", 0) == 0) {
      return ctx.error("accessor " + std::to_string(it->second) + " (" + what + " " + name +
                       ") has unsupported type " + acc.type);
    }
    components = acc.components;
    if (draco) {
      auto d = draco->attributes.find(name);
      if (d != draco->attributes.end()) {
        return std::optional<std::vector<float>>(std::move(d->second));
      }
    }
    auto values = readFloats(doc, it->second, ctx, what + " " + name);
    if (!values.ok()) return values.error();
    return std::optional<std::vector<float>>(std::move(values).value());
  }
};

template <int N>
std::vector<glm::vec<N, float>> toVectors(const std::vector<float>& f) {
  std::vector<glm::vec<N, float>> out(f.size() / N);
  for (size_t i = 0; i < out.size(); ++i) {
    for (int c = 0; c < N; ++c) out[i][c] = f[i * N + static_cast<size_t>(c)];
  }
  return out;
}

// glTF topology -> triangle list (glTF 2.0 section 3.7.2.1).
std::vector<uint32_t> triangulate(const std::vector<uint32_t>& s, int mode, size_t& leftover) {
  std::vector<uint32_t> tris;
  leftover = 0;
  if (mode == 4) {
    leftover = s.size() % 3;
    tris.assign(s.begin(), s.end() - static_cast<std::ptrdiff_t>(leftover));
  } else if (s.size() >= 3) {
    tris.reserve((s.size() - 2) * 3);
    for (size_t i = 0; i + 2 < s.size(); ++i) {
      if (mode == 5) {
        // Every other strip triangle swaps two vertices to keep the winding consistent.
        const bool odd = (i % 2) != 0;
        tris.insert(tris.end(), {s[i], s[odd ? i + 2 : i + 1], s[odd ? i + 1 : i + 2]});
      } else {
        tris.insert(tris.end(), {s[i + 1], s[i + 2], s[0]});
      }
    }
  }
  return tris;
}

// The primitive's vertex attributes (POSITION required; the others, where present, of its
// length).
Status readAttributes(AttributeSource& src, Primitive& prim, LoadContext& ctx,
                      const std::string& what) {
  int comps = 0;
  auto positions = src.get("POSITION", {3}, comps);
  if (!positions.ok()) return positions.error();
  if (!*positions) return ctx.error(what + " has no POSITION attribute");
  prim.positions = toVectors<3>(**positions);
  const size_t vertexCount = prim.positions.size();

  auto checkCount = [&](const std::string& name, size_t count) -> Status {
    if (count != vertexCount) {
      return ctx.error(what + " " + name + " has " + std::to_string(count) +
                       " elements but POSITION has " + std::to_string(vertexCount));
    }
    return {};
  };
  auto normals = src.get("NORMAL", {3}, comps);
  if (!normals.ok()) return normals.error();
  if (*normals) {
    prim.normals = toVectors<3>(**normals);
    PN_TRY(checkCount("NORMAL", prim.normals.size()));
  }
  auto tangents = src.get("TANGENT", {4}, comps);
  if (!tangents.ok()) return tangents.error();
  if (*tangents) {
    prim.tangents = toVectors<4>(**tangents);
    PN_TRY(checkCount("TANGENT", prim.tangents.size()));
  }
  for (int set = 0; set < 2; ++set) {
    const std::string name = "TEXCOORD_" + std::to_string(set);
    auto uv = src.get(name, {2}, comps);
    if (!uv.ok()) return uv.error();
    if (*uv) {
      auto& dst = set == 0 ? prim.uv0 : prim.uv1;
      dst = toVectors<2>(**uv);
      PN_TRY(checkCount(name, dst.size()));
    }
  }
  auto colors = src.get("COLOR_0", {3, 4}, comps);
  if (!colors.ok()) return colors.error();
  if (*colors) {
    if (comps == 3) {
      const auto rgb = toVectors<3>(**colors);
      prim.colors.resize(rgb.size());
      for (size_t i = 0; i < rgb.size(); ++i) prim.colors[i] = glm::vec4(rgb[i], 1.0f);
    } else {
      prim.colors = toVectors<4>(**colors);
    }
    PN_TRY(checkCount("COLOR_0", prim.colors.size()));
  }
  return {};
}

// Drops the triangles touching a non-finite position: they would poison bounds and
// rasterisation.
void dropNonFinite(std::vector<uint32_t>& tris, const Primitive& prim, LoadContext& ctx,
                   const std::string& what) {
  const size_t vertexCount = prim.positions.size();
  std::vector<bool> finite(vertexCount);
  for (size_t v = 0; v < vertexCount; ++v) {
    const glm::vec3& p = prim.positions[v];
    finite[v] = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  }
  size_t dropped = 0;
  size_t kept = 0;
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    if (finite[tris[t]] && finite[tris[t + 1]] && finite[tris[t + 2]]) {
      for (int k = 0; k < 3; ++k) tris[kept++] = tris[t + static_cast<size_t>(k)];
    } else {
      ++dropped;
    }
  }
  tris.resize(kept);
  if (dropped) {
    ctx.warn(what + ": " + std::to_string(dropped) +
             " triangle(s) with non-finite (NaN or infinite) positions dropped");
  }
}

// Normals (generated flat or smooth where missing, else normalised) and tangents (generated
// for a normal map, else the clearcoat's, where missing).
Status finishShading(const Document& doc, const PrimitiveDesc& pd, Primitive& prim, bool indexed,
                     int mode, LoadContext& ctx, const std::string& what) {
  if (prim.normals.empty()) {
    // Without indices the file gives no sharing information: flat normals, as glTF asks.
    // Non-indexed strips and fans share vertices, so unweld them first.
    if (!indexed && mode != 4) {
      PN_TRY(ctx.reserve(prim.indices.size() * 64, what + " unwelded vertices"));
      unweldVertices(prim);
    }
    PN_TRY(ctx.reserve(prim.positions.size() * 12, what + " generated normals"));
    generateNormals(prim);
  } else {
    for (glm::vec3& n : prim.normals) {
      const float len = glm::length(n);
      n = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0, 0, 1);
    }
  }

  // Tangents for the normal map, else for the clearcoat's own normal map, else for the
  // anisotropy's direction (its texture's UV set, or TEXCOORD_0: the direction is given
  // relative to the tangent even without a texture).
  int uvSet = -1;
  if (pd.material >= 0) {
    const MaterialDesc& md = doc.materials[static_cast<size_t>(pd.material)];
    for (TextureSlot slot :
         {TextureSlot::Normal, TextureSlot::ClearcoatNormal, TextureSlot::Anisotropy}) {
      if (uvSet < 0 && md.textures[slotIndex(slot)].texture >= 0)
        uvSet = md.textures[slotIndex(slot)].texCoord;
    }
    if (uvSet < 0 && md.material.anisotropy > 0.0f) uvSet = 0;
  }
  if (uvSet >= 0 && prim.tangents.empty()) {
    const auto& uv = uvSet == 0 ? prim.uv0 : prim.uv1;
    if (uvSet > 1 || uv.empty()) {
      ctx.warn(what + ": the normal map (or anisotropy) uses TEXCOORD_" + std::to_string(uvSet) +
               ", which the primitive does not have; tangents are arbitrary");
    }
    PN_TRY(ctx.reserve(prim.positions.size() * 16, what + " generated tangents"));
    generateTangents(prim, uvSet);
  } else {
    for (glm::vec4& t : prim.tangents) t.w = t.w < 0.0f ? -1.0f : 1.0f;
  }
  return {};
}

// Poses a skinned primitive; its JOINTS_0 and WEIGHTS_0 come through `src`, so Draco-compressed
// ones are read from the decoded mesh (their accessors have no data of their own).
// With `keep`, its joints and weights also go there, for playback.
Status skinPrimitive(AttributeSource& src, const std::vector<glm::mat4>& joints, Primitive& prim,
                     LoadContext& ctx, const std::string& what, Deformation* keep) {
  int components = 0;
  auto ji = src.get("JOINTS_0", {4}, components);
  if (!ji.ok()) return ji.error();
  auto wi = src.get("WEIGHTS_0", {4}, components);
  if (!wi.ok()) return wi.error();
  if (!ji->has_value() || !wi->has_value()) return {};  // not skinned itself
  PN_TRY(applySkin(**ji, **wi, joints, prim, ctx, what));
  if (keep) {
    const std::vector<float>& j = **ji;
    const std::vector<float>& w = **wi;
    keep->joints.resize(j.size() / 4);
    keep->weights.resize(w.size() / 4);
    for (size_t v = 0; v < keep->joints.size(); ++v) {
      keep->joints[v] = {j[4 * v], j[4 * v + 1], j[4 * v + 2], j[4 * v + 3]};
      keep->weights[v] = {w[4 * v], w[4 * v + 1], w[4 * v + 2], w[4 * v + 3]};
    }
  }
  return {};
}

// A primitive whose triangles all have zero area draws nothing: say so rather than render an
// empty picture without a word (a skin or morph that collapses it, or data that is not there).
void warnIfFlat(const Primitive& prim, LoadContext& ctx, const std::string& what) {
  const auto& p = prim.positions;
  const auto& idx = prim.indices;
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    const glm::vec3 e1 = p[idx[t + 1]] - p[idx[t]], e2 = p[idx[t + 2]] - p[idx[t]];
    if (glm::length(glm::cross(e1, e2)) > 0.0f) return;
  }
  if (idx.empty()) return;
  ctx.warn(what + ": all " + std::to_string(idx.size() / 3) +
           " triangles have zero area (its positions, skinned or morphed, collapse), so it draws "
           "nothing");
}

Result<Primitive> convertPrimitive(Document& doc, const PrimitiveDesc& pd,
                                   const std::vector<float>& weights,
                                   const std::vector<glm::mat4>& joints, LoadContext& ctx,
                                   const std::string& what) {
  std::optional<DecodedDraco> draco;
  if (pd.draco) {
    auto pos = pd.attributes.find("POSITION");
    const bool hasFallback = pos != pd.attributes.end() &&
                             doc.accessors[static_cast<size_t>(pos->second)].bufferView >= 0;
    // Decoded whenever a decoder is there (natively always; in the browser once
    // web/lib/decoders.mjs has loaded it). Without one, uncompressed fallback data is read when
    // the file has it (the extension was optional), and otherwise decodeDraco reports the error.
    if (hasDraco() || !hasFallback) {
      auto decoded = decodeDraco(doc, pd, ctx, what);
      if (!decoded.ok()) return decoded.error();
      draco = std::move(decoded).value();
    }
  }
  AttributeSource src{doc, pd, ctx, what, draco ? &*draco : nullptr};

  Primitive prim;
  PN_TRY(readAttributes(src, prim, ctx, what));
  // Playback keeps the primitive as the file has it, and what poses it.
  std::optional<Primitive> base;
  auto deformation = std::make_shared<Deformation>();
  if (ctx.options.playback && (!pd.targets.empty() || !joints.empty())) {
    // The rest copy, joints and weights, and three displacements a target: within the budget.
    PN_TRY(ctx.reserve(prim.positions.size() * (72 + 36 * pd.targets.size()),
                       what + " playback data"));
    base = prim;
  }
  if (!pd.targets.empty()) {
    PN_TRY(applyMorphTargets(doc, pd, weights, prim, ctx, what));
    if (base) {
      auto targets = readMorphTargets(doc, pd, prim.positions.size(), ctx, what);
      if (!targets.ok()) return targets.error();
      deformation->targets = std::move(targets).value();
    }
  }
  if (!joints.empty()) {
    PN_TRY(skinPrimitive(src, joints, prim, ctx, what, base ? deformation.get() : nullptr));
  }
  const size_t vertexCount = prim.positions.size();

  // Index sequence in the primitive's topology.
  std::vector<uint32_t> sequence;
  const bool indexed = draco.has_value() || pd.indices >= 0;
  if (draco) {
    sequence = std::move(draco->indices);
  } else if (pd.indices >= 0) {
    auto idx = readIndices(doc, pd.indices, ctx, what + " indices");
    if (!idx.ok()) return idx.error();
    sequence = std::move(idx).value();
  } else {
    PN_TRY(ctx.reserve(vertexCount * 4, what + " indices"));
    sequence.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) sequence[i] = static_cast<uint32_t>(i);
  }
  for (size_t i = 0; i < sequence.size(); ++i) {
    if (sequence[i] >= vertexCount) {
      return ctx.error(what + ": index " + std::to_string(sequence[i]) + " (at position " +
                       std::to_string(i) + ") is out of range of the vertex count " +
                       std::to_string(vertexCount));
    }
  }
  size_t leftover = 0;
  // Draco always decodes to a triangle list, whatever the primitive's mode says.
  const int mode = draco ? 4 : pd.mode;
  if (mode != 4) PN_TRY(ctx.reserve(sequence.size() * 12, what + " triangulated indices"));
  std::vector<uint32_t> tris = triangulate(sequence, mode, leftover);
  if (leftover) {
    ctx.warn(what + ": " + std::to_string(leftover) +
             " trailing indices do not form a triangle; ignored");
  }

  dropNonFinite(tris, prim, ctx, what);
  prim.indices = std::move(tris);
  warnIfFlat(prim, ctx, what);
  prim.material = pd.material;
  if (!doc.variants.empty()) {
    prim.variantMaterials.assign(doc.variants.size(), pd.material);
    for (const auto& [material, variants] : pd.variantMappings) {
      for (int v : variants) prim.variantMaterials[static_cast<size_t>(v)] = material;
    }
  }

  PN_TRY(finishShading(doc, pd, prim, indexed, mode, ctx, what));

  for (uint32_t i : prim.indices) prim.bounds.extend(prim.positions[i]);
  if (base && (!deformation->targets.empty() || !deformation->joints.empty())) {
    if (base->positions.size() != prim.positions.size()) {
      // Flat normals of a strip or fan without indices unweld its vertices.
      ctx.warn(what + ": its vertices were unwelded for flat normals; it plays at its rest pose");
    } else {
      // Generated normals and tangents come from the unposed positions, as the pose moves them.
      base->indices = prim.indices;
      PN_TRY(finishShading(doc, pd, *base, indexed, mode, ctx, what));
      deformation->positions = std::move(base->positions);
      deformation->normals = std::move(base->normals);
      deformation->tangents = std::move(base->tangents);
      prim.deformation = std::move(deformation);
    }
  }
  return prim;
}

}  // namespace

Result<Mesh> convertMesh(Document& doc, int meshIndex, const std::vector<float>& weights,
                         const std::vector<glm::mat4>& joints, LoadContext& ctx) {
  const MeshDesc& md = doc.meshes[static_cast<size_t>(meshIndex)];
  const std::vector<float>& pose = weights.empty() ? md.weights : weights;
  Mesh mesh;
  mesh.name = md.name;
  for (size_t i = 0; i < md.primitives.size(); ++i) {
    const PrimitiveDesc& pd = md.primitives[i];
    const std::string what =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(i);
    if (pd.mode < 4) {
      static const char* kModes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
      ctx.warn(what + ": " + kModes[pd.mode] + " are not rendered; skipped");
      continue;
    }
    auto prim = convertPrimitive(doc, pd, pose, joints, ctx, what);
    if (!prim.ok()) return prim.error();
    mesh.primitives.push_back(std::move(prim).value());
  }
  return mesh;
}

}  // namespace penumbra::gltf
