#include "gpu/gpu_deformation.h"

#include <algorithm>
#include <span>
#include <string>

namespace penumbra {
namespace {

template <class T>
Status addRest(GpuDeformation& g, int location, const std::vector<T>& data, int components) {
  auto buf = gl::Buffer::create(gl::BufferKind::Vertex, std::span<const T>(data));
  if (!buf) return buf.error();
  g.rest.setAttribute(location, *buf, components, gl::AttribType::Float, false, 0, 0);
  g.buffers.push_back(std::move(*buf));
  return {};
}

}  // namespace

Result<std::unique_ptr<GpuDeformation>> GpuDeformation::create(const Deformation& d, int mesh) {
  auto g = std::make_unique<GpuDeformation>();
  g->rest = gl::VertexArray::create();
  g->mesh = mesh;
  g->vertexCount = static_cast<int>(d.positions.size());
  g->skinned = !d.joints.empty();
  g->tangents = !d.tangents.empty();
  g->targets = std::min(static_cast<int>(d.targets.size()), kMaxMorphTargets);
  PN_TRY(addRest(*g, 0, d.positions, 3));
  if (!d.normals.empty()) {
    PN_TRY(addRest(*g, 1, d.normals, 3));
  } else {
    g->rest.setConstant(1, 0, 0, 1, 0);
  }
  if (g->tangents) PN_TRY(addRest(*g, 2, d.tangents, 4));
  if (g->skinned) {
    PN_TRY(addRest(*g, kDeformJointsLocation, d.joints, 4));
    PN_TRY(addRest(*g, kDeformWeightsLocation, d.weights, 4));
  }
  for (const glm::vec3& p : d.positions) g->restBounds.extend(p);

  // Displacements: three texels (position, normal, tangent) per target and vertex.
  const size_t n = d.positions.size();
  g->targetRange.resize(static_cast<size_t>(g->targets));
  if (g->targets > 0) {
    const size_t texels = 3 * n * static_cast<size_t>(g->targets);
    const int width = static_cast<int>(std::min<size_t>(texels, 2048));
    const int height = static_cast<int>((texels + static_cast<size_t>(width) - 1) /
                                        static_cast<size_t>(width));
    std::vector<glm::vec4> data(static_cast<size_t>(width) * static_cast<size_t>(height),
                                glm::vec4(0.0f));
    for (size_t t = 0; t < static_cast<size_t>(g->targets); ++t) {
      const Deformation::Target& target = d.targets[t];
      const std::vector<glm::vec3>* parts[3] = {&target.positions, &target.normals,
                                                &target.tangents};
      for (size_t a = 0; a < 3; ++a) {
        if (parts[a]->size() != n) continue;
        for (size_t v = 0; v < n; ++v) {
          data[(t * 3 + a) * n + v] = glm::vec4((*parts[a])[v], 0.0f);
        }
      }
      for (const glm::vec3& delta : target.positions) g->targetRange[t].extend(delta);
      if (!g->targetRange[t].valid()) g->targetRange[t].extend(glm::vec3(0.0f));
    }
    gl::TextureDesc desc{.width = width, .height = height, .format = gl::PixelFormat::RGBA32F};
    desc.sampler.minFilter = desc.sampler.magFilter = gl::Filter::Nearest;
    auto tex = gl::Texture2D::create(desc);
    if (!tex) return tex.error();
    tex->upload(0, data.data(), gl::DataType::Float);
    g->morphs = std::move(*tex);
    g->morphWidth = width;
  }

  if (g->skinned) {
    // Each joint's box over the vertices it moves (weight > 0), in bind space.
    int joints = 0;
    for (const glm::vec4& j : d.joints) {
      joints = std::max(joints, static_cast<int>(std::max(std::max(j.x, j.y), std::max(j.z, j.w))) + 1);
    }
    g->jointBoxes.resize(static_cast<size_t>(joints));
    for (size_t v = 0; v < n; ++v) {
      for (int k = 0; k < 4; ++k) {
        if (d.weights[v][k] > 0.0f) {
          g->jointBoxes[static_cast<size_t>(d.joints[v][k])].extend(d.positions[v]);
        }
      }
    }
  }
  return g;
}

Bounds GpuDeformation::posedBounds(const std::vector<float>& weights,
                                   const std::vector<glm::mat4>* joints) const {
  // The morph targets move a vertex by at most the weighted sum of their displacement ranges.
  glm::vec3 lo(0.0f), hi(0.0f);
  for (size_t t = 0; t < targetRange.size() && t < weights.size(); ++t) {
    const glm::vec3 a = weights[t] * targetRange[t].min, b = weights[t] * targetRange[t].max;
    lo += glm::min(a, b);
    hi += glm::max(a, b);
  }
  auto grown = [&](const Bounds& box) {
    Bounds out;
    if (box.valid()) {
      out.extend(box.min + lo);
      out.extend(box.max + hi);
    }
    return out;
  };
  if (!skinned || !joints) return grown(restBounds);
  // A skinned vertex is a convex blend of its joints' transforms of it: the union of each
  // joint's transformed box holds it.
  Bounds out;
  for (size_t j = 0; j < jointBoxes.size() && j < joints->size(); ++j) {
    const Bounds box = grown(jointBoxes[j]);
    if (box.valid()) out.extend(box.transformed((*joints)[j]));
  }
  return out;
}

}  // namespace penumbra
