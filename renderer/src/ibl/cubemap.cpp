// Cube-map and panorama geometry, and panorama -> cube resampling.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ibl/parallel.h"
#include "ibl/sampling.h"
#include "penumbra/ibl.h"

namespace penumbra::ibl {
namespace {


// A box-filtered pyramid of the panorama's RGB, for area-filtered minification.
struct PanoramaLevel {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
  const float* at(int x, int y) const { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
};

std::vector<PanoramaLevel> buildPanoramaPyramid(const Image& panorama, int levels) {
  std::vector<PanoramaLevel> pyramid(1);
  PanoramaLevel& base = pyramid[0];
  base.width = panorama.width;
  base.height = panorama.height;
  base.rgb.resize(static_cast<size_t>(base.width) * base.height * 3);
  const int c = panorama.channels;
  for (size_t i = 0; i < static_cast<size_t>(base.width) * base.height; ++i) {
    const float* p = &panorama.pixels[i * c];
    for (int k = 0; k < 3; ++k) base.rgb[i * 3 + k] = c >= 3 ? p[k] : p[0];
  }
  while (static_cast<int>(pyramid.size()) < levels && pyramid.back().height > 1) {
    const PanoramaLevel& src = pyramid.back();
    PanoramaLevel dst;
    dst.width = std::max(1, src.width / 2);
    dst.height = std::max(1, src.height / 2);
    dst.rgb.resize(static_cast<size_t>(dst.width) * dst.height * 3);
    for (int y = 0; y < dst.height; ++y) {
      const int y0 = std::min(2 * y, src.height - 1);
      const int y1 = std::min(2 * y + 1, src.height - 1);
      for (int x = 0; x < dst.width; ++x) {
        const int x0 = std::min(2 * x, src.width - 1);
        const int x1 = std::min(2 * x + 1, src.width - 1);
        float* out = &dst.rgb[(static_cast<size_t>(y) * dst.width + x) * 3];
        for (int k = 0; k < 3; ++k) {
          out[k] = 0.25f *
                   (src.at(x0, y0)[k] + src.at(x1, y0)[k] + src.at(x0, y1)[k] + src.at(x1, y1)[k]);
        }
      }
    }
    pyramid.push_back(std::move(dst));
  }
  return pyramid;
}

// Bilinear lookup with horizontal wrap-around and vertical clamping.
glm::vec3 samplePanoramaLevel(const PanoramaLevel& level, float u, float v) {
  const float x = u * static_cast<float>(level.width) - 0.5f;
  const float y = v * static_cast<float>(level.height) - 0.5f;
  const float fx0 = std::floor(x);
  const float fy0 = std::floor(y);
  const float fx = x - fx0;
  const float fy = y - fy0;
  int xa = static_cast<int>(fx0) % level.width;
  if (xa < 0) xa += level.width;
  const int xb = xa + 1 == level.width ? 0 : xa + 1;
  const int ya = std::clamp(static_cast<int>(fy0), 0, level.height - 1);
  const int yb = std::clamp(static_cast<int>(fy0) + 1, 0, level.height - 1);
  const float* p00 = level.at(xa, ya);
  const float* p10 = level.at(xb, ya);
  const float* p01 = level.at(xa, yb);
  const float* p11 = level.at(xb, yb);
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const float top = p00[k] + (p10[k] - p00[k]) * fx;
    const float bottom = p01[k] + (p11[k] - p01[k]) * fx;
    out[k] = top + (bottom - top) * fy;
  }
  return out;
}

glm::vec3 samplePanorama(const std::vector<PanoramaLevel>& pyramid, const glm::vec3& dir,
                         float lod) {
  const glm::vec2 uv = panoramaCoord(dir);
  const float maxLod = static_cast<float>(pyramid.size() - 1);
  lod = std::clamp(lod, 0.0f, maxLod);
  const int l0 = static_cast<int>(lod);
  const float f = lod - static_cast<float>(l0);
  const glm::vec3 a = samplePanoramaLevel(pyramid[l0], uv.x, uv.y);
  if (f <= 0.0f || l0 + 1 >= static_cast<int>(pyramid.size())) return a;
  return a + (samplePanoramaLevel(pyramid[l0 + 1], uv.x, uv.y) - a) * f;
}

double solidAngleCorner(double x, double y) {
  return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0));
}

}  // namespace

const char* faceName(int face) {
  static const char* kNames[kFaceCount] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  return face >= 0 && face < kFaceCount ? kNames[face] : "?";
}

const char* faceTag(int face) {
  static const char* kTags[kFaceCount] = {"px", "nx", "py", "ny", "pz", "nz"};
  return face >= 0 && face < kFaceCount ? kTags[face] : "?";
}

glm::vec3 cubeDirection(int face, float s, float t) {
  // Inverse of the GL table: sc = 2s - 1, tc = 2t - 1 on the face of major axis ma = +-1.
  const float sc = 2.0f * s - 1.0f;
  const float tc = 2.0f * t - 1.0f;
  glm::vec3 d;
  switch (face) {
    case kPositiveX:
      d = {1.0f, -tc, -sc};
      break;
    case kNegativeX:
      d = {-1.0f, -tc, sc};
      break;
    case kPositiveY:
      d = {sc, 1.0f, tc};
      break;
    case kNegativeY:
      d = {sc, -1.0f, -tc};
      break;
    case kPositiveZ:
      d = {sc, -tc, 1.0f};
      break;
    default:
      d = {-sc, -tc, -1.0f};
      break;
  }
  return glm::normalize(d);
}

glm::vec3 texelDirection(int face, int x, int y, int size) {
  const float inv = 1.0f / static_cast<float>(size);
  return cubeDirection(face, (static_cast<float>(x) + 0.5f) * inv,
                       (static_cast<float>(y) + 0.5f) * inv);
}

CubeCoord cubeCoord(const glm::vec3& d) {
  const float ax = std::fabs(d.x);
  const float ay = std::fabs(d.y);
  const float az = std::fabs(d.z);
  CubeCoord c;
  float sc;
  float tc;
  float ma;
  if (ax >= ay && ax >= az) {
    ma = ax;
    c.face = d.x >= 0.0f ? kPositiveX : kNegativeX;
    sc = d.x >= 0.0f ? -d.z : d.z;
    tc = -d.y;
  } else if (ay >= az) {
    ma = ay;
    c.face = d.y >= 0.0f ? kPositiveY : kNegativeY;
    sc = d.x;
    tc = d.y >= 0.0f ? d.z : -d.z;
  } else {
    ma = az;
    c.face = d.z >= 0.0f ? kPositiveZ : kNegativeZ;
    sc = d.z >= 0.0f ? d.x : -d.x;
    tc = -d.y;
  }
  const float inv = 0.5f / ma;
  c.s = std::clamp(sc * inv + 0.5f, 0.0f, 1.0f);
  c.t = std::clamp(tc * inv + 0.5f, 0.0f, 1.0f);
  return c;
}

double texelSolidAngle(int x, int y, int size) {
  const double inv = 2.0 / size;
  const double x0 = x * inv - 1.0;
  const double y0 = y * inv - 1.0;
  const double x1 = x0 + inv;
  const double y1 = y0 + inv;
  return solidAngleCorner(x0, y0) - solidAngleCorner(x0, y1) - solidAngleCorner(x1, y0) +
         solidAngleCorner(x1, y1);
}

std::vector<double> texelSolidAngles(int size) {
  PN_CHECK(size > 0, "face size must be positive");
  std::vector<double> omega(static_cast<size_t>(size) * size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x)
      omega[static_cast<size_t>(y) * size + x] = texelSolidAngle(x, y, size);
  }
  return omega;
}

glm::vec3 panoramaDirection(float u, float v) {
  const float phi = 2.0f * kPi * (u - 0.5f);
  const float elevation = kPi * (0.5f - v);
  const float c = std::cos(elevation);
  return {c * std::cos(phi), std::sin(elevation), c * std::sin(phi)};
}

glm::vec2 panoramaCoord(const glm::vec3& d) {
  const float len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  float u = 0.5f + std::atan2(d.z, d.x) * (0.5f / kPi);
  if (u >= 1.0f) u -= 1.0f;
  const float v = 0.5f - std::asin(std::clamp(d.y / len, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

RadianceReport sanitizeRadiance(Image& image) {
  const int c = image.channels;
  const int colour = c >= 3 ? 3 : 1;
  RadianceReport r;
  const size_t n = static_cast<size_t>(image.width) * image.height;
  r.pixels = static_cast<int64_t>(n);
  for (size_t i = 0; i < n; ++i) {
    bool isNan = false, isInf = false, isNegative = false, isBright = false;
    for (int k = 0; k < colour; ++k) {
      float& v = image.pixels[i * c + k];
      if (std::isnan(v)) {
        v = 0.0f;
        isNan = true;
      } else if (v < 0.0f) {
        v = 0.0f;
        isNegative = true;
      } else if (std::isinf(v)) {
        v = kMaxRadiance;
        isInf = true;
      } else if (v > kMaxRadiance) {
        v = kMaxRadiance;
        isBright = true;
      }
    }
    r.nan += isNan;
    r.infinite += isInf;
    r.negative += isNegative;
    r.tooBright += isBright;
    r.replaced += isNan || isInf || isNegative || isBright;
  }
  return r;
}

Result<std::string> radianceVerdict(const RadianceReport& r, const std::string& name) {
  if (r.replaced == 0) return std::string();
  std::string kinds;
  auto add = [&kinds](int64_t count, const char* what) {
    if (count == 0) return;
    if (!kinds.empty()) kinds += ", ";
    kinds += std::to_string(count) + " " + what;
  };
  add(r.nan, "NaN");
  add(r.infinite, "infinite");
  add(r.negative, "negative");
  add(r.tooBright, "above 65504");
  if (r.replaced == r.pixels) {
    return makeError(name +
                     ": no usable radiance: every pixel is NaN, infinite, negative or "
                     "above 65504 (" +
                     kinds + ")");
  }
  return name + ": replaced " + std::to_string(r.replaced) + " of " + std::to_string(r.pixels) +
         " pixels (" + kinds + "; NaN and negative by 0, the rest by 65504)";
}

Cubemap::Cubemap(int faceEdge, int mipCount) : size(faceEdge) {
  mips.resize(static_cast<size_t>(std::max(mipCount, 0)));
  for (int m = 0; m < mipCount; ++m) {
    for (Image& f : mips[m]) f = Image(faceSize(m), faceSize(m), 3);
  }
}

glm::vec3 sampleCubemap(const Cubemap& cube, int mip, const glm::vec3& direction) {
  const CubeCoord c = cubeCoord(direction);
  const Image& face = cube.face(mip, c.face);
  const int n = face.width;
  const float x = c.s * static_cast<float>(n) - 0.5f;
  const float y = c.t * static_cast<float>(n) - 0.5f;
  const int x0 = std::clamp(static_cast<int>(std::floor(x)), 0, n - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(y)), 0, n - 1);
  const int x1 = std::min(x0 + 1, n - 1);
  const int y1 = std::min(y0 + 1, n - 1);
  const float fx = std::clamp(x - static_cast<float>(x0), 0.0f, 1.0f);
  const float fy = std::clamp(y - static_cast<float>(y0), 0.0f, 1.0f);
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const float top = face.pixel(x0, y0)[k] + (face.pixel(x1, y0)[k] - face.pixel(x0, y0)[k]) * fx;
    const float bottom =
        face.pixel(x0, y1)[k] + (face.pixel(x1, y1)[k] - face.pixel(x0, y1)[k]) * fx;
    out[k] = top + (bottom - top) * fy;
  }
  return out;
}

Result<Cubemap> panoramaToCubemap(const Image& panorama, int faceSize, int threads) {
  if (panorama.width != 2 * panorama.height || panorama.height < 1) {
    return makeError("expected a 2:1 equirectangular panorama, got " +
                     std::to_string(panorama.width) + "x" + std::to_string(panorama.height));
  }
  if (panorama.channels < 1 || panorama.channels > 4 ||
      panorama.pixels.size() !=
          static_cast<size_t>(panorama.width) * panorama.height * panorama.channels) {
    return makeError("invalid panorama image");
  }
  if (!isPowerOfTwo(faceSize) || faceSize > 16384) {
    return makeError("face size must be a power of two between 1 and 16384, got " +
                     std::to_string(faceSize));
  }
  // Largest texel-to-panorama size ratio (at face centres) bounds the pyramid depth.
  const float panoramaTexel = kPi / static_cast<float>(panorama.height);
  const float maxRatio = (2.0f / static_cast<float>(faceSize)) / panoramaTexel;
  const int levels = 2 + static_cast<int>(std::max(0.0f, std::ceil(std::log2(maxRatio))));
  const std::vector<PanoramaLevel> pyramid = buildPanoramaPyramid(panorama, levels);

  Cubemap cube(faceSize, 1);
  const float inv = 1.0f / static_cast<float>(faceSize);
  parallelFor(kFaceCount * faceSize, threads, [&](int row) {
    const int face = row / faceSize;
    const int y = row % faceSize;
    Image& out = cube.face(0, face);
    for (int x = 0; x < faceSize; ++x) {
      const glm::vec3 d = texelDirection(face, x, y, faceSize);
      const float ma = std::max(std::fabs(d.x), std::max(std::fabs(d.y), std::fabs(d.z)));
      // Angular edge of this texel: sqrt of its solid angle (2/N)^2 ma^3.
      const float ratio = 2.0f * inv * ma * std::sqrt(ma) / panoramaTexel;
      glm::vec3 value;
      if (ratio <= 1.0f) {
        value = samplePanorama(pyramid, d, 0.0f);
      } else {
        // Four sub-texel samples, each covering a quarter of the texel.
        const float lod = std::log2(ratio) - 1.0f;
        value = glm::vec3(0.0f);
        for (int k = 0; k < 4; ++k) {
          const float s = (static_cast<float>(x) + 0.25f + 0.5f * static_cast<float>(k & 1)) * inv;
          const float t = (static_cast<float>(y) + 0.25f + 0.5f * static_cast<float>(k >> 1)) * inv;
          value += samplePanorama(pyramid, cubeDirection(face, s, t), lod);
        }
        value *= 0.25f;
      }
      float* p = out.pixel(x, y);
      p[0] = value.x;
      p[1] = value.y;
      p[2] = value.z;
    }
  });
  return cube;
}

Image cubemapToPanorama(const Cubemap& cube, int mip, int width, int threads) {
  PN_CHECK(mip >= 0 && mip < cube.mipCount(), "mip out of range");
  PN_CHECK(width >= 2, "panorama width must be at least 2");
  const int height = width / 2;
  Image out(width, height, 3);
  parallelFor(height, threads, [&](int y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec3 d = panoramaDirection((static_cast<float>(x) + 0.5f) / width,
                                            (static_cast<float>(y) + 0.5f) / height);
      const glm::vec3 v = sampleCubemap(cube, mip, d);
      float* p = out.pixel(x, y);
      p[0] = v.x;
      p[1] = v.y;
      p[2] = v.z;
    }
  });
  return out;
}

}  // namespace penumbra::ibl
