// The packed environment file: every face of every specular mip in ONE Radiance RGBE (.hdr)
// image (the paper's Figure 6), with a JSON manifest (face size, mips, roughness per mip, SH,
// conventions) embedded as the header line "PENUMBRA_ENV={...}" and also written beside it as
// <name>.json. One request loads the whole environment, natively or in wasm, without
// OpenImageIO; stb_image and other Radiance readers read it as an ordinary .hdr picture.
// docs/environment-format.md specifies it byte by byte.
//
// Layout: width = 6 * faceSize, faces left to right in the order +X, -X, +Y, -Y, +Z, -Z; mip m
// (face edge faceSize >> m) starts at row faceSize * (2 - 2^(1-m)) (mip 0 at row 0, mip 1
// below it, ...), face f of mip m at column f * (faceSize >> m). Unused texels are black.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "penumbra/error.h"
#include "penumbra/ibl.h"

namespace penumbra {

// What a packed file holds is exactly what the prefilter produces.
using PackedEnvironment = ibl::PrefilteredEnvironment;

inline constexpr const char* kPackedFormatName = "penumbra-packed-environment";
// Version 2 adds the optional "sun" (ibl::Sun); files without a sun are written as version 1.
inline constexpr int kPackedFormatVersion = 2;
inline constexpr const char* kPackedHeaderKey = "PENUMBRA_ENV";

// The manifest as one line of JSON (the value of the PENUMBRA_ENV header line).
Result<std::string> packedManifestJson(const PackedEnvironment& env);
// The whole file in memory. Deterministic: equal inputs give equal bytes.
Result<std::vector<uint8_t>> encodePackedEnvironment(const PackedEnvironment& env);
// Writes PATH (normally *.hdr) and the manifest, pretty-printed, as PATH with its extension
// replaced by .json. Both atomically.
Status writePackedEnvironment(const std::string& path, const PackedEnvironment& env);

// The same environment as a KTX 2.0 cube map for other engines (three.js's KTX2Loader, the glTF
// Sample Viewer): VK_FORMAT_R16G16B16A16_SFLOAT, every mip, faces +X -X +Y -Y +Z -Z with rows
// from t = 0 as GL uploads them, alpha 1, the manifest under kKtx2ManifestKey in the key/value
// data, KTXwriter the generator. Deterministic.
inline constexpr const char* kKtx2ManifestKey = "penumbra.environment";
Result<std::vector<uint8_t>> encodeKtx2Environment(const PackedEnvironment& env);
// Writes it atomically.
Status writeKtx2Environment(const std::string& path, const PackedEnvironment& env);

// Reads a packed file: validates the manifest against the image size and unpacks the faces.
Result<PackedEnvironment> readPackedEnvironment(const std::string& path);
Result<PackedEnvironment> readPackedEnvironmentFromMemory(std::span<const uint8_t> bytes,
                                                          const std::string& nameForErrors);

// Row where mip m starts in the packed image.
int packedMipRow(int faceSize, int mip);
// Height of the packed image: the sum of the face sizes of all mips.
int packedHeight(int faceSize, int mipCount);

}  // namespace penumbra
