#include "viewer_settings.h"

#include <limits>
#include <string>
#include <type_traits>

namespace penumbra::web {

using nlohmann::json;

json settingsToJson(const RenderSettings& s) {
  const ProgressiveSettings& p = s.progressive;
  return {{"width", s.width},
          {"height", s.height},
          {"exposure", s.exposure},
          {"toneMapper", toneMapperName(s.toneMapper)},
          {"environmentIntensity", s.environmentIntensity},
          {"environmentRotation", s.environmentRotation},
          {"showBackground", s.showBackground},
          {"backgroundBlur", s.backgroundBlur},
          {"frames", p.frames},
          {"fd", p.directDelay},
          {"occlusionDistance", p.occlusionDistance},
          {"lightSamples", p.lightSamples},
          {"shadowMapSize", p.shadowMapSize},
          {"screenSpaceIndirect", p.screenSpaceIndirect},
          {"indirectClamp", p.indirectClamp},
          {"seed", p.seed}};
}

namespace {

// Reads changes[key] into out when present, with a one-line message on a type mismatch
// (nlohmann would throw; the viewer reports instead).
template <class T>
Status take(const json& changes, const char* key, T& out) {
  auto it = changes.find(key);
  if (it == changes.end() || it->is_null()) return {};
  bool ok = false;
  if constexpr (std::is_same_v<T, bool>) {
    ok = it->is_boolean();
  } else if constexpr (std::is_integral_v<T>) {
    // JSON.stringify writes whole numbers without a fraction, so integers arrive as such.
    // Out-of-range values are refused here, before a narrowing conversion could wrap them.
    ok = it->is_number_integer();
    if (ok && it->is_number_unsigned()) {
      ok = it->template get<unsigned long long>() <= std::numeric_limits<T>::max();
    } else if (ok) {
      const long long v = it->template get<long long>();
      ok = v >= static_cast<long long>(std::numeric_limits<T>::min()) &&
           (v < 0 || static_cast<unsigned long long>(v) <= std::numeric_limits<T>::max());
    }
  } else {
    ok = it->is_number();
  }
  if (!ok) {
    return makeError(std::string("setting '") + key + "' must be " +
                     (std::is_same_v<T, bool> ? "true or false"
                      : std::is_integral_v<T> ? "an integer"
                                              : "a number"));
  }
  out = it->template get<T>();
  return {};
}

}  // namespace

Result<RenderSettings> mergeSettings(const RenderSettings& base, const json& changes) {
  if (!changes.is_object()) return makeError("settings must be an object");
  static const char* const kKnown[] = {
      "width",  "height",       "exposure",           "toneMapper",        "environmentIntensity",
      "environmentRotation",    "showBackground",     "backgroundBlur",    "frames",
      "fd",     "occlusionDistance", "lightSamples",  "shadowMapSize",     "screenSpaceIndirect",
      "indirectClamp", "seed"};
  for (const auto& [key, value] : changes.items()) {
    bool known = false;
    for (const char* k : kKnown) known = known || key == k;
    if (!known) return makeError("unknown setting '" + key + "'");
  }
  RenderSettings s = base;
  ProgressiveSettings& p = s.progressive;
  PN_TRY(take(changes, "width", s.width));
  PN_TRY(take(changes, "height", s.height));
  PN_TRY(take(changes, "exposure", s.exposure));
  PN_TRY(take(changes, "environmentIntensity", s.environmentIntensity));
  PN_TRY(take(changes, "environmentRotation", s.environmentRotation));
  PN_TRY(take(changes, "showBackground", s.showBackground));
  PN_TRY(take(changes, "backgroundBlur", s.backgroundBlur));
  PN_TRY(take(changes, "frames", p.frames));
  PN_TRY(take(changes, "fd", p.directDelay));
  PN_TRY(take(changes, "occlusionDistance", p.occlusionDistance));
  PN_TRY(take(changes, "lightSamples", p.lightSamples));
  PN_TRY(take(changes, "shadowMapSize", p.shadowMapSize));
  PN_TRY(take(changes, "screenSpaceIndirect", p.screenSpaceIndirect));
  PN_TRY(take(changes, "indirectClamp", p.indirectClamp));
  PN_TRY(take(changes, "seed", p.seed));
  if (auto it = changes.find("toneMapper"); it != changes.end() && !it->is_null()) {
    if (!it->is_string()) return makeError("setting 'toneMapper' must be a name");
    auto t = parseToneMapper(it->get<std::string>());
    if (!t) return t.error();
    s.toneMapper = *t;
  }
  PN_TRY(validate(s));
  return s;
}

}  // namespace penumbra::web
