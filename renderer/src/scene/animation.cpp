// Animation channels sampled at a time, and a rig posed from them (penumbra/animation.h). The
// loader's still (gltf_animation.cpp) and playback (Renderer::setPose) both sample here.
#include "penumbra/animation.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "penumbra/error.h"

namespace penumbra {

std::vector<float> AnimationCurve::sample(float time) const {
  using I = Interpolation;
  const bool rotation = path == Path::Rotation;
  const size_t keys = times.size();
  PN_CHECK(keys > 0 && width > 0, "AnimationCurve::sample: an empty curve");
  const size_t stride = interpolation == I::CubicSpline ? 3 * width : width;
  const size_t offset = interpolation == I::CubicSpline ? width : 0;  // value between tangents
  auto value = [&](size_t k) {
    return values.begin() + static_cast<std::ptrdiff_t>(k * stride + offset);
  };
  std::vector<float> out(width);
  // Before the first key and after the last the sampler holds its end values (glTF 3.11).
  if (time <= times.front() || keys == 1) {
    std::copy_n(value(0), width, out.begin());
    return out;
  }
  if (time >= times.back()) {
    std::copy_n(value(keys - 1), width, out.begin());
    return out;
  }
  const size_t k =
      static_cast<size_t>(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
  const float dt = times[k + 1] - times[k];
  const float u = dt > 0.0f ? (time - times[k]) / dt : 0.0f;
  if (interpolation == I::Step) {
    std::copy_n(value(k), width, out.begin());
  } else if (interpolation == I::Linear && rotation) {
    const auto a = value(k), b = value(k + 1);
    const glm::quat qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
    const glm::quat q = glm::slerp(qa, glm::dot(qa, qb) < 0.0f ? -qb : qb, u);
    out = {q.x, q.y, q.z, q.w};
  } else if (interpolation == I::Linear) {
    for (size_t c = 0; c < width; ++c) out[c] = (1.0f - u) * value(k)[c] + u * value(k + 1)[c];
  } else {
    // Hermite: the key's value and out-tangent, the next key's in-tangent and value (glTF C.2).
    const float u2 = u * u, u3 = u2 * u;
    const float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2,
                h11 = u3 - u2;
    const auto v0 = value(k), v1 = value(k + 1);
    const auto outTangent = v0 + static_cast<std::ptrdiff_t>(width);
    const auto inTangent = v1 - static_cast<std::ptrdiff_t>(width);
    for (size_t c = 0; c < width; ++c) {
      out[c] = h00 * v0[c] + h10 * dt * outTangent[c] + h01 * v1[c] + h11 * dt * inTangent[c];
    }
  }
  if (rotation) {
    const float len =
        std::sqrt(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3]);
    if (len > 0.0f) {
      for (float& c : out) c /= len;
    }
  }
  return out;
}

const std::vector<float>& Pose::weightsOf(int mesh) const {
  static const std::vector<float> kNone;
  return mesh >= 0 && static_cast<size_t>(mesh) < weights.size()
             ? weights[static_cast<size_t>(mesh)]
             : kNone;
}

const std::vector<glm::mat4>* Pose::jointsOf(int skin) const {
  return skin >= 0 && static_cast<size_t>(skin) < joints.size() ? &joints[static_cast<size_t>(skin)]
                                                                : nullptr;
}

glm::mat4 composeTrs(const glm::vec3& translation, const glm::quat& rotation,
                     const glm::vec3& scale) {
  glm::mat4 local = glm::mat4_cast(rotation);
  local[0] *= scale.x;
  local[1] *= scale.y;
  local[2] *= scale.z;
  local[3] = glm::vec4(translation, 1.0f);
  return local;
}

namespace {

// The rig's nodes with clip `animation` (-1: none) applied at `time`.
std::vector<Rig::Node> posedNodes(const Rig& rig, int animation, float time) {
  std::vector<Rig::Node> nodes = rig.nodes;
  if (animation < 0 || static_cast<size_t>(animation) >= rig.clips.size()) return nodes;
  for (const AnimationCurve& curve : rig.clips[static_cast<size_t>(animation)]) {
    Rig::Node& node = nodes[static_cast<size_t>(curve.node)];
    const std::vector<float> v = curve.sample(time);
    using P = AnimationCurve::Path;
    if (curve.path == P::Weights) node.weights = v;
    if (curve.path == P::Translation) node.translation = {v[0], v[1], v[2]};
    if (curve.path == P::Scale) node.scale = {v[0], v[1], v[2]};
    if (curve.path == P::Rotation) node.rotation = glm::quat(v[3], v[0], v[1], v[2]);
  }
  return nodes;
}

// Node parts blended by weight (the weights sum to 1): translations, scales and morph weights
// linearly, rotations as normalised weighted sums on one side of the sphere (nlerp).
std::vector<Rig::Node> blendedNodes(const Rig& rig, std::span<const PoseLayer> layers) {
  float total = 0.0f;
  for (const PoseLayer& l : layers) total += std::max(l.weight, 0.0f);
  if (layers.empty() || !(total > 0.0f)) return rig.nodes;
  std::vector<Rig::Node> out = rig.nodes;
  for (Rig::Node& n : out) {
    n.translation = n.scale = glm::vec3(0.0f);
    n.rotation = glm::quat(0.0f, 0.0f, 0.0f, 0.0f);
    std::fill(n.weights.begin(), n.weights.end(), 0.0f);
  }
  for (const PoseLayer& layer : layers) {
    const float w = std::max(layer.weight, 0.0f) / total;
    if (w <= 0.0f) continue;
    const std::vector<Rig::Node> nodes = posedNodes(rig, layer.animation, layer.time);
    for (size_t i = 0; i < nodes.size(); ++i) {
      Rig::Node& o = out[i];
      o.translation += w * nodes[i].translation;
      o.scale += w * nodes[i].scale;
      const glm::quat q = glm::dot(o.rotation, nodes[i].rotation) < 0.0f ? -nodes[i].rotation
                                                                           : nodes[i].rotation;
      o.rotation = glm::quat(o.rotation.w + w * q.w, o.rotation.x + w * q.x,
                             o.rotation.y + w * q.y, o.rotation.z + w * q.z);
      o.weights.resize(std::max(o.weights.size(), nodes[i].weights.size()), 0.0f);
      for (size_t k = 0; k < nodes[i].weights.size(); ++k) o.weights[k] += w * nodes[i].weights[k];
    }
  }
  for (Rig::Node& n : out) {
    const float len = glm::length(n.rotation);
    n.rotation = len > 0.0f ? n.rotation / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  }
  return out;
}

}  // namespace

Pose poseRig(const Rig& rig, int animation, float time) {
  const PoseLayer layer{animation, time, 1.0f};
  return poseRig(rig, std::span<const PoseLayer>(&layer, 1));
}

Pose poseRig(const Rig& rig, std::span<const PoseLayer> layers) {
  std::vector<Rig::Node> nodes =
      layers.size() == 1 ? posedNodes(rig, layers[0].animation, layers[0].time)
                         : blendedNodes(rig, layers);
  // World transforms parent first (the loader checked the tree acyclic).
  std::vector<glm::mat4> world(nodes.size());
  std::vector<bool> done(nodes.size(), false);
  std::vector<int> chain;
  for (size_t i = 0; i < nodes.size(); ++i) {
    chain.clear();
    for (int v = static_cast<int>(i); v >= 0 && !done[static_cast<size_t>(v)];
         v = nodes[static_cast<size_t>(v)].parent) {
      chain.push_back(v);
    }
    for (auto c = chain.rbegin(); c != chain.rend(); ++c) {
      const int up = nodes[static_cast<size_t>(*c)].parent;
      const glm::mat4 base = up >= 0 ? world[static_cast<size_t>(up)] : glm::mat4(1.0f);
      const Rig::Node& n = nodes[static_cast<size_t>(*c)];
      world[static_cast<size_t>(*c)] =
          base * (n.hasMatrix ? n.matrix : composeTrs(n.translation, n.rotation, n.scale));
      done[static_cast<size_t>(*c)] = true;
    }
  }
  Pose pose;
  pose.instanceWorld.resize(rig.instanceNode.size(), glm::mat4(1.0f));
  for (size_t i = 0; i < rig.instanceNode.size(); ++i) {
    const int node = rig.instanceNode[i];
    if (node < 0 || rig.instanceSkinned[i]) continue;
    pose.instanceWorld[i] = world[static_cast<size_t>(node)] * rig.instanceLocal[i];
  }
  for (const Rig::Skin& skin : rig.skins) {
    std::vector<glm::mat4>& joints = pose.joints.emplace_back(skin.joints.size());
    for (size_t j = 0; j < skin.joints.size(); ++j) {
      joints[j] = world[static_cast<size_t>(skin.joints[j])] * skin.inverseBind[j];
    }
  }
  pose.weights.resize(rig.meshes.size());
  for (size_t m = 0; m < rig.meshes.size(); ++m) {
    const int node = rig.meshes[m].weightsNode;
    if (node >= 0) pose.weights[m] = nodes[static_cast<size_t>(node)].weights;
  }
  return pose;
}

}  // namespace penumbra
