// The browser's KTX2 transcoder behind ktx2_backend.h: Binomial's Basis Universal transcoder
// (three.js's copy on npm), loaded by web/lib/decoders.mjs and set as
// Module.penumbraDecoders.basis before the load runs; the calls are synchronous. The target is
// the first block format the WebGL2 context samples (ASTC 4x4, BC7, ETC2 RGBA: UASTC maps to
// ASTC losslessly) with every level the file has, else RGBA8 level 0 (the renderer makes the
// mipmaps then).
#include <emscripten/emscripten.h>

#include "scene/ktx2_backend.h"

// clang-format off
EM_JS(int, pn_basis_loaded, (), {
  const d = Module["penumbraDecoders"];
  return d && d["basis"] ? 1 : 0;
});

// Transcodes into buffers kept on Module until pn_ktx2_take copies them. Returns the number of
// levels (info: width, height, GL format or 0 for RGBA8, levels), or 0 with a reason in err.
EM_JS(int, pn_ktx2_open, (const uint8_t* src, double len, double maxPixels, int maxSize,
                          int* info, char* err, int cap), {
  const basis = Module["penumbraDecoders"]["basis"];
  let file = null;
  try {
    file = new basis.KTX2File(HEAPU8.slice(src >>> 0, (src >>> 0) + len));
    if (!file.isValid()) throw new Error("not a valid KTX2 file");
    const w = file.getWidth(), h = file.getHeight();
    if (w < 1 || h < 1 || w * h > maxPixels) throw new Error(`a ${w}x${h} image is too large`);
    if (!file.startTranscoding()) throw new Error("the transcoder cannot start on this file");
    // basisu transcoder_texture_format: cTFETC2_RGBA 1, cTFBC7_RGBA 6, cTFASTC_4x4_RGBA 10,
    // cTFRGBA32 13.
    let target = 13, glFormat = 0;
    const gl = typeof GLctx !== "undefined" ? GLctx : null;
    if (gl && w % 4 === 0 && h % 4 === 0 && w <= maxSize && h <= maxSize) {
      if (gl.getExtension("WEBGL_compressed_texture_astc")) [target, glFormat] = [10, 0x93B0];
      else if (gl.getExtension("EXT_texture_compression_bptc")) [target, glFormat] = [6, 0x8E8C];
      else if (gl.getExtension("WEBGL_compressed_texture_etc")) [target, glFormat] = [1, 0x9278];
    }
    const levels = glFormat ? Math.max(1, file.getLevels()) : 1;
    const out = [];
    for (let level = 0; level < levels; ++level) {
      const size = file.getImageTranscodedSizeInBytes(level, 0, 0, target);
      const buf = new Uint8Array(size);
      if (!file.transcodeImage(buf, level, 0, 0, target, 0, -1, -1)) {
        throw new Error(`transcoding level ${level} failed`);
      }
      out.push(buf);
    }
    HEAP32[(info >>> 2)] = w;
    HEAP32[(info >>> 2) + 1] = h;
    HEAP32[(info >>> 2) + 2] = glFormat;
    HEAP32[(info >>> 2) + 3] = levels;
    Module["penumbraKtx2"] = out;
    const name = { 0: "RGBA8", 0x93B0: "ASTC 4x4", 0x8E8C: "BC7", 0x9278: "ETC2 RGBA" }[glFormat];
    console.debug(`[penumbra] KTX2 ${w}x${h}: ${name}, ${levels} level(s)`);
    return levels;
  } catch (e) {
    stringToUTF8(String(e && e.message ? e.message : e).split("\n")[0], err, cap);
    return 0;
  } finally {
    if (file) {
      file.close();
      file.delete();
    }
  }
});

EM_JS(double, pn_ktx2_size, (int level), { return Module["penumbraKtx2"][level].length; });

EM_JS(void, pn_ktx2_take, (int level, uint8_t* out), {
  HEAPU8.set(Module["penumbraKtx2"][level], out >>> 0);
});

EM_JS(void, pn_ktx2_drop, (), { Module["penumbraKtx2"] = null; });
// clang-format on

namespace penumbra::gltf::backend {

bool ktx2Available() {
  return pn_basis_loaded() != 0;
}

std::string ktx2Transcode(std::span<const uint8_t> src, uint64_t maxPixels, int maxSize,
                          bool blocks, ImageData& out) {
  char err[256] = {0};
  int info[4] = {0, 0, 0, 0};
  const int levels =
      pn_ktx2_open(src.data(), static_cast<double>(src.size()), static_cast<double>(maxPixels),
                   blocks ? maxSize : 0, info, err, sizeof err);
  if (levels <= 0) return err[0] ? err : "transcoding failed";
  out.width = info[0];
  out.height = info[1];
  out.compressedFormat = static_cast<uint32_t>(info[2]);
  std::string problem;
  for (int level = 0; level < levels && problem.empty(); ++level) {
    const double size = pn_ktx2_size(level);
    if (out.compressedFormat == 0 && size != 4.0 * out.width * out.height) {
      problem = "the transcoder returned an unexpected size";
      break;
    }
    std::vector<uint8_t> bytes(static_cast<size_t>(size));
    pn_ktx2_take(level, bytes.data());
    if (out.compressedFormat == 0) {
      out.pixels = std::move(bytes);
    } else {
      out.compressedLevels.push_back(std::move(bytes));
    }
  }
  pn_ktx2_drop();
  return problem;
}

}  // namespace penumbra::gltf::backend
