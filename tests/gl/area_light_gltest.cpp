// The area-light irradiance chunk (glsl/chunks/area_lights.glsl) against closed forms and
// brute-force quadrature: E = integral over the light of L cos(theta_p) cos(theta_l) / r^2.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "gl/objects.h"
#include "gl/program.h"
#include "gl_fixture.h"
#include "passes/fullscreen_pass.h"
#include "passes/limits.h"

namespace penumbra::test {
namespace {

struct LightDesc {
  glm::vec3 pos, dir, right, up;
  glm::vec2 size;
  bool disk;
};

constexpr int kPoints = 32;

// Irradiance per unit luminance at kPoints points start + i * step with normal n, on the GPU.
std::vector<float> gpuIrradiance(const LightDesc& l, glm::vec3 start, glm::vec3 step, glm::vec3 n) {
  gl::ShaderLibrary library;
  library.setCommonDefines(passes::commonDefines());  // PN_LIGHT_DISK, ...
  auto pass = passes::FullscreenPass::create(library, "test/area_irradiance.frag");
  EXPECT_TRUE(pass.ok()) << (pass.ok() ? "" : pass.message());
  auto tex =
      gl::Texture2D::create({.width = kPoints, .height = 1, .format = gl::PixelFormat::RGBA32F});
  gl::Framebuffer fb = gl::Framebuffer::create();
  fb.attachColor(0, *tex);
  fb.setDrawBuffers(1);
  EXPECT_TRUE(fb.checkComplete().ok());
  gl::setViewport(0, 0, kPoints, 1);
  const gl::Program& p = pass->begin();
  p.set("uLightPos", l.pos);
  p.set("uLightDir", l.dir);
  p.set("uLightRight", l.right);
  p.set("uLightUp", l.up);
  p.set("uLightSize", l.size);
  p.set("uDisk", l.disk ? 1 : 0);
  p.set("uStart", start);
  p.set("uStep", step);
  p.set("uNormal", n);
  pass->draw();
  auto data = fb.readRgbaFloat(0, 0, 0, kPoints, 1);
  gl::Framebuffer::bindDefault();
  std::vector<float> out;
  for (int i = 0; i < kPoints; ++i) out.push_back(data[static_cast<size_t>(i) * 4]);
  return out;
}

// Midpoint quadrature of the irradiance integral over the light's true shape.
double bruteForce(const LightDesc& l, glm::dvec3 p, glm::dvec3 n, int res = 400) {
  double e = 0.0;
  const double w = l.size.x, h = l.size.y;
  const double dA = (w / res) * (h / res);
  for (int j = 0; j < res; ++j) {
    for (int i = 0; i < res; ++i) {
      const double u = ((i + 0.5) / res - 0.5) * w, v = ((j + 0.5) / res - 0.5) * h;
      if (l.disk && (u * u + v * v) > 0.25 * w * w) continue;
      glm::dvec3 q = glm::dvec3(l.pos) + u * glm::dvec3(l.right) + v * glm::dvec3(l.up);
      glm::dvec3 d = q - p;
      const double r2 = glm::dot(d, d);
      glm::dvec3 dn = d / std::sqrt(r2);
      const double cp = glm::dot(dn, n), cl = -glm::dot(dn, glm::dvec3(l.dir));
      if (cp <= 0 || cl <= 0) continue;
      e += cp * cl / r2 * dA;
    }
  }
  return e;
}

class AreaLightGLTest : public GlFixture {};

TEST_F(AreaLightGLTest, DiskOnAxisMatchesAnalyticFormFactor) {
  const float r = 0.5f;
  LightDesc l{{0, 0, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {2 * r, 2 * r}, true};
  // Points straight below at heights 0.1 .. 3.2.
  auto e = gpuIrradiance(l, {0, -0.1f, 0}, {0, -0.1f, 0}, {0, 1, 0});
  for (int i = 0; i < kPoints; ++i) {
    const double h = 0.1 * (i + 1);
    const double expected = M_PI * r * r / (r * r + h * h);  // E / L
    EXPECT_NEAR(e[static_cast<size_t>(i)], expected, 0.02 * expected) << "height " << h;
  }
}

TEST_F(AreaLightGLTest, RectBelowCentreMatchesClosedForm) {
  const float a = 1.0f, h = 0.5f;
  LightDesc l{{0, h, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {a, a}, false};
  auto e = gpuIrradiance(l, {0, 0, 0}, {0, 0, 0}, {0, 1, 0});
  const double x = a / (2 * h), y = a / (2 * h);
  // Four corner rectangles of the standard parallel-rectangle form factor.
  const double f = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                    y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                   (2 * M_PI);
  const double expected = M_PI * 4.0 * f;
  EXPECT_NEAR(e[0], expected, 0.01 * expected);
}

TEST_F(AreaLightGLTest, TiltedAndHorizonClippedReceiversMatchQuadrature) {
  // A rect light tilted 30 degrees; receivers on a vertical wall beside it, so the light
  // straddles the wall's horizon for some points (the clipping path).
  const glm::vec3 dir = glm::normalize(glm::vec3(0.5f, -0.866f, 0.0f));
  const glm::vec3 right = glm::normalize(glm::cross(dir, glm::vec3(0, 0, 1)));
  const glm::vec3 up = glm::cross(right, dir);
  for (bool disk : {false, true}) {
    LightDesc l{{0, 1, 0}, dir, right, up, {0.8f, 0.4f}, disk};
    if (disk) l.size = {0.6f, 0.6f};
    const glm::vec3 start{0.3f, 1.4f, 0.05f}, step{0, -0.06f, 0}, n{-1, 0, 0};
    auto e = gpuIrradiance(l, start, step, n);
    for (int i = 0; i < kPoints; ++i) {
      glm::dvec3 p = glm::dvec3(start + step * static_cast<float>(i));
      const double expected = bruteForce(l, p, glm::dvec3(n));
      EXPECT_NEAR(e[static_cast<size_t>(i)], expected, 0.02 * expected + 1e-4)
          << (disk ? "disk" : "rect") << " point " << i;
    }
  }
}

}  // namespace
}  // namespace penumbra::test
