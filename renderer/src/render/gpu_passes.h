// GpuPasses, one part of Renderer::Impl (render/renderer_impl.h): what draws. The context's
// capabilities, the shader library, the frame targets and every pass object: the passes made
// when the renderer starts, the targets and shadow maps when a frame first needs them.
#pragma once

#include <algorithm>
#include <optional>

#include "gl/capabilities.h"
#include "gl/program.h"
#include "passes/accumulate_pass.h"
#include "passes/deform_pass.h"
#include "passes/effect_chain.h"
#include "passes/lighting_pass.h"
#include "passes/limits.h"
#include "passes/occlusion_pass.h"
#include "passes/point_shadow_pass.h"
#include "passes/prepass.h"
#include "passes/probe_volume.h"
#include "passes/shadow_pass.h"
#include "passes/targets.h"
#include "penumbra/renderer.h"

namespace penumbra {

struct GpuPasses {
  gl::Capabilities caps;
  gl::ShaderLibrary library;
  std::optional<passes::RenderTargets> targets;
  std::optional<passes::ShadowPass> shadows;
  std::optional<passes::PointShadowPass> pointShadows;
  std::optional<passes::Prepass> prepass;
  std::optional<passes::LightingPass> lighting;
  std::optional<passes::AccumulatePass> accumulate;
  std::optional<passes::OcclusionPass> occlusionPass;
  passes::EffectChain effects;                // post effects, tone mapping last
  std::optional<passes::ProbeVolume> probes;  // absent without renderable half floats
  std::optional<passes::DeformPass> deform;   // made at the first pose (Renderer::setPose)

  // The capabilities, the shaders' common defines and the passes every frame uses.
  Status createPasses(const RendererOptions& options) {
    caps = gl::queryCapabilities(options.desktopGl, {.forceHalfFloat = options.forceHalfFloat});
    library.setCommonDefines(passes::commonDefines());
    auto lit = passes::LightingPass::create(library);
    if (!lit) return lit.error();
    lighting.emplace(std::move(*lit));
    auto pre = passes::Prepass::create(library);
    if (!pre) return pre.error();
    prepass.emplace(std::move(*pre));
    auto acc = passes::AccumulatePass::create(library);
    if (!acc) return acc.error();
    accumulate.emplace(std::move(*acc));
    auto occ = passes::OcclusionPass::create(library);
    if (!occ) return occ.error();
    occlusionPass.emplace(std::move(*occ));
    if (caps.colorBufferHalfFloat) {
      auto pv = passes::ProbeVolume::create(library);
      if (!pv) return pv.error();
      probes.emplace(std::move(*pv));
    }
    return {};
  }

  // The frame targets and the shadow maps are made when something first draws or reads them,
  // not when settings change: a viewer sets its canvas's size and then a scene's settings
  // before its first frame, and made at each step the 1280x720 defaults took the phone page's
  // GPU memory at start-up to 116 MB (56 MB now). An allocation that fails is reported by the
  // call that needed it. (Settings that change their size reset them: Impl::applySettings.)
  Status ensureFrameResources(const RenderSettings& settings) {
    if (!targets) {
      auto t = passes::RenderTargets::create(
          settings.width, settings.height, caps.accumulationFormat,
          // Half floats hold the prepass (view normal, linear depth) well enough for the
          // occlusion march's 0.2 % depth tolerance, at half the bandwidth of its random reads.
          caps.colorBufferHalfFloat ? gl::PixelFormat::RGBA16F : caps.accumulationFormat);
      if (!t) return t.error();
      targets.emplace(std::move(*t));
    }
    if (!shadows) {
      auto sp = passes::ShadowPass::create(library, settings.progressive.shadowMapSize);
      if (!sp) return sp.error();
      shadows.emplace(std::move(*sp));
    }
    if (!pointShadows) {
      // Cube maps: six faces each, so at most 1024 pixels a face (24 MB a light at 1024).
      auto pp = passes::PointShadowPass::create(library,
                                                std::min(settings.progressive.shadowMapSize, 1024));
      if (!pp) return pp.error();
      pointShadows.emplace(std::move(*pp));
    }
    return {};
  }

  // The displayed image of `shown` (the mean, or an early frame's mix with frame 1) into
  // `output` (the display target, or a host's framebuffer): the post effects, then tone
  // mapping (passes/effect_chain.h).
  Status drawDisplayed(const RenderSettings& settings, const passes::EffectOutput& output,
                       const gl::Texture2D& shown) {
    return effects.draw(library, shown, targets->width, targets->height, settings,
                        caps.colorBufferHalfFloat, output);
  }
};

}  // namespace penumbra
