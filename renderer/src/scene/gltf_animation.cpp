// glTF animations posed at one time: a still renderer shows an animated model as it stands at
// time t of one animation (the rest pose without one). Every channel is sampled on the CPU (STEP,
// LINEAR with shortest-path slerp for rotations, CUBICSPLINE), its node's translation, rotation,
// scale or morph weights replaced, before node transforms, skins and morphs are computed: the
// same path as the rest pose, so the converged image at time t is that of a file whose rest
// pose is that pose.
#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "scene/gltf_document.h"
#include "scene/gltf_json.h"

namespace penumbra::gltf {
namespace {

AnimationDesc::Path pathNamed(const std::string& s, bool& ok) {
  using P = AnimationDesc::Path;
  ok = true;
  if (s == "translation") return P::Translation;
  if (s == "rotation") return P::Rotation;
  if (s == "scale") return P::Scale;
  if (s == "weights") return P::Weights;
  ok = false;  // "pointer" (KHR_animation_pointer) and others: ignored with a warning
  return P::Translation;
}

// The sampler's value at `time` with `width` floats a key (4 for rotations).
std::vector<float> sample(const std::vector<float>& times, const std::vector<float>& values,
                          AnimationDesc::Interpolation interp, size_t width, float time,
                          bool rotation) {
  using I = AnimationDesc::Interpolation;
  const size_t keys = times.size();
  const size_t stride = interp == I::CubicSpline ? 3 * width : width;
  const size_t offset = interp == I::CubicSpline ? width : 0;  // the value between the tangents
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
  if (interp == I::Step) {
    std::copy_n(value(k), width, out.begin());
  } else if (interp == I::Linear && rotation) {
    const auto a = value(k), b = value(k + 1);
    const glm::quat qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
    const glm::quat q = glm::slerp(qa, glm::dot(qa, qb) < 0.0f ? -qb : qb, u);
    out = {q.x, q.y, q.z, q.w};
  } else if (interp == I::Linear) {
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

}  // namespace

void parseAnimations(Parser& p, const json& root, Document& doc, size_t accessorCount,
                     size_t nodeCount) {
  const json* list = p.array(root, "animations", "glTF");
  if (!list) return;
  for (size_t a = 0; a < list->size(); ++a) {
    const json& o = (*list)[a];
    const std::string path = "animations[" + std::to_string(a) + "]";
    AnimationDesc anim;
    anim.name = p.string(o, "name", path);
    if (const json* samplers = p.array(o, "samplers", path)) {
      for (size_t s = 0; s < samplers->size(); ++s) {
        const json& so = (*samplers)[s];
        const std::string sp = path + ".samplers[" + std::to_string(s) + "]";
        AnimationDesc::Sampler sampler;
        sampler.input = p.index(so, "input", sp, accessorCount, "accessors", true);
        sampler.output = p.index(so, "output", sp, accessorCount, "accessors", true);
        const std::string interp = p.string(so, "interpolation", sp);
        using I = AnimationDesc::Interpolation;
        sampler.interpolation = interp == "STEP"          ? I::Step
                                : interp == "CUBICSPLINE" ? I::CubicSpline
                                                          : I::Linear;
        if (!interp.empty() && interp != "STEP" && interp != "CUBICSPLINE" && interp != "LINEAR") {
          p.fail(sp + ".interpolation", "must be LINEAR, STEP or CUBICSPLINE");
        }
        anim.samplers.push_back(sampler);
      }
    }
    if (const json* channels = p.array(o, "channels", path)) {
      for (size_t c = 0; c < channels->size(); ++c) {
        const json& co = (*channels)[c];
        const std::string cp = path + ".channels[" + std::to_string(c) + "]";
        AnimationDesc::Channel channel;
        channel.sampler = p.index(co, "sampler", cp, anim.samplers.size(), "samplers", true);
        if (const json* target = p.object(co, "target", cp)) {
          channel.node = p.index(*target, "node", cp + ".target", nodeCount, "nodes");
          channel.path = pathNamed(p.string(*target, "path", cp + ".target"), channel.known);
        }
        anim.channels.push_back(channel);
      }
    }
    doc.animations.push_back(std::move(anim));
  }
}

float animationDuration(Document& doc, int animation, LoadContext& ctx) {
  float end = 0.0f;
  for (const AnimationDesc::Sampler& s : doc.animations[static_cast<size_t>(animation)].samplers) {
    auto times = readFloats(doc, s.input, ctx, "animation input");
    if (times.ok() && !times->empty() && std::isfinite(times->back())) {
      end = std::max(end, times->back());
    }
  }
  return end;
}

Status poseAnimation(Document& doc, int animation, float time, LoadContext& ctx) {
  const AnimationDesc& anim = doc.animations[static_cast<size_t>(animation)];
  const std::string where = "animations[" + std::to_string(animation) + "]";
  std::vector<bool> moved(doc.nodes.size(), false);
  for (size_t c = 0; c < anim.channels.size(); ++c) {
    const AnimationDesc::Channel& ch = anim.channels[c];
    const std::string what = where + ".channels[" + std::to_string(c) + "]";
    if (ch.node < 0 || !ch.known) {
      ctx.warn(what +
               ": a target other than a node's translation, rotation, scale or weights; "
               "ignored");
      continue;
    }
    const AnimationDesc::Sampler& s = anim.samplers[static_cast<size_t>(ch.sampler)];
    auto times = readFloats(doc, s.input, ctx, what + " input");
    if (!times.ok()) return times.error();
    auto values = readFloats(doc, s.output, ctx, what + " output");
    if (!values.ok()) return values.error();
    NodeDesc& node = doc.nodes[static_cast<size_t>(ch.node)];
    using P = AnimationDesc::Path;
    const size_t perKey = s.interpolation == AnimationDesc::Interpolation::CubicSpline ? 3 : 1;
    size_t width = ch.path == P::Rotation ? 4 : 3;
    if (ch.path == P::Weights) {
      width = times->empty() ? 0 : values->size() / (times->size() * perKey);
    }
    if (times->empty() || width == 0 || values->size() != times->size() * perKey * width ||
        !std::is_sorted(times->begin(), times->end())) {
      return ctx.error(what + ": the sampler's input (" + std::to_string(times->size()) +
                       " times, ascending) and output (" + std::to_string(values->size()) +
                       " values) do not match");
    }
    const std::vector<float> v =
        sample(*times, *values, s.interpolation, width, time, ch.path == P::Rotation);
    if (ch.path == P::Weights) {
      node.weights = v;
      continue;
    }
    if (node.hasMatrix) {
      ctx.warn(what + ": node " + std::to_string(ch.node) +
               " has a matrix, which animations may not target; ignored");
      continue;
    }
    if (ch.path == P::Translation) node.translation = {v[0], v[1], v[2]};
    if (ch.path == P::Scale) node.scale = {v[0], v[1], v[2]};
    if (ch.path == P::Rotation) node.rotation = glm::quat(v[3], v[0], v[1], v[2]);
    moved[static_cast<size_t>(ch.node)] = true;
  }
  for (size_t n = 0; n < doc.nodes.size(); ++n) {
    if (moved[n]) doc.nodes[n].local = composeTrs(doc.nodes[n]);
  }
  return {};
}

glm::mat4 composeTrs(const NodeDesc& n) {
  glm::mat4 local = glm::mat4_cast(n.rotation);
  local[0] *= n.scale.x;
  local[1] *= n.scale.y;
  local[2] *= n.scale.z;
  local[3] = glm::vec4(n.translation, 1.0f);
  return local;
}

}  // namespace penumbra::gltf
