// KHR_materials_iridescence, _anisotropy, _diffuse_transmission and _dispersion in the
// renderer: white furnaces (each keeps energy), and what each must visibly do: a film's colour
// that follows its thickness, a highlight stretched along the anisotropy's direction, light
// passing to a surface's other side, and refraction split into colours.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "ibl/sampling.h"
#include "penumbra/environment.h"
#include "penumbra/ibl.h"
#include "render_fixture.h"

namespace penumbra::test {
namespace {

class LaterExtensionsGLTest : public GlFixture {};

constexpr int kSize = 48;

Result<Image> render(Scene s, glm::vec3 sky, const Camera& camera, int frames = 8) {
  finishScene(s);
  RenderSettings rs;
  rs.width = rs.height = kSize;
  rs.progressive.frames = frames;
  return renderRadiance(s, uniformEnvironment(sky), camera, rs);
}

// A unit sphere of one material seen from 4 units away (20 degrees: it fills the image).
Result<Image> sphere(const Material& m, glm::vec3 sky, const std::vector<Light>& lights = {}) {
  Scene s;
  s.materials.push_back(m);
  s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
  s.lights = lights;
  return render(std::move(s), sky, lookAtCamera({0, 0, 4}, {0, 0, 0}, 20.0f));
}

glm::vec3 meanOf(const Image& img, int x0, int y0, int x1, int y1) {
  glm::vec3 sum(0.0f);
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x)
      sum += glm::vec3(img.pixel(x, y)[0], img.pixel(x, y)[1], img.pixel(x, y)[2]);
  }
  return sum / float((x1 - x0) * (y1 - y0));
}

// The sphere's central 28x28 pixels.
glm::vec3 centre(const Material& m, glm::vec3 sky, const std::vector<Light>& lights = {}) {
  auto img = sphere(m, sky, lights);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img.ok() ? meanOf(*img, 10, 10, 38, 38) : glm::vec3(-1.0f);
}

TEST_F(LaterExtensionsGLTest, WhiteFurnaceHoldsWithEachExtension) {
  // A white dielectric reflects exactly a white environment whatever the film, the anisotropy
  // or the share passed through to its other side (where the same sky arrives).
  for (int k = 0; k < 3; ++k) {
    Material m = lambert(glm::vec3(1.0f));
    m.roughnessFactor = 0.5f;
    const char* what = k == 0 ? "iridescence" : k == 1 ? "anisotropy" : "diffuse transmission";
    if (k == 0) m.iridescence = 1.0f;
    if (k == 1) m.anisotropy = 0.9f;
    if (k == 2) m.diffuseTransmission = 0.6f;
    const glm::vec3 c = centre(m, glm::vec3(1.0f));
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(c[ch], 1.0f, 0.03f) << what << " channel " << ch;
  }
}

TEST_F(LaterExtensionsGLTest, IridescenceColoursTheReflectionByFilmThickness) {
  // A black base shows only its reflection: grey without a film, coloured with one, in other
  // colours at another thickness, and unchanged by a film of thickness 0.
  Material m = lambert(glm::vec3(0.0f));
  m.roughnessFactor = 0.3f;
  const glm::vec3 bare = centre(m, glm::vec3(1.0f));
  m.iridescence = 1.0f;
  m.iridescenceThicknessMax = 0.0f;
  const glm::vec3 none = centre(m, glm::vec3(1.0f));
  m.iridescenceThicknessMax = 300.0f;
  const glm::vec3 thin = centre(m, glm::vec3(1.0f));
  m.iridescenceThicknessMax = 550.0f;
  const glm::vec3 thick = centre(m, glm::vec3(1.0f));
  const auto spread = [](glm::vec3 c) {
    return (std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b})) / std::max(c.g, 1e-6f);
  };
  EXPECT_LT(spread(bare), 0.02f);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(none[ch], bare[ch], 0.03f * bare[ch] + 1e-4f);
  EXPECT_GT(spread(thin), 0.2f) << thin.r << " " << thin.g << " " << thin.b;
  EXPECT_GT(spread(thick), 0.2f) << thick.r << " " << thick.g << " " << thick.b;
  // Another thickness, another colour: the red-to-blue ratios differ by a quarter or more.
  const float a = thin.r / std::max(thin.b, 1e-6f), b = thick.r / std::max(thick.b, 1e-6f);
  EXPECT_GT(std::max(a, b) / std::min(a, b), 1.25f) << a << " vs " << b;
}

// Pixels of the central row and column brighter than half the image's peak: the highlight's
// extent across and up the image.
glm::ivec2 highlightExtent(const Image& img) {
  float peak = 0.0f;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) peak = std::max(peak, img.pixel(x, y)[1]);
  glm::ivec2 n(0);
  for (int i = 0; i < kSize; ++i) {
    if (img.pixel(i, kSize / 2)[1] > 0.5f * peak) ++n.x;
    if (img.pixel(kSize / 2, i)[1] > 0.5f * peak) ++n.y;
  }
  return n;
}

TEST_F(LaterExtensionsGLTest, AnisotropyStretchesTheHighlightAlongItsDirection) {
  // A glossy metal sphere lit from the camera by a small area light: round highlight without
  // anisotropy, long along the direction with it (the sphere has no tangents, so the frame is
  // the x axis projected: the direction runs across the image), up the image when rotated.
  Light lamp;
  lamp.type = LightType::Disk;
  lamp.intensity = 200.0f;
  lamp.position = {0, 0, 6};
  lamp.direction = {0, 0, -1};
  lamp.width = lamp.height = 0.3f;
  Material m = lambert(glm::vec3(1.0f));
  m.metallicFactor = 1.0f;
  m.roughnessFactor = 0.25f;
  glm::ivec2 extent[3];
  for (int k = 0; k < 3; ++k) {
    m.anisotropy = k == 0 ? 0.0f : 0.8f;
    m.anisotropyRotation = k == 2 ? 1.5707963f : 0.0f;
    auto img = sphere(m, glm::vec3(0.0f), {lamp});
    ASSERT_TRUE(img.ok()) << img.message();
    extent[k] = highlightExtent(*img);
  }
  EXPECT_LE(std::abs(extent[0].x - extent[0].y), 2) << extent[0].x << " x " << extent[0].y;
  EXPECT_GT(extent[1].x, 2 * extent[1].y) << extent[1].x << " x " << extent[1].y;
  EXPECT_GT(extent[2].y, 2 * extent[2].x) << extent[2].x << " x " << extent[2].y;
}

// A sky that brightens toward the zenith (no sun: its peak is under 20 times its mean).
float zenithSky(glm::vec3 d) {
  const float y = std::max(d.y, 0.0f);
  return 0.05f + 2.0f * y * y * y * y;
}

// The split sum's prefiltered term of an anisotropic GGX lobe (normal n, stretch t, view v)
// under zenithSky: the n.l-weighted mean over light directions reflected about half vectors
// drawn from D(h) (n.h), with the exact sky (not its prefiltered cube).
double lobeMean(glm::vec3 n, glm::vec3 t, glm::vec3 v, float alphaT, float alphaB) {
  const glm::vec3 b = glm::cross(n, t);
  double sum = 0.0, weight = 0.0;
  constexpr uint32_t kN = 1u << 18;
  for (uint32_t i = 0; i < kN; ++i) {
    const glm::vec3 hl = ibl::sampleGgxDAnisotropic(ibl::hammersley(i, kN), alphaT, alphaB);
    const glm::vec3 h = ibl::toWorld(hl, t, b, n);
    if (glm::dot(v, h) <= 0.0f) continue;
    const glm::vec3 l = ibl::reflectAbout(v, h);
    const double w = std::max(glm::dot(n, l), 0.0f);
    sum += w * zenithSky(l);
    weight += w;
  }
  return sum / weight;
}

TEST_F(LaterExtensionsGLTest, AnisotropicMetalReflectsItsLobesMeanOfTheSky) {
  // A smooth white metal floor stretched fully (alpha_t 1, alpha_b 0.01), seen from 34 degrees
  // up through a narrow field: its reflection of a sky brightening toward the zenith is the
  // stretched lobe's mean (the metal's energy is compensated in full, so nothing else scales
  // it), which the later frames sample; along the plane of incidence the lobe reaches the
  // bright zenith, across it stays near the mirror direction. The extension's bent normal
  // alone (one lookup, as before 2026-12-08) read 0.22 of the first.
  Image pano(256, 128, 3);
  for (int y = 0; y < pano.height; ++y) {
    for (int x = 0; x < pano.width; ++x) {
      const float l = zenithSky(ibl::panoramaDirection((x + 0.5f) / 256.0f, (y + 0.5f) / 128.0f));
      float* p = pano.pixel(x, y);
      p[0] = p[1] = p[2] = l;
    }
  }
  ibl::PrefilterOptions options;
  options.faceSize = 64;
  options.samples = 64;
  auto env = ibl::prefilterCpu(pano, options);
  ASSERT_TRUE(env.ok()) << env.message();
  const glm::vec3 eye(0.0f, 2.0f, 3.0f);
  // Rotation 0 stretches along the x axis (the floor has no tangents), a quarter turn along z.
  const std::pair<float, glm::vec3> stretches[] = {{1.5707963f, {0, 0, 1}}, {0.0f, {1, 0, 0}}};
  for (const auto& [rotation, along] : stretches) {
    Material m = lambert(glm::vec3(1.0f));
    m.metallicFactor = 1.0f;
    m.roughnessFactor = 0.1f;
    m.anisotropy = 1.0f;
    m.anisotropyRotation = rotation;
    Scene s;
    s.materials.push_back(m);
    s.meshes.push_back(quadMesh(8.0f, 0.0f, 0));
    finishScene(s);
    RenderSettings rs;
    rs.width = rs.height = kSize;
    rs.progressive.frames = 32;
    auto img = renderRadiance(s, *env, lookAtCamera(eye, {0, 0, 0}, 8.0f), rs);
    ASSERT_TRUE(img.ok()) << img.message();
    const float got = meanOf(*img, 20, 20, 28, 28).g;
    const double want = lobeMean({0, 1, 0}, along, glm::normalize(eye), 1.0f, 0.01f);
    EXPECT_NEAR(got / want, 1.0, 0.06)
        << "rotation " << rotation << ": rendered " << got << ", the lobe's mean " << want;
  }
}

TEST_F(LaterExtensionsGLTest, DiffuseTransmissionPassesLightToTheOtherSide) {
  // A floor seen from above, lit only from below (a directional light and, separately, an
  // area light facing up): dark without diffuse transmission; with it, the transmission
  // colour, about E (1 - specular albedo) / pi for the sun of illuminance E. The floor's own
  // shadow maps must not shadow it from behind.
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 3.0f;
  sun.direction = {0, 1, 0};
  Light panel;
  panel.type = LightType::Rect;
  panel.intensity = 20.0f;
  panel.position = {0, -1.0f, 0};
  panel.direction = {0, 1, 0};
  panel.right = {1, 0, 0};
  panel.up = {0, 0, 1};
  panel.width = panel.height = 2.0f;
  for (const Light& light : {sun, panel}) {
    const bool isSun = light.type == LightType::Directional;
    glm::vec3 c[2];
    for (int k = 0; k < 2; ++k) {
      Scene s;
      Material m = lambert(glm::vec3(0.2f, 0.8f, 0.2f));
      m.diffuseTransmission = k == 0 ? 0.0f : 1.0f;
      m.diffuseTransmissionColor = {1.0f, 0.0f, 0.0f};
      s.materials.push_back(m);
      s.meshes.push_back(quadMesh(4.0f, 0.0f, 0));
      s.lights = {light};
      auto img = render(std::move(s), glm::vec3(0.0f), lookAtCamera({0, 3, 0}, {0, 0, 0}, 30.0f));
      ASSERT_TRUE(img.ok()) << img.message();
      c[k] = meanOf(*img, 16, 16, 32, 32);
    }
    const char* what = isSun ? "directional light" : "area light";
    EXPECT_LT(c[0].r + c[0].g + c[0].b, 1e-3f) << what;
    EXPECT_GT(c[1].r, isSun ? 0.8f * 3.0f / 3.14159f : 0.5f) << what;
    EXPECT_LT(c[1].r, isSun ? 3.0f / 3.14159f : 20.0f) << what;
    EXPECT_LT(c[1].g + c[1].b, 1e-3f) << what << ": the transmission colour, not the base";
  }
}

TEST_F(LaterExtensionsGLTest, DispersionSplitsTheColoursOfRefraction) {
  // A glass ball over grey stripes: without dispersion what it refracts stays grey (red equals
  // blue everywhere); with it red and blue are bent by different indices and part.
  ImageData stripes;
  stripes.name = "stripes";
  stripes.width = 8;
  stripes.height = 1;
  for (int i = 0; i < 8; ++i) {
    const uint8_t v = i % 2 ? 255 : 0;
    stripes.pixels.insert(stripes.pixels.end(), {v, v, v, 255});
  }
  float split[2];
  for (int k = 0; k < 2; ++k) {
    Scene s;
    s.images.push_back(stripes);
    SamplerDesc nearest;
    nearest.minFilter = nearest.magFilter = 9728;
    s.samplers.push_back(nearest);
    Material floor = lambert(glm::vec3(1.0f));
    floor.baseColorTexture.image = 0;
    floor.baseColorTexture.sampler = 0;
    Material glass = lambert(glm::vec3(1.0f));
    glass.roughnessFactor = 0.0f;
    glass.transmission = 1.0f;
    glass.thickness = 2.0f;
    glass.dispersion = k == 0 ? 0.0f : 20.0f;
    s.materials = {floor, glass};
    Mesh plane = quadMesh(4.0f, 0.0f, 0);
    plane.primitives[0].uv0 = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
    s.meshes.push_back(std::move(plane));
    s.meshes.push_back(sphereMesh({0, 1.2f, 0}, 0.8f, 1, 96));
    auto img = render(std::move(s), glm::vec3(1.0f), lookAtCamera({0, 5, 0}, {0, 0, 0}, 24.0f));
    ASSERT_TRUE(img.ok()) << img.message();
    double sum = 0.0;
    for (int y = 18; y < 30; ++y) {
      for (int x = 18; x < 30; ++x) sum += std::abs(img->pixel(x, y)[0] - img->pixel(x, y)[2]);
    }
    split[k] = static_cast<float>(sum / (12.0 * 12.0));
  }
  EXPECT_LT(split[0], 0.01f);
  EXPECT_GT(split[1], 0.05f) << "without dispersion " << split[0];
}

}  // namespace
}  // namespace penumbra::test
