// RenderSettings <-> JSON for the web viewer's JS API (web/lib/penumbra.mjs). The keys are the
// API's names (camelCase, as in docs/web.md), not the scene-file layout: the JS side passes a
// flat object of whatever the user changed.
#pragma once

#include <nlohmann/json.hpp>

#include "penumbra/error.h"
#include "penumbra/settings.h"

namespace penumbra::web {

// All settings as a flat JSON object.
nlohmann::json settingsToJson(const RenderSettings& s);

// Applies the keys present in `changes` on top of `base`; unknown keys and wrong types are
// errors naming the key (a typo in a setting must not pass silently). Validates the result.
Result<RenderSettings> mergeSettings(const RenderSettings& base, const nlohmann::json& changes);

}  // namespace penumbra::web
