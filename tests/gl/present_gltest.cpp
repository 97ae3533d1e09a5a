// Renderer::present into a viewport larger than the render size (a browser's canvas above its
// render resolution) interpolates between the image's texels instead of repeating them; at the
// render size it shows exactly the displayed image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gl/objects.h"
#include "gl/texture.h"
#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class PresentGLTest : public GlFixture {};

constexpr int kRenderW = 16, kRenderH = 12;

// A bright ball on a dark sky at 16x12: hard edges a few texels apart.
Result<std::unique_ptr<Renderer>> smallRender() {
  Scene s;
  s.materials = {lambert(glm::vec3(0.9f))};
  s.materials[0].emissiveFactor = glm::vec3(4.0f);
  s.meshes.push_back(sphereMesh({0.0f, 0.0f, 0.0f}, 0.5f, 0, 16));
  finishScene(s);
  auto r = Renderer::create();
  if (!r) return r.error();
  RenderSettings rs;
  rs.width = kRenderW;
  rs.height = kRenderH;
  rs.progressive.frames = 4;
  PN_TRY((*r)->setSettings(rs));
  PN_TRY((*r)->setScene(s));
  PN_TRY((*r)->setEnvironment(uniformEnvironment(glm::vec3(0.02f))));
  (*r)->setCamera(lookAtCamera({0.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 45.0f));
  while (!(*r)->converged()) {
    auto f = (*r)->step();
    if (!f) return f.error();
  }
  return r;
}

// Presents into a w x h RGBA8 target and returns its pixels (row 0 at the bottom).
std::vector<uint8_t> presentInto(Renderer& r, int w, int h) {
  auto tex = gl::Texture2D::create({.width = w, .height = h, .format = gl::PixelFormat::RGBA8});
  EXPECT_TRUE(tex.ok());
  if (!tex) return {};
  gl::Framebuffer fb = gl::Framebuffer::create();
  fb.attachColor(0, *tex);
  EXPECT_TRUE(fb.checkComplete().ok());
  auto st = r.present({.framebuffer = fb.id(), .width = w, .height = h});
  EXPECT_TRUE(st.ok()) << (st.ok() ? "" : st.message());
  return fb.readRgba8(0, 0, 0, w, h);
}

TEST_F(PresentGLTest, AnUpscaledImageIsInterpolatedNotBlocky) {
  auto r = smallRender();
  ASSERT_TRUE(r.ok()) << r.message();
  constexpr int kScale = 8, w = kRenderW * kScale, h = kRenderH * kScale;
  const std::vector<uint8_t> px = presentInto(**r, w, h);
  ASSERT_EQ(px.size(), static_cast<size_t>(w) * h * 4);
  // Along the middle row: repeated texels jump by a whole edge between two pixels; interpolated
  // ones spread it over the texel's eight pixels.
  int lo = 255, hi = 0, step = 0;
  for (int x = 0; x < w; ++x) {
    const int v = px[(static_cast<size_t>(h / 2) * w + x) * 4];
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    if (x > 0) step = std::max(step, std::abs(v - px[(static_cast<size_t>(h / 2) * w + x - 1) * 4]));
  }
  ASSERT_GT(hi - lo, 100) << "the ball and the sky are both in the row";
  EXPECT_LT(step, (hi - lo) / 3) << "largest step between neighbours " << step << " of " << hi - lo;
}

TEST_F(PresentGLTest, AtTheRenderSizeItIsTheDisplayedImage) {
  auto r = smallRender();
  ASSERT_TRUE(r.ok()) << r.message();
  const std::vector<uint8_t> px = presentInto(**r, kRenderW, kRenderH);
  auto display = (*r)->readDisplay();
  ASSERT_TRUE(display.ok()) << display.message();
  ASSERT_EQ(display->width, kRenderW);
  for (int y = 0; y < kRenderH; ++y) {
    for (int x = 0; x < kRenderW; ++x) {
      // readDisplay has row 0 at the top, the framebuffer at the bottom.
      const float want = display->pixel(x, kRenderH - 1 - y)[0] * 255.0f;
      EXPECT_NEAR(px[(static_cast<size_t>(y) * kRenderW + x) * 4], want, 1.01) << x << "," << y;
    }
  }
}

}  // namespace
}  // namespace penumbra::test
