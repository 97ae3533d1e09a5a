// Where a frame's light samples come from: the point on an area light's surface a shadow map
// is rendered from, the jittered direction of a directional light's sample, and the
// environment's sun as a directional light. Pure functions of the light, the sample point and
// the settings, so the Renderer stays about scheduling GL work.
#pragma once

#include <optional>

#include <glm/glm.hpp>

#include "passes/probe_volume.h"
#include "penumbra/ibl.h"
#include "penumbra/scene.h"
#include "penumbra/settings.h"

namespace penumbra::render {

// The environment's sun as a directional light, turned and scaled like the environment.
Light sunLight(const ibl::Sun& sun, const RenderSettings& settings);

// A sky-shadow sample as a directional light: travelling away from the sampled direction
// (turned like the environment), colour = radiance / pdf times the environment intensity: the
// irradiance estimate whose shadowed part the lighting pass subtracts.
Light skyLight(const ibl::SkySample& sample, const RenderSettings& settings);

// The direction of travel of a punctual light sample: a directional light's is spread over
// its angular size (the sample point u on a disk), the others' is the light's own.
glm::vec3 punctualDirection(const Light& light, glm::vec2 u, const RenderSettings& settings);

// World position of an area-light sample on the light's true surface.
glm::vec3 samplePosition(const Light& light, glm::vec2 u);

// Every light as a probe capture shades it, sampled at point u.
std::vector<passes::CaptureLight> captureLights(const std::vector<Light>& lights, glm::vec2 u,
                                                const RenderSettings& settings);

}  // namespace penumbra::render
