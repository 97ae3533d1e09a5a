// Transparency end to end: every alpha mode renders, BLEND surfaces converge to the
// order-independent composite (stochastic transparency), and MASK and BLEND surfaces cast
// cut-out and partial shadows. Expected images are built from renders of the layers on their
// own: with occlusion out of reach and a uniform environment, each layer's radiance does not
// depend on the others, so the composite is an exact per-pixel mix of those renders.
#include <array>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class TransparencyGLTest : public GlFixture {};

// A horizontal rectangle [x0, x1] x [z0, z1] at height y facing +Y, with UVs (u along x).
Primitive rectangle(float x0, float x1, float z0, float z1, float y, int material) {
  Primitive p;
  p.positions = {{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}};
  p.normals.assign(4, glm::vec3(0, 1, 0));
  p.uv0 = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  p.indices = {0, 1, 2, 0, 2, 3};
  p.material = material;
  for (const auto& v : p.positions) p.bounds.extend(v);
  return p;
}

Mesh meshOf(Primitive p) {
  Mesh m;
  m.primitives.push_back(std::move(p));
  return m;
}

Material blend(glm::vec3 albedo, float alpha) {
  Material m = lambert(albedo);
  m.baseColorFactor.a = alpha;
  m.alphaMode = AlphaMode::Blend;
  return m;
}

// A 4x4 checkerboard of albedo 0.1 and 0.9 over [-1, 1]^2 at y = 0 (materials 0 and 1).
Scene checkerboard() {
  Scene s;
  s.materials = {lambert(glm::vec3(0.1f)), lambert(glm::vec3(0.9f))};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const float x = -1.0f + 0.5f * static_cast<float>(i),
                  z = -1.0f + 0.5f * static_cast<float>(j);
      s.meshes.push_back(meshOf(rectangle(x, x + 0.5f, z, z + 0.5f, 0.0f, (i + j) % 2)));
    }
  }
  return s;
}

// Adds a layer of one material; returns the scene finished.
Scene withLayer(Scene s, const Material& m, Primitive p) {
  p.material = static_cast<int>(s.materials.size());
  s.materials.push_back(m);
  s.meshes.push_back(meshOf(std::move(p)));
  finishScene(s);
  return s;
}

// Seen from above under a uniform white sky, with occlusion out of reach: every surface's
// radiance is its own.
RenderSettings topDownSettings(int frames) {
  RenderSettings rs;
  rs.width = rs.height = 64;
  rs.progressive.frames = frames;
  rs.progressive.probeVolume = false;  // the composites below are of direct light
  rs.progressive.occlusionDistance = 1e-4f;
  rs.progressive.screenSpaceIndirect = false;
  // Sky shadows have their own tests; their per-frame estimate would only add noise to the
  // exact composites compared here.
  rs.progressive.skyShadows = false;
  return rs;
}

Image render(const Scene& s, const PackedEnvironment& env, const Camera& cam,
             const RenderSettings& rs) {
  auto img = renderRadiance(s, env, cam, rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img.ok() ? std::move(*img) : Image{};
}

// sum_i w_i * images_i, per pixel (RGB; alpha 1).
Image mix(std::initializer_list<std::pair<float, const Image*>> terms) {
  Image out = *terms.begin()->second;
  for (size_t i = 0; i < out.pixels.size(); ++i) {
    if (i % 4 == 3) {
      out.pixels[i] = 1.0f;
      continue;
    }
    float v = 0.0f;
    for (const auto& [w, img] : terms) v += w * img->pixels[i];
    out.pixels[i] = v;
  }
  return out;
}

// Mean over k x k blocks: what remains of a difference there is bias, not per-pixel noise.
Image blockMean(const Image& img, int k) {
  Image out;
  out.width = img.width / k;
  out.height = img.height / k;
  out.channels = 4;
  out.pixels.assign(static_cast<size_t>(out.width) * out.height * 4, 0.0f);
  for (int y = 0; y < out.height * k; ++y) {
    for (int x = 0; x < out.width * k; ++x) {
      float* o = &out.pixels[(static_cast<size_t>(y / k) * out.width + x / k) * 4];
      for (int c = 0; c < 4; ++c) o[c] += img.pixel(x, y)[c] / static_cast<float>(k * k);
    }
  }
  return out;
}

// Stochastic coverage leaves per-pixel noise (each pixel's coverage is a mean of coin flips):
// the per-pixel bound allows about 5 standard deviations at 128 frames, and 8x8 block means,
// where the noise drops eightfold, must match closely.
::testing::AssertionResult convergesTo(const Image& actual, const Image& expected, double maxPixel,
                                       const std::string& name) {
  auto perPixel = matchesImage(actual, expected, {.maxAbs = maxPixel, .meanAbs = 0.04}, name);
  if (!perPixel) return perPixel;
  return matchesImage(blockMean(actual, 8), blockMean(expected, 8),
                      {.maxAbs = 0.025, .meanAbs = 0.008}, name + "_blocks");
}

// A 0.5 x 0.5 rect light 2 above the origin, facing down.
Light ceilingLight(float nits) {
  Light light;
  light.position = {0, 2, 0};
  light.direction = {0, -1, 0};
  light.right = {1, 0, 0};
  light.up = {0, 0, 1};
  light.width = light.height = 0.5f;
  light.intensity = nits;
  return light;
}

Camera topDown() {
  return lookAtCamera({0, 4, 0}, {0, 0, 0}, 35.0f);
}

TEST_F(TransparencyGLTest, EveryAlphaModeRendersEveryFrame) {
  // The regression: a BLEND material stopped frame 1 with GL_INVALID_OPERATION (its draws
  // ran with the background program bound). All four material paths, several frames each.
  Scene s = checkerboard();
  Material mask = lambert(glm::vec3(0.2f, 0.6f, 0.2f));
  mask.alphaMode = AlphaMode::Mask;
  mask.baseColorFactor.a = 0.7f;
  Material twoSided = lambert(glm::vec3(0.8f, 0.3f, 0.1f));
  twoSided.doubleSided = true;
  s = withLayer(s, blend(glm::vec3(0.2f, 0.3f, 0.9f), 0.4f),
                rectangle(-0.8f, 0.0f, -0.8f, 0.0f, 0.3f, 0));
  s = withLayer(s, mask, rectangle(0.0f, 0.8f, -0.8f, 0.0f, 0.3f, 0));
  s = withLayer(s, twoSided, rectangle(-0.8f, 0.0f, 0.0f, 0.8f, 0.3f, 0));
  s.lights.push_back(ceilingLight(5.0f));
  RenderSettings rs = topDownSettings(8);
  rs.progressive.occlusionDistance = 0.5f;  // the occlusion rays see the coverage too
  rs.progressive.screenSpaceIndirect = true;
  rs.progressive.directDelay = 0.0f;
  Image img = render(s, uniformEnvironment(glm::vec3(0.5f)), topDown(), rs);
  ASSERT_EQ(img.width, 64);
  // Each layer shows: the blue BLEND square is bluer than the checker beside it.
  const float* blendPixel = img.pixel(20, 20);
  EXPECT_GT(blendPixel[2], blendPixel[0]);
  for (float v : img.pixels) ASSERT_TRUE(std::isfinite(v));
}

struct HalfPlane {
  PackedEnvironment env = uniformEnvironment(glm::vec3(1.0f));
  Primitive plane = rectangle(-0.6f, 0.6f, -0.6f, 0.6f, 0.5f, 0);
  glm::vec3 colour{0.8f, 0.5f, 0.2f};
  // The checkerboard alone, the plane opaque over it, the plane at alpha 0.5 over it.
  std::array<Image, 3> render(int frames) const {
    const RenderSettings rs = topDownSettings(frames);
    Scene base = checkerboard();
    finishScene(base);
    return {
        test::render(base, env, topDown(), rs),
        test::render(withLayer(checkerboard(), lambert(colour), plane), env, topDown(), rs),
        test::render(withLayer(checkerboard(), blend(colour, 0.5f), plane), env, topDown(), rs)};
  }
};

TEST_F(TransparencyGLTest, HalfTransparentPlaneConvergesToTheComposite) {
  const auto [below, opaque, actual] = HalfPlane().render(128);
  const Image expected = mix({{0.5f, &opaque}, {0.5f, &below}});
  // Coverage is stratified in blocks of 16 frames; 128 frames end halfway through a block.
  EXPECT_TRUE(convergesTo(actual, expected, 0.1, "transparency_half_plane"));
  // And it is not simply one of the two layers.
  auto toOpaque = compareImages(actual, opaque);
  ASSERT_TRUE(toOpaque.ok());
  EXPECT_GT(toOpaque->maxAbs, 0.2);
}

TEST_F(TransparencyGLTest, OneLayerIsExactAfterAWholeBlockOfFrames) {
  // Frame 1 alpha-blends; frames 2..17 visit all 16 coverage strata of each pixel once, so
  // alpha 0.5 keeps the plane in exactly 8 of them: no noise left away from its edges (where
  // the sub-pixel jitter changes what the pixel covers).
  const auto [below, opaque, actual] = HalfPlane().render(17);
  const Image expected = mix({{0.5f, &opaque}, {0.5f, &below}});
  EXPECT_TRUE(
      matchesImage(actual, expected, {.maxAbs = 0.2, .meanAbs = 0.002}, "transparency_one_block"));
  // Away from edges (both layers flat over the pixel's 3x3 neighbourhood): exact.
  auto flat = [](const Image& img, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        for (int c = 0; c < 3; ++c) {
          if (std::abs(img.pixel(x + dx, y + dy)[c] - img.pixel(x, y)[c]) > 1e-3f) return false;
        }
      }
    }
    return true;
  };
  int checked = 0;
  for (int y = 1; y < actual.height - 1; ++y) {
    for (int x = 1; x < actual.width - 1; ++x) {
      if (!flat(below, x, y) || !flat(opaque, x, y)) continue;
      ++checked;
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(actual.pixel(x, y)[c], expected.pixel(x, y)[c], 0.01)
            << "pixel " << x << "," << y;
      }
    }
  }
  EXPECT_GT(checked, 2000);
}

// A 4x4 floor under a 0.5 x 0.5 rect light 2 above it, seen from low down so that whatever
// hangs at height 1 between them stays out of view; no environment light.
struct ShadowSetup {
  Scene scene;
  Camera camera = lookAtCamera({0, 0.5f, 2.5f}, {0, 0, 0}, 30.0f);
  RenderSettings settings = topDownSettings(64);
  ShadowSetup() {
    scene.materials = {lambert(glm::vec3(0.8f))};
    scene.meshes.push_back(meshOf(rectangle(-2, 2, -2, 2, 0.0f, 0)));
    scene.lights.push_back(ceilingLight(40.0f));  // the lit floor reads about 0.6
    settings.width = 96;
    settings.height = 64;
    settings.progressive.shadowMapSize = 512;
    settings.progressive.directDelay = 0.0f;
  }
  Image render(const Material* occluder, const Primitive& shape) const {
    Scene s = scene;
    if (occluder) {
      s = withLayer(s, *occluder, shape);
    } else {
      finishScene(s);
    }
    return test::render(s, uniformEnvironment(glm::vec3(0.0f)), camera, settings);
  }
};

TEST_F(TransparencyGLTest, BlendOccluderCastsAShadowOfOneMinusAlpha) {
  ShadowSetup setup;
  const Primitive square = rectangle(-0.5f, 0.5f, -0.5f, 0.5f, 1.0f, 0);
  const Material solid = lambert(glm::vec3(0.5f));
  const Material glass = blend(glm::vec3(0.5f), 0.6f);
  const Image lit = setup.render(nullptr, square);
  const Image shadowed = setup.render(&solid, square);
  const Image partial = setup.render(&glass, square);
  // Each light sample is blocked with probability alpha where the square would block it.
  const Image expected = mix({{0.4f, &lit}, {0.6f, &shadowed}});
  EXPECT_TRUE(convergesTo(partial, expected, 0.15, "transparency_partial_shadow"));
  auto toLit = compareImages(partial, lit);
  ASSERT_TRUE(toLit.ok());
  EXPECT_GT(toLit->maxAbs, 0.2);  // the shadow is there
}

TEST_F(TransparencyGLTest, MaskLeafCastsACutOutShadow) {
  ShadowSetup setup;
  // A 2x1 texture, alpha 0 on the left and 1 on the right, nearest filtering: the MASK square
  // should cast exactly the shadow of its right half.
  setup.scene.images.push_back(
      {.name = "half", .width = 2, .height = 1, .pixels = {255, 255, 255, 0, 255, 255, 255, 255}});
  setup.scene.samplers.push_back({.magFilter = 9728, .minFilter = 9728});
  Material leaf = lambert(glm::vec3(0.3f, 0.6f, 0.2f));
  leaf.alphaMode = AlphaMode::Mask;
  leaf.baseColorTexture.image = 0;
  leaf.baseColorTexture.sampler = 0;
  const Material solid = lambert(glm::vec3(0.5f));
  const Image cut = setup.render(&leaf, rectangle(-0.5f, 0.5f, -0.5f, 0.5f, 1.0f, 0));
  const Image half = setup.render(&solid, rectangle(0.0f, 0.5f, -0.5f, 0.5f, 1.0f, 0));
  const Image whole = setup.render(&solid, rectangle(-0.5f, 0.5f, -0.5f, 0.5f, 1.0f, 0));
  EXPECT_TRUE(
      matchesImage(cut, half, {.maxAbs = 0.06, .meanAbs = 0.004}, "transparency_mask_shadow"));
  auto toWhole = compareImages(cut, whole);
  ASSERT_TRUE(toWhole.ok());
  EXPECT_GT(toWhole->maxAbs, 0.2);  // the cut-away half lets light through
}

}  // namespace
}  // namespace penumbra::test
