#include "passes/occlusion_pass.h"

#include <array>
#include <utility>

#include "gpu/gpu_environment.h"
#include "passes/limits.h"
#include "passes/probe_volume.h"

namespace penumbra::passes {

namespace {
Result<FullscreenPass> tracePass(gl::ShaderLibrary& library, bool probes, bool probeCache) {
  return FullscreenPass::create(library, "occlusion_trace.frag", false,
                                {{"PN_PROBES", probes ? "1" : "0"},
                                 {"PN_PROBE_CACHE", probeCache ? "1" : "0"},
                                 {"PN_CAPTURE", "0"}});
}
}  // namespace

Result<OcclusionPass> OcclusionPass::create(gl::ShaderLibrary& library) {
  auto pass = tracePass(library, false, false);
  if (!pass) return pass.error();
  auto filter = FullscreenPass::create(library, "occlusion_filter.frag", false, {});
  if (!filter) return filter.error();
  return OcclusionPass(library, std::move(*pass), std::move(*filter));
}

glm::ivec2 OcclusionPass::blockOffset(int frame) {
  // Diagonal pairs first: two frames already sample both rows and columns.
  static constexpr std::array<glm::ivec2, 4> kOrder = {glm::ivec2(0, 0), glm::ivec2(1, 1),
                                                       glm::ivec2(1, 0), glm::ivec2(0, 1)};
  return kOrder[static_cast<size_t>(((frame % 4) + 4) % 4)];
}

Status OcclusionPass::trace(const OcclusionInputs& in) {
  RenderTargets& t = *in.targets;
  PN_CHECK(in.block == 1 || in.block == 2, "OcclusionPass: blocks of 1 or 2 pixels");
  PN_CHECK(in.environment != nullptr, "OcclusionPass: the environment is required");
  const bool probes = in.probes != nullptr && in.probes->active();
  const bool cached = probes && in.probeCache && static_cast<bool>(t.probeCache);
  std::unique_ptr<FullscreenPass>& probesPass = probesPass_[cached ? 1 : 0];
  // The probe variants only once the volume is looked up: frame 1's programs stay few.
  if (probes && !probesPass) {
    auto pass = tracePass(*library_, true, cached);
    if (!pass) return pass.error();
    probesPass = std::make_unique<FullscreenPass>(std::move(*pass));
  }
  PN_TRY(t.ensureOcclusion(in.block));
  t.occlusion.framebuffer.bind();
  gl::setViewport(0, 0, t.occlusionWidth(in.block), t.occlusionHeight(in.block));
  const FullscreenPass& pass = probes ? *probesPass : pass_;
  const gl::Program& p = pass.begin();
  in.environment->bind(p, in.environmentIntensity, in.environmentRotation);
  if (probes) in.probes->bind(p);
  if (cached) p.bind("uProbeCache", t.probeCache);
  p.bind("uPrepass", t.prepass.color);
  p.bind("uAccumulated", t.accumulation[static_cast<size_t>(t.current)].color);
  p.set("uIndirectEnabled", in.indirect ? 1 : 0);
  p.set("uIndirectClamp", in.indirectClamp > 0.0f ? in.indirectClamp : 3.0e38f);
  p.set("uOcclusionDistance", in.occlusionDistance);
  p.set("uView", in.view);
  p.set("uProjection", in.projection);
  p.set("uInvView", glm::inverse(in.view));
  p.set("uInvProjection", glm::inverse(in.projection));
  p.set("uViewOrigin", in.viewOrigin);
  p.set("uViewportSize", glm::vec2(t.width, t.height));
  p.set("uSequence", in.sequence);
  p.set("uBlock", in.block);
  p.set("uBlockOffset", in.block == 2 ? glm::vec2(blockOffset(in.frame)) : glm::vec2(0.0f));
  pass.draw();
  if (in.filter > 0.0f) filter(in);
  return {};
}

void OcclusionPass::filter(const OcclusionInputs& in) {
  RenderTargets& t = *in.targets;
  const gl::Program& p = filter_.begin();
  p.bind("uPrepass", t.prepass.color);
  p.set("uBlock", in.block);
  p.set("uStrength", in.filter);
  // Along rows into the spare target, then down columns back into the one the lighting reads.
  t.occlusionFiltered.framebuffer.bind();
  p.bind("uRays", t.occlusion.color);
  p.set("uVertical", 0);
  filter_.draw();
  t.occlusion.framebuffer.bind();
  p.bind("uRays", t.occlusionFiltered.color);
  p.set("uVertical", 1);
  filter_.draw();
}

}  // namespace penumbra::passes
