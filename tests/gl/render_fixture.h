// Helpers for renderer GL tests: small scenes built in code and a one-call render.
#pragma once

#include <memory>

#include "gl_fixture.h"
#include "penumbra/renderer.h"
#include "penumbra/scene.h"

namespace penumbra::test {

// A square of side `size` in the XZ plane at height y, facing +Y, with one material.
Mesh quadMesh(float size, float y, int material);
// A rectangle p0 + s e1 + t e2 (s, t in [0, 1]) facing n (counter-clockwise seen from n).
Mesh rectangle(glm::vec3 p0, glm::vec3 e1, glm::vec3 e2, glm::vec3 n, int material);
// A box [min, max] with outward normals (5 faces, no bottom when `open` is set).
Mesh boxMesh(glm::vec3 min, glm::vec3 max, int material);
// A box seen from inside: boxMesh with its normals and windings turned inward.
Mesh insideBox(glm::vec3 lo, glm::vec3 hi, int material);
// A Lambertian material of the given albedo (metallic 0, roughness 1).
Material lambert(glm::vec3 albedo);
// A camera at `eye` looking at `target` with vertical field of view `yfovDeg`.
Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfovDeg);
// Fills bounds and instances (identity transforms) of a scene built from meshes.
void finishScene(Scene& scene);

// Scales a scene in place by k about the origin, as if it had been modelled in other units:
// vertex positions and bounds, instance translations, light positions, sizes and ranges,
// camera positions and clip planes (ymag of orthographic ones). Light intensities stay:
// an area light's luminance (radiance) does not depend on its size. Punctual lights (candela,
// whose irradiance falls with 1/d^2) are left as they are, so only area-lit scenes keep
// their image.
void scaleScene(Scene& scene, float k);

// Renders `frames` frames and returns the linear radiance.
Result<Image> renderRadiance(const Scene& scene, const PackedEnvironment& env, const Camera& camera,
                             RenderSettings settings, const RendererOptions& options = {});

}  // namespace penumbra::test

namespace penumbra::test {
// A UV sphere of radius r centred at c.
Mesh sphereMesh(glm::vec3 c, float r, int material, int segments = 48);
// Mean over RGB and all pixels.
double meanRgb(const Image& image);
// RMSE over RGB of two images of equal size.
double rmse(const Image& a, const Image& b);
// Radiance (mean of RGB) of the image where world point p projects with viewProj: the pixel it
// falls in, or bilinear between pixel centres (a profile not quantised to pixels).
float radianceAt(const Image& image, const glm::mat4& viewProj, glm::vec3 p, bool bilinear = false);
}  // namespace penumbra::test
