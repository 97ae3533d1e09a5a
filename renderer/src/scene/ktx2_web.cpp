// The browser's KTX2 transcoder behind ktx2_backend.h: Binomial's Basis Universal transcoder
// (three.js's copy on npm), loaded by web/lib/decoders.mjs and set as
// Module.penumbraDecoders.basis before the load runs; the calls are synchronous.
#include <emscripten/emscripten.h>

#include "scene/ktx2_backend.h"

// clang-format off
EM_JS(int, pn_basis_loaded, (), {
  const d = Module["penumbraDecoders"];
  return d && d["basis"] ? 1 : 0;
});

// Transcodes into a buffer kept on Module until pn_ktx2_take copies it; returns its byte size
// (width and height into dims[0], dims[1]), or 0 with a one-line reason in err.
EM_JS(double, pn_ktx2_open, (const uint8_t* src, double len, double maxPixels, int* dims,
                             char* err, int cap), {
  const basis = Module["penumbraDecoders"]["basis"];
  let file = null;
  try {
    file = new basis.KTX2File(HEAPU8.slice(src >>> 0, (src >>> 0) + len));
    if (!file.isValid()) throw new Error("not a valid KTX2 file");
    const w = file.getWidth(), h = file.getHeight();
    if (w < 1 || h < 1 || w * h > maxPixels) throw new Error(`a ${w}x${h} image is too large`);
    if (!file.startTranscoding()) throw new Error("the transcoder cannot start on this file");
    const RGBA32 = 13;  // basisu transcoder_texture_format::cTFRGBA32
    const size = file.getImageTranscodedSizeInBytes(0, 0, 0, RGBA32);
    const out = new Uint8Array(size);
    if (!file.transcodeImage(out, 0, 0, 0, RGBA32, 0, -1, -1)) throw new Error("transcoding failed");
    HEAP32[(dims >>> 2)] = w;
    HEAP32[(dims >>> 2) + 1] = h;
    Module["penumbraKtx2"] = out;
    return size;
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

EM_JS(void, pn_ktx2_drop, (), { Module["penumbraKtx2"] = null; });

EM_JS(void, pn_ktx2_take, (uint8_t* out), {
  HEAPU8.set(Module["penumbraKtx2"], out >>> 0);
  Module["penumbraKtx2"] = null;
});
// clang-format on

namespace penumbra::gltf::backend {

bool ktx2Available() {
  return pn_basis_loaded() != 0;
}

std::string ktx2Transcode(std::span<const uint8_t> src, uint64_t maxPixels, ImageData& out) {
  char err[256] = {0};
  int dims[2] = {0, 0};
  const double size = pn_ktx2_open(src.data(), static_cast<double>(src.size()),
                                   static_cast<double>(maxPixels), dims, err, sizeof err);
  if (size <= 0) return err[0] ? err : "transcoding failed";
  if (size != 4.0 * dims[0] * dims[1]) {
    pn_ktx2_drop();
    return "the transcoder returned an unexpected size";
  }
  out.width = dims[0];
  out.height = dims[1];
  out.pixels.assign(static_cast<size_t>(size), 0);
  pn_ktx2_take(out.pixels.data());
  return {};
}

}  // namespace penumbra::gltf::backend
