// KHR_materials_ior, _specular, _clearcoat, _sheen and _unlit in the renderer: white
// furnaces (energy is conserved whatever F0 and F90 are), the reflectance following the index
// of refraction and the specular colour, and unlit surfaces showing their base colour.
#include <cstdio>

#include <gtest/gtest.h>

#include "penumbra/environment.h"
#include "render_fixture.h"
#include "test_support.h"

namespace penumbra::test {
namespace {

class MaterialExtensionsGLTest : public GlFixture {};

constexpr int kExtensionsSize = 48;

// A unit sphere seen from 4 units away with the given vertical field of view, 8 frames.
Result<Image> renderSphere(const Material& material, glm::vec3 sky, float fovDeg,
                           const std::vector<Light>& lights = {}) {
  Scene s;
  s.materials.push_back(material);
  s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
  s.lights = lights;
  finishScene(s);
  RenderSettings rs;
  rs.width = rs.height = kExtensionsSize;
  rs.progressive.frames = 8;
  auto img =
      renderRadiance(s, uniformEnvironment(sky), lookAtCamera({0, 0, 4}, {0, 0, 0}, fovDeg), rs);
  EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
  return img;
}

// Mean radiance (RGB) of the sphere's central 28x28 pixels under a uniform environment.
glm::vec3 sphereUnderUniformSky(const Material& material, glm::vec3 sky) {
  auto img = renderSphere(material, sky, 20.0f);
  if (!img.ok()) return glm::vec3(-1.0f);
  glm::vec3 sum(0.0f);
  for (int y = 10; y < 38; ++y) {
    for (int x = 10; x < 38; ++x)
      sum += glm::vec3(img->pixel(x, y)[0], img->pixel(x, y)[1], img->pixel(x, y)[2]);
  }
  return sum / float(28 * 28);
}

TEST_F(MaterialExtensionsGLTest, WhiteFurnaceHoldsForAnyIorAndSpecular) {
  // A white dielectric reflects exactly the environment: what the specular lobe does not
  // reflect reaches the diffuse base (glTF's fresnel_mix), for F0 from 0 to 0.18 and F90 < 1.
  for (float ior : {1.0f, 1.5f, 2.5f}) {
    for (float spec : {0.0f, 0.5f, 1.0f}) {
      Material m = lambert(glm::vec3(1.0f));
      m.roughnessFactor = 0.5f;
      m.ior = ior;
      m.specularFactor = spec;
      const glm::vec3 c = sphereUnderUniformSky(m, glm::vec3(1.0f));
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(c[k], 1.0f, 0.02f) << "ior " << ior << ", specular " << spec;
      }
    }
  }
}

TEST_F(MaterialExtensionsGLTest, ReflectanceFollowsIorAndSpecularColour) {
  // A black dielectric shows only its specular reflection: more with a higher index (F0 0.04
  // at 1.5, 0.18 at 2.5), none of a colour the specular colour removes, none at specular 0.
  Material m = lambert(glm::vec3(0.0f));
  m.roughnessFactor = 0.3f;
  const glm::vec3 glass = sphereUnderUniformSky(m, glm::vec3(1.0f));
  m.ior = 2.5f;
  const glm::vec3 diamondLike = sphereUnderUniformSky(m, glm::vec3(1.0f));
  EXPECT_GT(diamondLike.g, 2.0f * glass.g);
  m.ior = 1.5f;
  m.specularColorFactor = glm::vec3(1.0f, 0.0f, 1.0f);
  const glm::vec3 tinted = sphereUnderUniformSky(m, glm::vec3(1.0f));
  EXPECT_NEAR(tinted.r, glass.r, 0.02f * glass.r + 1e-3f);
  EXPECT_LT(tinted.g, 0.6f * glass.g) << "only the grazing (F90) part stays";
  m.specularColorFactor = glm::vec3(1.0f);
  m.specularFactor = 0.0f;
  const glm::vec3 none = sphereUnderUniformSky(m, glm::vec3(1.0f));
  EXPECT_LT(none.g, 1e-3f);
}

TEST_F(MaterialExtensionsGLTest, ClearcoatAddsALayerAndKeepsTheFurnace) {
  // A coat over a white base still reflects the white environment (what the coat reflects,
  // the base below does not get: 1 - coat F(n.v)), and over a black base it adds a glossy
  // reflection of its own, scaled by its strength.
  for (float rough : {0.0f, 0.5f}) {
    Material m = lambert(glm::vec3(1.0f));
    m.clearcoat = 1.0f;
    m.clearcoatRoughness = rough;
    const glm::vec3 c = sphereUnderUniformSky(m, glm::vec3(1.0f));
    EXPECT_NEAR(c.g, 1.0f, 0.03f) << "coat roughness " << rough;
  }
  Material black = lambert(glm::vec3(0.0f));
  black.specularFactor = 0.0f;  // no base reflection: what remains is the coat's
  const glm::vec3 bare = sphereUnderUniformSky(black, glm::vec3(1.0f));
  black.clearcoat = 1.0f;
  const glm::vec3 full = sphereUnderUniformSky(black, glm::vec3(1.0f));
  black.clearcoat = 0.5f;
  const glm::vec3 half = sphereUnderUniformSky(black, glm::vec3(1.0f));
  EXPECT_LT(bare.g, 1e-3f);
  // At least F0 everywhere, more at grazing angles; the centre's 0.04 is only as exact as the
  // half-float DFG table (about 1e-4).
  EXPECT_GT(full.g, 0.0395f) << "at least F0 everywhere, more at grazing angles";
  EXPECT_NEAR(half.g, 0.5f * full.g, 0.02f * full.g);
}

TEST_F(MaterialExtensionsGLTest, ClearcoatNormalMapTiltsOnlyTheCoat) {
  // A coat normal map that tilts the normal by about 72 degrees: at the sphere's centre the
  // coat sees the sky at a grazing angle and reflects more of it (Fresnel), while the base,
  // on the unmapped normal, does not change.
  const auto render = [](Material m, bool mapped) {
    Scene s;
    if (mapped) {
      ImageData tilt;  // tangent-space (0.95, 0, 0.31), one texel
      tilt.name = "tilt";
      tilt.width = tilt.height = 1;
      tilt.pixels = {249, 128, 167, 255};
      s.images.push_back(tilt);
      m.clearcoatNormalTexture.image = 0;
    }
    s.materials.push_back(m);
    s.meshes.push_back(sphereMesh({0, 0, 0}, 1.0f, 0, 96));
    Primitive& p = s.meshes[0].primitives[0];
    for (const glm::vec3& n : p.normals) {
      const glm::vec3 t = glm::normalize(glm::cross(glm::vec3(0, 1, 0.001f), n));
      p.tangents.emplace_back(t, 1.0f);
    }
    finishScene(s);
    RenderSettings rs;
    rs.width = rs.height = kExtensionsSize;
    rs.progressive.frames = 8;
    auto img = renderRadiance(s, uniformEnvironment(glm::vec3(1.0f)),
                              lookAtCamera({0, 0, 4}, {0, 0, 0}, 20.0f), rs);
    EXPECT_TRUE(img.ok()) << (img.ok() ? "" : img.message());
    glm::vec3 sum(0.0f);
    if (!img.ok()) return sum;
    for (int y = 20; y < 28; ++y) {
      for (int x = 20; x < 28; ++x)
        sum += glm::vec3(img->pixel(x, y)[0], img->pixel(x, y)[1], img->pixel(x, y)[2]);
    }
    return sum / 64.0f;
  };
  Material coated = lambert(glm::vec3(0.0f));
  coated.specularFactor = 0.0f;  // what is reflected is the coat's
  coated.clearcoat = 1.0f;
  const glm::vec3 flat = render(coated, false), tilted = render(coated, true);
  EXPECT_NEAR(flat.g, 0.045f, 0.01f) << "about F0 near normal incidence";
  // Schlick at n.v = 0.31: 0.04 + 0.96 (1 - 0.31)^5 = 0.19.
  EXPECT_GT(tilted.g, 2.5f * flat.g) << "grazing on the tilted coat normal";
  Material base = lambert(glm::vec3(0.5f));  // no coat: the map changes nothing
  const glm::vec3 a = render(base, false), b = render(base, true);
  EXPECT_NEAR(b.g, a.g, 1e-4f);
}

// Mean radiance of the sphere's central disk (radius 6 px) and of a ring just inside its rim.
struct CentreAndRim {
  glm::vec3 centre{0.0f}, rim{0.0f};
  glm::vec3 total{0.0f};  // summed over the whole image
};
CentreAndRim sphereCentreAndRim(const Material& material, glm::vec3 sky,
                                const std::vector<Light>& lights = {}) {
  auto img = renderSphere(material, sky, 40.0f, lights);
  CentreAndRim out;
  if (!img.ok()) return out;
  // The sphere's radius on screen: tan(asin(1/4)) / tan(20 deg) of the half width.
  const float radius =
      std::tan(std::asin(0.25f)) / std::tan(glm::radians(20.0f)) * kExtensionsSize * 0.5f;
  int nc = 0, nr = 0;
  for (int y = 0; y < kExtensionsSize; ++y) {
    for (int x = 0; x < kExtensionsSize; ++x) {
      const float d =
          std::hypot(x + 0.5f - kExtensionsSize * 0.5f, y + 0.5f - kExtensionsSize * 0.5f);
      const glm::vec3 c(img->pixel(x, y)[0], img->pixel(x, y)[1], img->pixel(x, y)[2]);
      out.total += c;
      if (d < 6.0f) out.centre += c, ++nc;
      if (d > radius - 3.0f && d < radius - 1.5f) out.rim += c, ++nr;
    }
  }
  out.centre /= float(std::max(nc, 1));
  out.rim /= float(std::max(nr, 1));
  return out;
}

TEST_F(MaterialExtensionsGLTest, SheenKeepsTheFurnaceAndBrightensTheRim) {
  // Over a white base, a white sheen changes nothing in a white furnace: the base receives
  // exactly what the sheen does not reflect (albedo scaling), at any sheen roughness.
  for (float rough : {0.3f, 1.0f}) {
    Material m = lambert(glm::vec3(1.0f));
    m.sheenColor = glm::vec3(1.0f);
    m.sheenRoughness = rough;
    const glm::vec3 c = sphereUnderUniformSky(m, glm::vec3(1.0f));
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], 1.0f, 0.03f) << "sheen roughness " << rough;
  }
  // Over a black base without reflection, only the sheen remains: a rim brighter than the
  // centre (Charlie's lobe faces grazing directions), coloured by the sheen colour, never
  // brighter than the environment.
  Material black = lambert(glm::vec3(0.0f));
  black.specularFactor = 0.0f;
  black.sheenColor = glm::vec3(1.0f, 0.5f, 0.0f);
  black.sheenRoughness = 0.5f;
  const CentreAndRim cr = sphereCentreAndRim(black, glm::vec3(1.0f));
  EXPECT_GT(cr.rim.r, 2.0f * cr.centre.r);
  EXPECT_GT(cr.rim.r, 0.2f);
  EXPECT_LT(cr.rim.r, 1.0f);
  EXPECT_NEAR(cr.rim.g, 0.5f * cr.rim.r, 0.02f * cr.rim.r);
  EXPECT_LT(cr.rim.b, 1e-4f);
  // No sheen colour: nothing at all.
  black.sheenColor = glm::vec3(0.0f);
  EXPECT_LT(sphereCentreAndRim(black, glm::vec3(1.0f)).rim.r, 1e-4f);
}

TEST_F(MaterialExtensionsGLTest, AreaAndPunctualLightsShowTheSheen) {
  // In the dark, lit from above and behind the sphere (grazing for the rim the camera sees):
  // a black base without reflection shows only its sheen, in the sheen colour.
  Light area;
  area.type = LightType::Rect;
  area.intensity = 500.0f;
  area.position = {0, 2.5f, -1.5f};
  area.direction = glm::normalize(glm::vec3(0, -2.5f, 1.5f));
  area.right = {1, 0, 0};
  area.up = glm::normalize(glm::cross(area.right, area.direction));
  area.width = area.height = 1.0f;
  Light sun;
  sun.type = LightType::Directional;
  sun.intensity = 30.0f;
  sun.direction = area.direction;
  Material black = lambert(glm::vec3(0.0f));
  black.specularFactor = 0.0f;
  black.sheenRoughness = 0.5f;
  // The sheen's share of what a white diffuse base reflects, per light type, over the whole
  // lit crescent: the area light's sheen (its irradiance times the lobe toward its centre)
  // must agree with the directional light's (exact lobe) within a factor 2 for this
  // near-distant light. Measured 1.56 to 1.70 at 8 to 64 frames under two jitter sequences;
  // the two lights are not the same light (the area light subtends 0.12 sr, so it lights a
  // wider crescent), hence not 1. A thin band at the rim instead swung from 1.5 to 2.5 with the
  // jitter sequence: the crescent is two pixels thick there.
  float share[2] = {0.0f, 0.0f};
  int k = 0;
  for (const Light& light : {area, sun}) {
    const char* what = light.type == LightType::Rect ? "area light" : "directional light";
    black.sheenColor = glm::vec3(0.0f);
    const CentreAndRim none = sphereCentreAndRim(black, glm::vec3(0.0f), {light});
    black.sheenColor = glm::vec3(0.0f, 1.0f, 0.0f);
    const CentreAndRim green = sphereCentreAndRim(black, glm::vec3(0.0f), {light});
    const CentreAndRim white =
        sphereCentreAndRim(lambert(glm::vec3(1.0f)), glm::vec3(0.0f), {light});
    EXPECT_LT(none.total.g, 1e-4f) << what;
    EXPECT_GT(white.rim.g, 0.05f) << what;
    EXPECT_LT(green.total.r + green.total.b, 1e-4f) << what;
    share[k++] = green.total.g / std::max(white.total.g, 1e-6f);
    EXPECT_GT(share[k - 1], 0.02f) << what;
    EXPECT_LT(share[k - 1], 1.0f) << what;
  }
  std::printf("sheen share of the lit crescent: area light %.4f, directional light %.4f\n",
              share[0], share[1]);
  EXPECT_LT(std::max(share[0], share[1]) / std::min(share[0], share[1]), 2.0f);
}

TEST_F(MaterialExtensionsGLTest, UnlitShowsItsBaseColour) {
  Material m = lambert(glm::vec3(0.2f, 0.5f, 0.8f));
  m.unlit = true;
  for (float sky : {0.0f, 3.0f}) {
    const glm::vec3 c = sphereUnderUniformSky(m, glm::vec3(sky));
    EXPECT_NEAR(c.r, 0.2f, 1e-3f);
    EXPECT_NEAR(c.g, 0.5f, 1e-3f);
    EXPECT_NEAR(c.b, 0.8f, 1e-3f);
  }
}

}  // namespace
}  // namespace penumbra::test
