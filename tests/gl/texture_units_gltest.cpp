// Texture units handed out per program at link (gl/program.h): each program numbers the
// samplers it uses from 0 in name order, binds by sampler name, rebinds after another program
// took its units, and the largest lighting variants fit WebGL2's 16.
#include <string>

#include <gtest/gtest.h>

#include "gl/program.h"
#include "gl/texture.h"
#include "gl_fixture.h"
#include "passes/lighting_variant.h"
#include "passes/limits.h"

namespace penumbra::test {
namespace {

class TextureUnitsGLTest : public GlFixture {};

gl::ShaderLibrary samplerLibrary() {
  return gl::ShaderLibrary({
      {"prelude.glsl", "precision highp float;\n"},
      {"quad.vert", "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n"},
      {"samplers.frag",
       "uniform sampler2D uB;\n"
       "uniform samplerCube uA;\n"
       "uniform highp sampler2DArray uC;\n"
       "uniform sampler2D uUnused;\n"
       "out vec4 c;\n"
       "void main() {\n"
       "  c = texture(uB, vec2(0.5)) + texture(uA, vec3(1.0, 0.0, 0.0)) +\n"
       "      texture(uC, vec3(0.5, 0.5, 0.0));\n"
       "}\n"},
  });
}

gl::Texture2D smallTexture() {
  auto t = gl::Texture2D::create({.width = 2, .height = 2, .format = gl::PixelFormat::RGBA8});
  EXPECT_TRUE(t.ok()) << t.message();
  return std::move(*t);
}

GLint bound2d(int unit) {
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  GLint id = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &id);
  return id;
}

TEST_F(TextureUnitsGLTest, SamplersGetUnitsFromZeroInNameOrder) {
  gl::ShaderLibrary library = samplerLibrary();
  auto p = library.program("quad.vert", "samplers.frag");
  ASSERT_TRUE(p.ok()) << p.message();
  const gl::Program& prog = **p;
  EXPECT_EQ(prog.samplerCount(), 3);
  EXPECT_EQ(prog.unit("uA"), 0);
  EXPECT_EQ(prog.unit("uB"), 1);
  EXPECT_EQ(prog.unit("uC"), 2);
  EXPECT_EQ(prog.unit("uUnused"), -1);  // the linker dropped it: no unit
  EXPECT_EQ(prog.unit("uNothing"), -1);
  // The program's sampler uniforms hold those units.
  GLint value = -1;
  glGetUniformiv(prog.id(), prog.location("uB"), &value);
  EXPECT_EQ(value, 1);
  glGetUniformiv(prog.id(), prog.location("uC"), &value);
  EXPECT_EQ(value, 2);
}

TEST_F(TextureUnitsGLTest, BindRebindAndReleaseActOnTheSamplersUnit) {
  gl::ShaderLibrary library = samplerLibrary();
  auto p = library.program("quad.vert", "samplers.frag");
  ASSERT_TRUE(p.ok()) << p.message();
  const gl::Program& prog = **p;
  prog.use();
  gl::Texture2D a = smallTexture(), b = smallTexture();
  EXPECT_EQ(prog.unboundSampler(), "uA");
  prog.bind("uB", a);
  prog.bind("uUnused", b);  // not used: binds nothing
  EXPECT_EQ(bound2d(1), static_cast<GLint>(a.id()));
  EXPECT_NE(bound2d(3), static_cast<GLint>(b.id()));
  // Another program's bind took unit 1; rebind() puts a back.
  b.bind(1);
  EXPECT_EQ(bound2d(1), static_cast<GLint>(b.id()));
  prog.rebind();
  EXPECT_EQ(bound2d(1), static_cast<GLint>(a.id()));
  prog.release("uB");
  EXPECT_EQ(bound2d(1), 0);
  EXPECT_EQ(prog.unboundSampler(), "uA");
}

TEST(SamplerCountTest, TooManyIsAnErrorNamingTheProgramAndBothNumbers) {
  EXPECT_TRUE(gl::checkSamplerCount("a + b", 16, 16).ok());
  const Status s = gl::checkSamplerCount("mesh.vert + lighting.frag", 17, 16);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("mesh.vert + lighting.frag uses 17 textures"), std::string::npos)
      << s.message();
  EXPECT_NE(s.message().find("offers 16 texture units"), std::string::npos) << s.message();
}

// Every texture slot and feature, every light kind, the probe volume and its cache, the
// occlusion rays and the running mean; `pointShadows` or `lightCache` (a batch never has both:
// LightingPass::readsLightCache).
passes::ProgramKey largest(bool pointShadows) {
  passes::LightingVariant v;
  v.occlusion = v.area = v.punctual = v.probes = v.probeCache = v.accumulate = 1;
  v.pointShadows = pointShadows ? 1 : 0;
  v.lightCache = pointShadows ? 0 : 1;
  v.punctualKinds = kAllPunctualSamples;
  v.areaCount = 2;
  v.areaStarts = 1;
  v.punctualCount = 2;
  MaterialFeatures f;
  f.textures = (1u << kTextureSlotCount) - 1;
  f.clearcoat = f.sheen = f.iridescence = f.anisotropy = f.diffuseTransmission = 1;
  f.lightCacheable = pointShadows ? 0 : 1;
  return passes::ProgramKey(v, f);
}

TEST_F(TextureUnitsGLTest, LargestLightingProgramsFitSixteenUnits) {
  gl::ShaderLibrary library;
  library.setCommonDefines(passes::commonDefines());
  for (const bool pointShadows : {true, false}) {
    const passes::ProgramKey key = largest(pointShadows);
    auto p = library.program("mesh.vert", key.fragmentFile(), key.defines());
    ASSERT_TRUE(p.ok()) << p.message();
    const gl::Program& prog = **p;
    EXPECT_LE(prog.samplerCount(), 16) << (pointShadows ? "point shadows" : "light cache");
    // The roles the old table shared by hand now have units of their own where they meet.
    EXPECT_GE(prog.unit("uOcclusion"), 0);
    EXPECT_GE(prog.unit("uProbeCache"), 0);
    EXPECT_GE(prog.unit(pointShadows ? "uPointShadow1" : "uLightCache"), 0);
    EXPECT_GE(prog.unit("uMaterialLayers"), 0);
    std::printf("lighting.frag, %s: %d samplers\n",
                pointShadows ? "point shadows" : "light cache", prog.samplerCount());
  }
  // The compose pass reads the frame's copy and the glass light beside the rest.
  passes::ProgramKey compose = largest(true);
  compose.transmission = 2;
  auto c = library.program("mesh.vert", compose.fragmentFile(), compose.defines());
  ASSERT_TRUE(c.ok()) << c.message();
  EXPECT_LE((*c)->samplerCount(), 16);
  EXPECT_GE((*c)->unit("uBehind"), 0);
  EXPECT_GE((*c)->unit("uGlassLight"), 0);
  EXPECT_NE((*c)->unit("uBehind"), (*c)->unit("uGlassLight"));
}

}  // namespace
}  // namespace penumbra::test
