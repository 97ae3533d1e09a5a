#include "penumbra/settings.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

namespace penumbra {

const char* toneMapperName(ToneMapper t) {
  switch (t) {
    case ToneMapper::PbrNeutral:
      return "pbr-neutral";
    case ToneMapper::AcesFitted:
      return "aces";
    case ToneMapper::Reinhard:
      return "reinhard";
    case ToneMapper::None:
      return "none";
  }
  return "?";
}

Result<ToneMapper> parseToneMapper(std::string_view name) {
  std::string n(name);
  std::transform(n.begin(), n.end(), n.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (n == "pbr-neutral" || n == "neutral" || n == "khronos") return ToneMapper::PbrNeutral;
  if (n == "aces" || n == "aces-fitted") return ToneMapper::AcesFitted;
  if (n == "reinhard") return ToneMapper::Reinhard;
  if (n == "none" || n == "linear") return ToneMapper::None;
  return makeError("unknown tone mapper '" + std::string(name) +
                   "' (expected pbr-neutral, aces, reinhard or none)");
}

Status validate(const RenderSettings& s) {
  auto bad = [](const std::string& what) { return makeError("invalid setting: " + what); };
  if (s.width < 1 || s.height < 1 || s.width > 16384 || s.height > 16384) {
    return bad("resolution " + std::to_string(s.width) + "x" + std::to_string(s.height) +
               " (each side must be 1..16384)");
  }
  const auto& p = s.progressive;
  if (p.frames < 1 || p.frames > 4096) {
    return bad("frames " + std::to_string(p.frames) + " (must be 1..4096)");
  }
  if (!(p.directDelay >= 0.0f && p.directDelay < 1.0f)) {
    return bad("fd " + std::to_string(p.directDelay) + " (must be in [0, 1))");
  }
  if (!(p.occlusionDistance > 0.0f) || !std::isfinite(p.occlusionDistance)) {
    return bad("occlusion distance must be positive");
  }
  if (!(p.indirectClamp >= 0.0f) || !std::isfinite(p.indirectClamp)) {
    return bad("indirect clamp must be 0 (off) or positive");
  }
  if (p.lightSamples < 0 || p.lightSamples > 4096) {
    return bad("light samples " + std::to_string(p.lightSamples) + " (must be 0..4096)");
  }
  if (p.shadowMapSize < 16 || p.shadowMapSize > 8192 ||
      (p.shadowMapSize & (p.shadowMapSize - 1)) != 0) {
    return bad("shadow-map size " + std::to_string(p.shadowMapSize) +
               " (must be a power of two in 16..8192)");
  }
  if (!std::isfinite(s.exposure) || !std::isfinite(s.environmentIntensity) ||
      s.environmentIntensity < 0.0f || !std::isfinite(s.environmentRotation)) {
    return bad("exposure, environment intensity and rotation must be finite (intensity >= 0)");
  }
  if (!(s.backgroundBlur >= 0.0f && s.backgroundBlur <= 1.0f)) {
    return bad("background blur must be in [0, 1]");
  }
  return {};
}

}  // namespace penumbra
