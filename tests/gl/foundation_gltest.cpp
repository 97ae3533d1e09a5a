// Foundation GL tests: float accumulation with jitter, backend equivalence, readable errors
// for incomplete framebuffers and broken shaders, and the program cache.
#include <array>
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "gl/errors.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "gl_fixture.h"

namespace penumbra::test {
namespace {

constexpr int kFoundationSize = 8;
// A triangle in NDC chosen so no pixel centre of the 8x8 target lies on an edge for any of
// the jitters below (checked by the CPU reference, which would otherwise be ambiguous).
constexpr std::array<float, 6> kTriangle = {-0.93f, -0.81f, 0.87f, -0.66f, -0.21f, 0.91f};

// 16 sub-pixel jitters (in pixels) from the 2D Halton (2,3) sequence, centred on 0.
std::array<std::array<float, 2>, 16> jitters() {
  std::array<std::array<float, 2>, 16> j{};
  for (int i = 0; i < 16; ++i) {
    auto halton = [](int index, int base) {
      float f = 1.0f, r = 0.0f;
      for (int k = index; k > 0; k /= base) {
        f /= static_cast<float>(base);
        r += f * static_cast<float>(k % base);
      }
      return r;
    };
    j[i] = {halton(i + 1, 2) - 0.5f, halton(i + 1, 3) - 0.5f};
  }
  return j;
}

// CPU coverage of a pixel centre by the jittered triangle (edge functions).
bool covered(float px, float py, float jx, float jy) {
  auto toPix = [](float ndc) { return (ndc * 0.5f + 0.5f) * kFoundationSize; };
  float x[3], y[3];
  for (int i = 0; i < 3; ++i) {
    x[i] = toPix(kTriangle[2 * i]) + jx;
    y[i] = toPix(kTriangle[2 * i + 1]) + jy;
  }
  auto edge = [&](int a, int b) {
    return (x[b] - x[a]) * (py - y[a]) - (y[b] - y[a]) * (px - x[a]);
  };
  float e0 = edge(0, 1), e1 = edge(1, 2), e2 = edge(2, 0);
  return (e0 > 0 && e1 > 0 && e2 > 0) || (e0 < 0 && e1 < 0 && e2 < 0);
}

struct Target {
  gl::Texture2D texture;
  gl::Framebuffer framebuffer;
};

Target makeTarget(gl::PixelFormat format) {
  auto tex = gl::Texture2D::create(
      {.width = kFoundationSize, .height = kFoundationSize, .format = format});
  EXPECT_TRUE(tex.ok()) << (tex.ok() ? "" : tex.message());
  Target t{std::move(*tex), gl::Framebuffer::create()};
  t.framebuffer.attachColor(0, t.texture);
  t.framebuffer.setDrawBuffers(1);
  EXPECT_TRUE(t.framebuffer.checkComplete().ok());
  return t;
}

// Renders the 16 jittered frames additively; frame k writes colour ((k+1)/16, 1/16, 0.5, 1).
std::vector<float> renderAccumulated(gl::ShaderLibrary& library, gl::PixelFormat format) {
  Target target = makeTarget(format);
  auto program = library.program("test/jitter_quad.vert", "test/constant.frag");
  EXPECT_TRUE(program.ok()) << (program.ok() ? "" : program.message());
  auto vbo = gl::Buffer::create(gl::BufferKind::Vertex, std::span<const float>(kTriangle));
  EXPECT_TRUE(vbo.ok());
  gl::VertexArray vao = gl::VertexArray::create();
  vao.setAttribute(0, *vbo, 2, gl::AttribType::Float, false, 0, 0);

  target.framebuffer.bind();
  gl::setViewport(0, 0, kFoundationSize, kFoundationSize);
  gl::clearBufferFloat(0, 0, 0, 0, 0);
  gl::apply({.depthTest = gl::DepthTest::Off,
             .depthWrite = false,
             .blend = gl::Blend::Additive,
             .cull = gl::Cull::None});
  (*program)->use();
  const auto js = jitters();
  for (int k = 0; k < 16; ++k) {
    (*program)->set("uJitter", glm::vec2(js[k][0], js[k][1]) * (2.0f / kFoundationSize));
    (*program)->set("uColor", glm::vec4((k + 1) / 16.0f, 1.0f / 16.0f, 0.5f, 1.0f));
    vao.draw(gl::Primitive::Triangles, 3);
  }
  EXPECT_TRUE(gl::checkError("accumulating").ok());
  return target.framebuffer.readRgbaFloat(0, 0, 0, kFoundationSize, kFoundationSize);
}

class FoundationGLTest : public GlFixture {};

TEST_F(FoundationGLTest, ReportsCapabilitiesOfAWebGl2ClassContext) {
  EXPECT_GE(caps().maxTextureSize, 2048);
  EXPECT_GE(caps().maxDrawBuffers, 4);
  EXPECT_TRUE(caps().colorBufferFloat || caps().colorBufferHalfFloat);
  EXPECT_NE(caps().report().find("accumulation format"), std::string::npos);
  EXPECT_FALSE(context().description().empty());
}

TEST_F(FoundationGLTest, ForcedHalfFloatPolicyPicksRgba16f) {
  auto c = gl::queryCapabilities(context().isDesktopGl(), {.forceHalfFloat = true});
  ASSERT_TRUE(c.colorBufferHalfFloat);
  EXPECT_EQ(c.accumulationFormat, gl::PixelFormat::RGBA16F);
  ASSERT_FALSE(c.fallbacks.empty());
}

TEST_F(FoundationGLTest, AccumulatesJitteredFramesInFloatTargetLikeTheCpu) {
  ASSERT_TRUE(caps().colorBufferFloat && caps().floatBlend);
  gl::ShaderLibrary library;
  std::vector<float> gpu = renderAccumulated(library, gl::PixelFormat::RGBA32F);
  const auto js = jitters();
  int partial = 0;
  for (int y = 0; y < kFoundationSize; ++y) {
    for (int x = 0; x < kFoundationSize; ++x) {
      float expected[4] = {0, 0, 0, 0};
      int hits = 0;
      for (int k = 0; k < 16; ++k) {
        if (!covered(x + 0.5f, y + 0.5f, js[k][0], js[k][1])) continue;
        ++hits;
        expected[0] += (k + 1) / 16.0f;
        expected[1] += 1.0f / 16.0f;
        expected[2] += 0.5f;
        expected[3] += 1.0f;
      }
      if (hits > 0 && hits < 16) ++partial;
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(gpu[(y * kFoundationSize + x) * 4 + c], expected[c], 1e-5f)
            << "pixel " << x << "," << y << " channel " << c;
      }
    }
  }
  EXPECT_GT(partial, 4) << "the jitter must produce partially covered (anti-aliased) pixels";
}

TEST_F(FoundationGLTest, HalfFloatTargetAccumulatesWithinHalfPrecision) {
  ASSERT_TRUE(caps().colorBufferHalfFloat);
  gl::ShaderLibrary library;
  std::vector<float> half = renderAccumulated(library, gl::PixelFormat::RGBA16F);
  std::vector<float> full = renderAccumulated(library, gl::PixelFormat::RGBA32F);
  for (size_t i = 0; i < full.size(); ++i) EXPECT_NEAR(half[i], full[i], 0.02f);
}

// An allocation's failure is reported at once natively; with deferred checks (the WebGL
// build's default: no glGetError round trip per allocation) by the next checkError, naming the
// first allocation since the last check.
TEST_F(FoundationGLTest, AllocationFailuresAreReportedAtOnceOrByTheNextCheck) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  ASSERT_GT(maxSize, 0);
  const int tooWide = maxSize + 1;
  gl::clearErrors();
  auto now = gl::Renderbuffer::create(tooWide, 4, gl::PixelFormat::RGBA8);
  ASSERT_FALSE(now.ok());
  EXPECT_NE(now.message().find("x4 renderbuffer failed: GL_INVALID_VALUE"), std::string::npos)
      << now.message();

  gl::setDeferredAllocationChecks(true);
  auto fine = gl::Renderbuffer::create(4, 4, gl::PixelFormat::RGBA8);
  EXPECT_TRUE(fine.ok());
  EXPECT_TRUE(gl::checkError("frame 1").ok());  // nothing failed: nothing is reported
  auto later = gl::Renderbuffer::create(tooWide, 4, gl::PixelFormat::RGBA8);
  EXPECT_TRUE(later.ok());  // not checked yet
  auto after = gl::Renderbuffer::create(8, 8, gl::PixelFormat::RGBA8);
  const Status frame = gl::checkError("frame 2");
  gl::setDeferredAllocationChecks(false);
  ASSERT_FALSE(frame.ok());
  const std::string expected = "frame 2 (after allocating a " + std::to_string(tooWide) +
                               "x4 renderbuffer, or a later call) failed: GL_INVALID_VALUE";
  EXPECT_EQ(frame.message(), expected);
  EXPECT_TRUE(gl::checkError("frame 3").ok());
}

TEST_F(FoundationGLTest, IncompleteFramebufferIsAReadableError) {
  gl::Framebuffer fb = gl::Framebuffer::create();
  auto status = fb.checkComplete();
  ASSERT_FALSE(status.ok());
  EXPECT_NE(status.message().find("GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT"),
            std::string::npos)
      << status.message();
  gl::Framebuffer::bindDefault();
}

TEST_F(FoundationGLTest, ShaderSyntaxErrorNamesFileAndLine) {
  gl::ShaderLibrary library({
      {"prelude.glsl", "precision highp float;\n"},
      {"ok.vert", "void main() { gl_Position = vec4(0.0); }\n"},
      {"chunk.glsl", "float helper() { return 1.0; }\n"},
      {"broken.frag",
       "#include \"chunk.glsl\"\nout vec4 c;\nvoid main() {\n  c = vec4(helper()) +;\n}\n"},
  });
  auto program = library.program("ok.vert", "broken.frag");
  ASSERT_FALSE(program.ok());
  EXPECT_NE(program.message().find("broken.frag:4"), std::string::npos) << program.message();
  EXPECT_EQ(library.cachedPrograms(), 0u);
}

TEST_F(FoundationGLTest, MissingIncludeAndCycleAreErrors) {
  gl::ShaderLibrary library({{"a.frag", "#include \"b.glsl\"\n"},
                             {"b.glsl", "#include \"a.frag\"\n"},
                             {"c.frag", "#include \"nope.glsl\"\n"}});
  auto cyc = library.compose("a.frag", gl::ShaderStage::Fragment, {});
  ASSERT_FALSE(cyc.ok());
  EXPECT_NE(cyc.message().find("cycle"), std::string::npos);
  auto missing = library.compose("c.frag", gl::ShaderStage::Fragment, {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.message().find("nope.glsl"), std::string::npos);
}

TEST_F(FoundationGLTest, ProgramCacheIsKeyedByFilesAndDefines) {
  gl::ShaderLibrary library;
  auto a = library.program("test/jitter_quad.vert", "test/constant.frag");
  auto b = library.program("test/jitter_quad.vert", "test/constant.frag");
  auto c = library.program("test/jitter_quad.vert", "test/constant.frag", {{"VARIANT", "2"}});
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(*a, *b);
  EXPECT_NE(*a, *c);
  EXPECT_EQ(library.cachedPrograms(), 2u);
}

TEST_F(FoundationGLTest, AbsurdTextureSizeIsAnError) {
  auto tex =
      gl::Texture2D::create({.width = 1 << 20, .height = 4, .format = gl::PixelFormat::RGBA8});
  ASSERT_FALSE(tex.ok());
  EXPECT_NE(tex.message().find("outside"), std::string::npos);
}

TEST_F(FoundationGLTest, TimerQueryMeasuresWhenAvailable) {
  auto q = gl::TimerQuery::create(caps().timerQuery);
  if (!caps().timerQuery) {
    EXPECT_FALSE(q.has_value());
    return;
  }
  ASSERT_TRUE(q.has_value());
  q->begin();
  gl::clearColor(0, 0, 0, 0);
  q->end();
  auto ns = q->resultNs();
  gl::clearErrors();
  if (ns) {
    EXPECT_LT(*ns, 10000000000ull);
  }
}

}  // namespace
}  // namespace penumbra::test

namespace penumbra::test {
namespace {

// Renders the accumulation image on a context of the given backend.
std::vector<float> renderOn(GlBackend backend, std::string& description) {
  auto ctx = GlContext::create({.backend = backend});
  EXPECT_TRUE(ctx.ok()) << (ctx.ok() ? "" : ctx.message());
  if (!ctx.ok()) return {};
  description = (*ctx)->description();
  gl::ShaderLibrary library;  // programs belong to the context that built them
  return renderAccumulated(library, gl::PixelFormat::RGBA32F);
}

TEST(BackendEquivalenceGLTest, EglAndOsMesaProduceTheSameImage) {
  std::string eglName, osmesaName;
  std::vector<float> egl = renderOn(GlBackend::EglSurfaceless, eglName);
  std::vector<float> osmesa = renderOn(GlBackend::OSMesa, osmesaName);
  ASSERT_EQ(egl.size(), osmesa.size());
  ASSERT_FALSE(egl.empty());
  EXPECT_NE(eglName.find("EGL"), std::string::npos);
  EXPECT_NE(osmesaName.find("OSMesa"), std::string::npos);
  for (size_t i = 0; i < egl.size(); ++i) EXPECT_EQ(egl[i], osmesa[i]) << "value " << i;
}

TEST(BackendSelectionGLTest, UnknownBackendNameIsAnError) {
  auto b = parseBackend("vulkan");
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.message().find("egl"), std::string::npos);
  EXPECT_EQ(*parseBackend("OSMesa"), GlBackend::OSMesa);
}

}  // namespace
}  // namespace penumbra::test
