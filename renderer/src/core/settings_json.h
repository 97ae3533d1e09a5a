// One setting to and from JSON, by the schema (core/settings.cpp); the web API and scene
// files both go through these.
#pragma once

#include <nlohmann/json.hpp>

#include "penumbra/settings.h"

namespace penumbra {

// The setting's JSON value: a bool, an integer, a number or a tone mapper name.
nlohmann::json settingJson(const RenderSettings& settings, const SettingInfo& info);
// A JSON value as the setting's double (not yet range-checked), or an error naming the key.
Result<double> settingFromJson(const nlohmann::json& value, const SettingInfo& info);

}  // namespace penumbra
