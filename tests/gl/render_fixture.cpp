#include "render_fixture.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace penumbra::test {

Mesh quadMesh(float size, float y, int material) {
  const float h = size * 0.5f;
  return rectangle({-h, y, -h}, {0, 0, size}, {size, 0, 0}, {0, 1, 0}, material);
}

Mesh rectangle(glm::vec3 p0, glm::vec3 e1, glm::vec3 e2, glm::vec3 n, int material) {
  Mesh m;
  Primitive p;
  p.positions = {p0, p0 + e1, p0 + e1 + e2, p0 + e2};
  p.normals.assign(4, n);
  p.indices = glm::dot(glm::cross(e1, e2), n) > 0.0f ? std::vector<uint32_t>{0, 1, 2, 0, 2, 3}
                                                     : std::vector<uint32_t>{0, 2, 1, 0, 3, 2};
  for (const glm::vec3& v : p.positions) p.bounds.extend(v);
  p.material = material;
  m.primitives.push_back(std::move(p));
  return m;
}

Mesh boxMesh(glm::vec3 lo, glm::vec3 hi, int material) {
  Mesh m;
  Primitive p;
  auto face = [&](glm::vec3 n, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    uint32_t base = static_cast<uint32_t>(p.positions.size());
    for (auto v : {a, b, c, d}) {
      p.positions.push_back(v);
      p.normals.push_back(n);
      p.bounds.extend(v);
    }
    // Wind counter-clockwise as seen from outside (along -n).
    glm::vec3 cr = glm::cross(b - a, c - a);
    if (glm::dot(cr, n) > 0) {
      p.indices.insert(p.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    } else {
      p.indices.insert(p.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  };
  face({0, 1, 0}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
  face({0, -1, 0}, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
  face({1, 0, 0}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});
  face({-1, 0, 0}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z});
  face({0, 0, 1}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
  face({0, 0, -1}, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
  p.material = material;
  m.primitives.push_back(std::move(p));
  return m;
}

Mesh insideBox(glm::vec3 lo, glm::vec3 hi, int material) {
  Mesh m = boxMesh(lo, hi, material);
  for (Primitive& p : m.primitives) {
    for (glm::vec3& n : p.normals) n = -n;
    for (size_t i = 0; i + 2 < p.indices.size(); i += 3)
      std::swap(p.indices[i + 1], p.indices[i + 2]);
  }
  return m;
}

Material lambert(glm::vec3 albedo) {
  Material m;
  m.baseColorFactor = glm::vec4(albedo, 1.0f);
  m.metallicFactor = 0.0f;
  m.roughnessFactor = 1.0f;
  return m;
}

Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfovDeg) {
  Camera c;
  glm::vec3 up =
      std::abs(glm::normalize(target - eye).y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
  c.world = glm::inverse(glm::lookAt(eye, target, up));
  c.yfov = glm::radians(yfovDeg);
  c.znear = 0.01f;
  return c;
}

void finishScene(Scene& scene) {
  scene.instances.clear();
  scene.bounds = {};
  for (size_t i = 0; i < scene.meshes.size(); ++i) {
    Instance inst;
    inst.mesh = static_cast<int>(i);
    scene.instances.push_back(inst);
    for (auto& p : scene.meshes[i].primitives) scene.bounds.extend(p.bounds);
  }
}

void scaleScene(Scene& scene, float k) {
  const auto scaleBounds = [k](Bounds& b) {
    if (b.valid()) b = {b.min * k, b.max * k};
  };
  for (Mesh& m : scene.meshes) {
    for (Primitive& p : m.primitives) {
      for (glm::vec3& v : p.positions) v *= k;
      scaleBounds(p.bounds);
    }
  }
  for (Instance& inst : scene.instances)
    inst.world[3] = glm::vec4(glm::vec3(inst.world[3]) * k, 1.0f);
  for (Light& l : scene.lights) {
    l.position *= k;
    l.width *= k;
    l.height *= k;
    l.range *= k;
  }
  for (Camera& c : scene.cameras) {
    c.world[3] = glm::vec4(glm::vec3(c.world[3]) * k, 1.0f);
    c.znear *= k;
    c.zfar *= k;
    c.ymag *= k;
  }
  scaleBounds(scene.bounds);
}

Result<Image> renderRadiance(const Scene& scene, const PackedEnvironment& env, const Camera& camera,
                             RenderSettings settings, const RendererOptions& options) {
  auto r = Renderer::create(options);
  if (!r) return r.error();
  PN_TRY((*r)->setSettings(settings));
  PN_TRY((*r)->setScene(scene));
  PN_TRY((*r)->setEnvironment(env));
  (*r)->setCamera(camera);
  while (!(*r)->converged()) {
    auto f = (*r)->step();
    if (!f) return f.error();
  }
  return (*r)->readRadiance();
}

}  // namespace penumbra::test

namespace penumbra::test {

Mesh sphereMesh(glm::vec3 c, float r, int material, int segments) {
  Mesh m;
  Primitive p;
  const int rings = segments / 2;
  for (int j = 0; j <= rings; ++j) {
    const float theta = static_cast<float>(M_PI) * j / rings;
    for (int i = 0; i <= segments; ++i) {
      const float phi = 2.0f * static_cast<float>(M_PI) * i / segments;
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                  -std::sin(theta) * std::sin(phi));
      p.positions.push_back(c + r * n);
      p.normals.push_back(n);
      p.bounds.extend(c + r * n);
    }
  }
  for (int j = 0; j < rings; ++j) {
    for (int i = 0; i < segments; ++i) {
      uint32_t a = j * (segments + 1) + i, b = a + segments + 1;
      p.indices.insert(p.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  p.material = material;
  m.primitives.push_back(std::move(p));
  return m;
}

double meanRgb(const Image& image) {
  double sum = 0.0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      for (int c = 0; c < 3; ++c) sum += image.pixel(x, y)[c];
    }
  }
  return sum / (3.0 * image.width * image.height);
}

double rmse(const Image& a, const Image& b) {
  double sum = 0.0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const double d = a.pixel(x, y)[c] - b.pixel(x, y)[c];
        sum += d * d;
        ++n;
      }
    }
  }
  return std::sqrt(sum / static_cast<double>(std::max<size_t>(n, 1)));
}

}  // namespace penumbra::test

namespace penumbra::test {

float radianceAt(const Image& image, const glm::mat4& viewProj, glm::vec3 p, bool bilinear) {
  const glm::vec4 c = viewProj * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(c) / c.w;
  const int w = image.width, h = image.height;
  const float x = (ndc.x * 0.5f + 0.5f) * static_cast<float>(w);
  const float y = (0.5f - ndc.y * 0.5f) * static_cast<float>(h);  // row 0 at the top
  const auto v = [&](int i, int j) {
    const float* px = image.pixel(std::clamp(i, 0, w - 1), std::clamp(j, 0, h - 1));
    return (px[0] + px[1] + px[2]) / 3.0f;
  };
  if (!bilinear) return v(static_cast<int>(x), static_cast<int>(y));
  const float cx = x - 0.5f, cy = y - 0.5f;
  const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
  const float fx = std::clamp(cx - static_cast<float>(x0), 0.0f, 1.0f);
  const float fy = std::clamp(cy - static_cast<float>(y0), 0.0f, 1.0f);
  return (1 - fy) * ((1 - fx) * v(x0, y0) + fx * v(x0 + 1, y0)) +
         fy * ((1 - fx) * v(x0, y0 + 1) + fx * v(x0 + 1, y0 + 1));
}

}  // namespace penumbra::test
