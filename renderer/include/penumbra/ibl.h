// Image-based lighting on the CPU, without GL: equirectangular panorama to cube map, the GGX
// split-sum specular prefilter (filtered importance sampling), diffuse irradiance as 9 spherical
// harmonics, and the DFG lookup table. The prefilter tool, the tests and the renderer's loader
// use it; docs/ibl.md states every convention below with its reasons.
//
// Conventions in brief:
//  - World frame: glTF's, +Y up, right-handed.
//  - Cube faces in the order +X, -X, +Y, -Y, +Z, -Z with the OpenGL cube-map orientation (the
//    major-axis / sc / tc table of the GL and GLES specifications). Face images have row 0 =
//    t = 0, so face i uploads as it is to GL_TEXTURE_CUBE_MAP_POSITIVE_X + i.
//  - Panorama: Blender's world-texture convention seen through the glTF importer (also
//    three.js's): the centre column looks along +X, u increasing turns toward +Z (u = 0.75 is
//    +Z, u = 0.25 is -Z, the left and right edges -X), the top row is +Y.
//  - Specular mip m of M has perceptual roughness r = m / (M - 1) and GGX alpha = r^2; mip 0 is
//    the unfiltered mirror level. Faces halve per mip down to PrefilterOptions::minFaceSize.
//  - SH: 9 coefficients of radiance L_lm; evaluateIrradiance() returns irradiance E(n), so a
//    constant environment L gives E = pi L and a Lambertian surface reflects albedo * E / pi.
//  - DFG LUT: x = n.v, y = perceptual roughness at texel centres; R = A, G = B of the split sum
//    (specular = prefiltered * (F0 A + B)), B = A + B = E_ss for multiple-scattering
//    compensation 1 + F0 (1 / E_ss - 1).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "penumbra/error.h"
#include "penumbra/image.h"

namespace penumbra::ibl {

inline constexpr int kFaceCount = 6;
enum CubeFace : int {
  kPositiveX = 0,
  kNegativeX = 1,
  kPositiveY = 2,
  kNegativeY = 3,
  kPositiveZ = 4,
  kNegativeZ = 5,
};
// "+X", "-X", ... for messages and manifests.
const char* faceName(int face);
// "px", "nx", "py", "ny", "pz", "nz" for file names.
const char* faceTag(int face);

// ---- Cube-map geometry (GL orientation) ------------------------------------------------------

// Unit direction through the point (s, t) in [0, 1]^2 of a face; t = 0 is the face image's
// first row. Values outside [0, 1] extend the face's plane (used for seam padding).
glm::vec3 cubeDirection(int face, float s, float t);
// Direction through the centre of texel (x, y) of a face `size` texels wide.
glm::vec3 texelDirection(int face, int x, int y, int size);

struct CubeCoord {
  int face = 0;
  float s = 0.0f;  // in [0, 1]
  float t = 0.0f;  // in [0, 1], 0 = first row
};
// Face and coordinates hit by a non-zero direction (GL's major-axis rule; ties go to X, then Y).
CubeCoord cubeCoord(const glm::vec3& direction);

// Exact solid angle of texel (x, y) on a face `size` texels wide; all texels sum to 4 pi.
double texelSolidAngle(int x, int y, int size);
// texelSolidAngle for every texel of a face, row-major: the same on all six faces, so loops
// over whole cube maps compute it once instead of once per face (it costs four atan2).
std::vector<double> texelSolidAngles(int size);

// ---- Equirectangular panorama (2:1) ------------------------------------------------------------

// Unit direction of panorama coordinates u, v in [0, 1] (v = 0 is the top row):
// phi = 2 pi (u - 1/2), elevation = pi (1/2 - v),
// direction = (cos(elev) cos(phi), sin(elev), cos(elev) sin(phi)).
glm::vec3 panoramaDirection(float u, float v);
// Inverse of panoramaDirection: u in [0, 1), v in [0, 1].
glm::vec2 panoramaCoord(const glm::vec3& direction);

// The largest radiance Penumbra keeps: the largest half float, since weak devices accumulate
// and sample in RGBA16F. Brighter values in a file are clamped to it (the sun of a real HDRI
// stays far below).
inline constexpr float kMaxRadiance = 65504.0f;

// What sanitizeRadiance found: pixels with at least one colour value of each kind.
struct RadianceReport {
  int64_t pixels = 0;
  int64_t nan = 0, infinite = 0, negative = 0, tooBright = 0;
  int64_t replaced = 0;  // pixels with any of them
};

// Replaces NaN and negative colour values with 0, infinite ones and values above kMaxRadiance
// with kMaxRadiance, in place, and counts them.
RadianceReport sanitizeRadiance(Image& image);
// The policy for radiance read from a file, in one place: an error when no pixel of `name` was
// usable as read (every one had a value replaced), otherwise a one-line warning that names the
// file and what was replaced, or "" when nothing was.
Result<std::string> radianceVerdict(const RadianceReport& report, const std::string& name);

// ---- Cube map --------------------------------------------------------------------------------

// Faces x mips of linear RGB radiance. mips[m][f] is a 3-channel Image of faceSize(m)^2.
struct Cubemap {
  int size = 0;  // face edge of mip 0
  std::vector<std::array<Image, kFaceCount>> mips;

  Cubemap() = default;
  // Allocates black faces for mips 0 .. mipCount - 1 (face size halves per mip, at least 1).
  Cubemap(int size, int mipCount);

  int mipCount() const { return static_cast<int>(mips.size()); }
  int faceSize(int mip) const { return size >> mip > 0 ? size >> mip : 1; }
  Image& face(int mip, int f) { return mips[mip][f]; }
  const Image& face(int mip, int f) const { return mips[mip][f]; }
};

// Bilinear lookup of one mip in a direction, clamped at face edges (not seamless: for previews
// and tests, not for filtering).
glm::vec3 sampleCubemap(const Cubemap& cube, int mip, const glm::vec3& direction);

// Resamples a 2:1 panorama (1 to 4 channels; grey is replicated, alpha ignored) to mip 0 of a
// cube map. Magnification is bilinear; minification is area-filtered (2x2 supersampling of
// each cube texel from a box-filtered panorama pyramid at the matching level, trilinear).
// Errors: not 2:1, faceSize not a power of two in [1, 16384].
// The thread count a request resolves to: 0 means std::thread::hardware_concurrency().
int resolveThreads(int requested);

Result<Cubemap> panoramaToCubemap(const Image& panorama, int faceSize, int threads = 0);
// An equirectangular view of one mip (bilinear), width x width/2, for previews.
Image cubemapToPanorama(const Cubemap& cube, int mip, int width, int threads = 0);

// ---- GGX specular prefilter (split sum, N = V = R) -------------------------------------------

inline constexpr int kDefaultFaceSize = 256;
inline constexpr int kDefaultSamples = 256;

// Options shared by every prefilter back end. Only prefilterCpu exists today; a GPU back end
// (prefilterGpu, in the GL library) is meant to take the same options and produce the same
// Cubemap layout, so callers switch by function, not by data.
// ---- The sun ----------------------------------------------------------------------------------

// A distant disk light taken out of a panorama (extractSun): the renderer draws it as a
// directional light whose shadow-map samples spread over the disk.
struct Sun {
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // unit vector towards the sun (glTF world frame)
  float angularRadius = 0.0f;             // radians
  glm::vec3 irradiance{0.0f};  // RGB at normal incidence: the removed excess radiance x omega
  float threshold = 0.0f;      // luminance the sun's pixels were clamped to
};

// Automatic extraction: a threshold of this many times the panorama's mean luminance; a sun
// must be at most this large and carry at least this share of the panorama's light (a
// softbox or a bright window stays in the environment).
inline constexpr double kSunAutoMeanMultiple = 20.0;
inline constexpr float kSunMaxAngularRadius = 0.1047f;  // 6 degrees
inline constexpr double kSunMinShare = 0.05;

// The environment without its sun as a distribution of directions for sky shadows: each
// frame the renderer draws one direction with probability proportional to its luminance,
// renders a directional shadow map for it and subtracts the light that direction's shadow
// takes from the diffuse environment term (an unbiased estimate of the sky's shadow). Built
// from mip 0 of the cube map, box-filtered to `resolution` texels per face edge. With
// `upperOnly`, only texels whose centre is above the horizon (+Y) take part: each sample
// subtracts up to the whole distribution's luminance times n.l, which for a surface facing
// the dark ground below would be many times the light it receives (dark speckles that take
// hundreds of frames to average out); the sky above is what casts the shadows one sees.
struct SkySample {
  glm::vec3 direction{0.0f, 1.0f, 0.0f};  // unit, towards the sky (environment frame)
  glm::vec3 radiance{0.0f};               // RGB of the texel it was drawn from
  float pdf = 0.0f;                       // per unit solid angle
};
class SkyDistribution {
 public:
  SkyDistribution() = default;
  static SkyDistribution build(const Cubemap& cube, int resolution = 16, bool upperOnly = false);
  bool empty() const { return total_ <= 0.0; }
  // Maps u in [0, 1)^2 to a direction: a texel by its share of the luminance, then a uniform
  // point on it (the texel's residual of u.x and u.y).
  SkySample sample(glm::vec2 u) const;
  // pdf of a direction (per unit solid angle), for tests.
  float pdf(const glm::vec3& direction) const;
  int resolution() const { return resolution_; }

 private:
  int resolution_ = 0;
  std::vector<glm::vec3> radiance_;  // per texel, face-major then row-major
  std::vector<double> cdf_;          // running sum of luminance x solid angle
  std::vector<float> solidAngle_;
  double total_ = 0.0;
};

struct SunOptions {
  // Luminance above which the region around the brightest pixel becomes the sun. Negative:
  // automatic (the rules above); 0: no extraction; positive: this threshold, no size or share
  // limits.
  float threshold = -1.0f;
};

// Finds the connected region above the threshold around the panorama's brightest pixel,
// clamps its pixels to the threshold (hue kept) and returns their excess as a Sun: energy
// conserved exactly, direction the energy-weighted centroid, radius from the energy-weighted
// spread (sqrt(2 mean angle^2), exact for a uniform disk). nullopt: no sun (the panorama is
// untouched).
std::optional<Sun> extractSun(Image& panorama, const SunOptions& options = {});

struct PrefilterOptions {
  int faceSize = kDefaultFaceSize;  // mip-0 face edge; a power of two
  // GGX samples per texel (a Fibonacci lattice) for mip 1 when it is importance sampled;
  // mip m uses samples * 2^(m-1) (at most 16x), see importanceSamplesForMip.
  int samples = kDefaultSamples;
  int minFaceSize = 4;  // smallest mip's face edge (power of two, <= faceSize)
  // A mip is convolved directly (every texel of a suitably box-filtered source level, exact)
  // when that takes at most this many (output texel, source texel) pairs; otherwise it is
  // importance sampled. 0 importance-samples every mip. The default makes the rough, small
  // mips direct (from 32-pixel faces down with 256-pixel input) at a few tens of ms.
  int64_t directBudget = int64_t{64} << 20;
  int threads = 0;  // 0: all hardware threads; results do not depend on it
  // Sun extraction before filtering (prefilterCpu / prefilterGpu): SunOptions::threshold.
  float sunThreshold = -1.0f;
  // Called with the completed fraction in [0, 1], from worker threads but never concurrently.
  std::function<void(float)> progress;
};

// Mip count for a chain from faceSize down to minFaceSize: log2(faceSize / minFaceSize) + 1.
int mipCountFor(int faceSize, int minFaceSize);
// Samples per texel that an importance-sampled mip m >= 1 uses: samples * 2^min(m - 1, 4).
int importanceSamplesForMip(int samples, int mip);
// Perceptual roughness of mip m of mipCount: m / (mipCount - 1) (0 when mipCount == 1).
float roughnessForMip(int mip, int mipCount);

// Prefilters mip 0 of `source` into a full chain of the same face size (options.faceSize is
// ignored; source.size must be a power of two >= options.minFaceSize). Mip 0 is copied
// unfiltered; mip m >= 1 holds, per texel direction n,
//   integral L(l) D(h) (n.l)+ dl / integral D(h) (n.l)+ dl,  h = normalize(n + l),
// the split sum's prefiltered radiance with N = V = R. Sharp mips estimate it with GGX
// samples read from a filtered source pyramid at the level given by each sample's density and
// the local texel solid angle (filtered importance sampling, Krivanek & Colbert 2008), plus an
// exact sum over the few brightest texels' excess (a sun); rough mips within
// options.directBudget sum over every texel of a coarser source level. See docs/ibl.md.
Result<Cubemap> prefilterCubemapCpu(const Cubemap& source, const PrefilterOptions& options);

// 9 real SH coefficients (bands 0..2) of radiance, RGB each, in the order
// Y00, Y1-1, Y10, Y11, Y2-2, Y2-1, Y20, Y21, Y22 with the basis of shBasis (and
// docs/environment-format.md section 5).
struct ShCoefficients {
  std::array<glm::vec3, 9> c{};
};

// Everything the renderer needs from an environment apart from the DFG LUT.
struct PrefilteredEnvironment {
  Cubemap specular;              // mips as above
  std::vector<float> roughness;  // perceptual roughness per mip
  ShCoefficients sh;             // radiance SH of the environment
  int samples = 0;               // samples per texel used for mips >= 1
  std::optional<Sun> sun;        // taken out of the panorama before filtering, if any
  std::string generator;         // "penumbra-prefilter 0.1.0" or the like
};

// The whole CPU pipeline: sanitised panorama -> cube (mip 0) -> prefiltered mips, and SH.
// The panorama must be free of NaN/Inf/negative/too bright values (see sanitizeRadiance).
Result<PrefilteredEnvironment> prefilterCpu(const Image& panorama, const PrefilterOptions& options);

// ---- Spherical harmonics ---------------------------------------------------------------------

// The 9 basis functions at a unit direction (glTF world frame, x, y, z as they are).
std::array<float, 9> shBasis(const glm::vec3& n);
// Projects one mip of a cube map with exact texel solid angles.
ShCoefficients projectSh(const Cubemap& cube, int mip = 0, int threads = 0);
// Irradiance E(n) = sum_l A_l sum_m L_lm Y_lm(n) with A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4.
glm::vec3 evaluateIrradiance(const ShCoefficients& sh, const glm::vec3& n);
// The band-limited radiance itself, sum L_lm Y_lm(n).
glm::vec3 evaluateShRadiance(const ShCoefficients& sh, const glm::vec3& n);
// {"convention": ..., "basis": [...], "coefficients": [[r, g, b] x 9]} on one line.
std::string shToJson(const ShCoefficients& sh);
// Writes shToJson(sh) and a newline to `path`, atomically.
Status writeShJson(const std::string& path, const ShCoefficients& sh);

// ---- DFG lookup table ------------------------------------------------------------------------

struct BrdfLutOptions {
  int size = 128;     // width = height
  int samples = 512;  // VNDF samples per texel
  int threads = 0;
};
// (A, B, A + B) for one n.v and perceptual roughness: A = integral (1 - Fc) f cos / F,
// B = integral Fc f cos / F, Fc = (1 - v.h)^5, with height-correlated Smith GGX.
glm::vec3 integrateDfg(float nDotV, float perceptualRoughness, int samples);
// size x size, 3 channels; texel (i, j) (j = row from the top) holds
// integrateDfg((i + 1/2) / size, (j + 1/2) / size).
Image computeBrdfLut(const BrdfLutOptions& options = {});

// ---- Sheen (KHR_materials_sheen) -------------------------------------------------------------
// The Charlie distribution with Estevez & Kulla's visibility, as glTF defines the sheen lobe;
// the shaders evaluate the same functions (glsl/chunks/brdf.glsl).

// Perceptual sheen roughness -> alpha, with the floor the shaders use (sin^(1/alpha) overflows
// below it and the lobe degenerates to a line at grazing angles).
float sheenAlpha(float perceptualRoughness);
// D(h) = (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi).
float sheenD(float nDotH, float alpha);
// Estevez & Kulla's visibility 1 / ((1 + Lambda(v) + Lambda(l)) 4 n.v n.l), clamped to [0, 1].
float sheenV(float nDotV, float nDotL, float alpha);
// Directional albedo E(n.v) = integral of D V n.l over the hemisphere (sheen colour 1), from
// `samples` cosine-distributed directions, limited to 1: the model reflects a little more than
// it receives at extreme grazing angles and low roughness, and glTF's albedo scaling of the
// base, 1 - max(sheenColor) E, needs E <= 1 to stay physical.
float integrateSheenAlbedo(float nDotV, float perceptualRoughness, int samples);
// size x size, 1 channel, laid out as computeBrdfLut (x = n.v, y = sheen roughness).
Image computeSheenLut(int size, int samples, int threads = 0);

}  // namespace penumbra::ibl
