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

Result<std::vector<AnimationCurve>> readClip(Document& doc, int animation, LoadContext& ctx) {
  const AnimationDesc& anim = doc.animations[static_cast<size_t>(animation)];
  const std::string where = "animations[" + std::to_string(animation) + "]";
  std::vector<AnimationCurve> curves;
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
    if (ch.path != P::Weights && doc.nodes[static_cast<size_t>(ch.node)].hasMatrix) {
      ctx.warn(what + ": node " + std::to_string(ch.node) +
               " has a matrix, which animations may not target; ignored");
      continue;
    }
    AnimationCurve curve;
    curve.node = ch.node;
    curve.path = static_cast<AnimationCurve::Path>(ch.path);
    curve.interpolation = static_cast<AnimationCurve::Interpolation>(s.interpolation);
    curve.width = width;
    curve.times = std::move(times).value();
    curve.values = std::move(values).value();
    curves.push_back(std::move(curve));
  }
  return curves;
}

void poseAnimation(Document& doc, const std::vector<AnimationCurve>& clip, float time) {
  std::vector<bool> moved(doc.nodes.size(), false);
  for (const AnimationCurve& curve : clip) {
    NodeDesc& node = doc.nodes[static_cast<size_t>(curve.node)];
    const std::vector<float> v = curve.sample(time);
    using P = AnimationCurve::Path;
    if (curve.path == P::Weights) {
      node.weights = v;
      continue;
    }
    if (curve.path == P::Translation) node.translation = {v[0], v[1], v[2]};
    if (curve.path == P::Scale) node.scale = {v[0], v[1], v[2]};
    if (curve.path == P::Rotation) node.rotation = glm::quat(v[3], v[0], v[1], v[2]);
    moved[static_cast<size_t>(curve.node)] = true;
  }
  for (size_t n = 0; n < doc.nodes.size(); ++n) {
    if (moved[n]) doc.nodes[n].local = composeTrs(doc.nodes[n]);
  }
}

glm::mat4 composeTrs(const NodeDesc& n) {
  return penumbra::composeTrs(n.translation, n.rotation, n.scale);
}

}  // namespace penumbra::gltf
