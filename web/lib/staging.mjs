// Gathering a scene's files for the wasm viewer: the main file (scene .json, .gltf or .glb)
// plus every file it references (a scene file's glTF and environment, a .gltf's external
// buffers and images), from URLs or from a set of dropped files. The result is a list of
// {path, bytes} relative to a staging folder; penumbra.mjs writes them into the module's
// in-memory file system, where the C++ loaders resolve references exactly as natively.

export class PenumbraError extends Error {
  constructor(message) {
    super(message);
    this.name = 'PenumbraError';
  }
}

const decoder = new TextDecoder();

// Bytes of any accepted source: ArrayBuffer, a typed array or DataView, a Blob/File.
export async function toBytes(source) {
  if (source instanceof Uint8Array) return source;
  if (source instanceof ArrayBuffer) return new Uint8Array(source);
  if (ArrayBuffer.isView(source)) {
    return new Uint8Array(source.buffer, source.byteOffset, source.byteLength);
  }
  if (typeof Blob !== 'undefined' && source instanceof Blob) {
    return new Uint8Array(await source.arrayBuffer());
  }
  throw new PenumbraError('expected a URL, an ArrayBuffer, a typed array or a Blob');
}

// `onBytes(received, total)`, when given, follows the download (total: the Content-Length, 0
// when the server does not say).
export async function fetchBytes(url, onBytes = null) {
  let response;
  try {
    response = await fetch(url);
  } catch (e) {
    throw new PenumbraError(fetchFailure(url, e));
  }
  if (!response.ok) {
    throw new PenumbraError(`cannot fetch ${url}: HTTP ${response.status} ${response.statusText}`.trim());
  }
  if (!onBytes || !response.body?.getReader) return new Uint8Array(await response.arrayBuffer());
  const total = Number(response.headers.get('content-length')) || 0;
  const reader = response.body.getReader();
  const chunks = [];
  let received = 0;
  onBytes(0, total);
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    chunks.push(value);
    received += value.length;
    onBytes(received, total);
  }
  const bytes = new Uint8Array(received);
  let at = 0;
  for (const c of chunks) { bytes.set(c, at); at += c.length; }
  return bytes;
}

// A scene's download as model-viewer reports it (its 'progress' event's totalProgress): the
// bytes received over those expected of every file fetched so far, never going back, below 1
// until the scene is loaded (the caller reports 1 then). file(url) gives fetchBytes' onBytes.
export class DownloadProgress {
  #files = new Map(); #last = 0; #report;
  constructor(report) { this.#report = report; }
  file(url) {
    return (received, total) => {
      this.#files.set(url, [received, Math.max(received, total)]);
      let got = 0, expected = 0;
      for (const [r, t] of this.#files.values()) { got += r; expected += t; }
      const p = expected > 0 ? Math.min(0.99, got / expected) : 0;
      if (p > this.#last) { this.#last = p; this.#report(p); }
    };
  }
}

// Why a fetch rejected, in words. The browser says only "Failed to fetch" both for a network
// failure and for a file of another site whose server does not allow this page (CORS; the real
// reason is shown only in the developer tools), so for another site both are named, with the fix.
export function fetchFailure(url, error) {
  const why = error && error.message ? error.message : String(error);
  let origin = null;
  try {
    const target = new URL(url, globalThis.location?.href);
    if (globalThis.location && target.origin !== globalThis.location.origin) origin = target.origin;
  } catch {}  // not a URL: the browser's message says so
  if (!origin) return `cannot fetch ${url}: ${why}`;
  return `cannot fetch ${url}: ${origin} is another site than this page, and its server did ` +
         `not allow this page to read it (CORS: it must send Access-Control-Allow-Origin), or ` +
         `the network failed; serve the file from this page's site or allow it there (${why})`;
}

// 'glb', 'gltf', 'scene' (a Penumbra scene file) or 'unknown', by content: dropped files and
// URLs do not always carry a trustworthy extension.
export function sniffScene(bytes) {
  if (bytes.length >= 4 && bytes[0] === 0x67 && bytes[1] === 0x6c && bytes[2] === 0x54 &&
      bytes[3] === 0x46) {
    return { kind: 'glb' };
  }
  let i = 0;
  while (i < bytes.length && i < 64 && (bytes[i] <= 0x20 || bytes[i] === 0xef || bytes[i] === 0xbb ||
                                        bytes[i] === 0xbf)) i++;
  if (bytes[i] !== 0x7b) return { kind: 'unknown' };  // '{'
  let json;
  try {
    json = JSON.parse(decoder.decode(bytes));
  } catch {
    return { kind: 'unknown' };  // malformed: the C++ loader words the error
  }
  if (json && typeof json.gltf === 'string' && !json.asset) return { kind: 'scene', json };
  return { kind: 'gltf', json };
}

// Relative references of a glTF document (buffers and images that are not data: URIs).
function gltfReferences(json) {
  const refs = [];
  for (const list of [json && json.buffers, json && json.images]) {
    if (!Array.isArray(list)) continue;
    for (const item of list) {
      if (item && typeof item.uri === 'string' && !item.uri.startsWith('data:')) refs.push(item.uri);
    }
  }
  return refs;
}

function sceneFileReferences(json) {
  const refs = [];
  const env = json.environment;
  if (typeof env === 'string') refs.push(env);
  else if (env && typeof env.file === 'string' && env.file) refs.push(env.file);
  return refs;
}

// Joins a relative path onto a folder ('a/b' + '../c.bin' = 'a/c.bin'); null when it climbs
// above the staging root or is absolute (those are left for the loader to report as missing).
export function joinPath(dir, rel) {
  if (/^[a-z][a-z0-9+.-]*:/i.test(rel) || rel.startsWith('/')) return null;
  const parts = dir ? dir.split('/') : [];
  for (const part of rel.split('/')) {
    if (part === '' || part === '.') continue;
    if (part === '..') {
      if (!parts.length) return null;
      parts.pop();
    } else {
      parts.push(part);
    }
  }
  return parts.join('/');
}

const dirname = (p) => (p.includes('/') ? p.slice(0, p.lastIndexOf('/')) : '');
const basename = (p) => p.slice(p.lastIndexOf('/') + 1);
const decodePath = (p) => { try { return decodeURIComponent(p); } catch { return p; } };

// How deep the main file sits in the staging folder: references may climb this many levels
// ('../env/studio_sky.hdr' from a scene file) and still land inside it.
const DEPTH = ['s1', 's2', 's3', 's4'];

// Collects the files of a scene. `main` is {bytes, name, url?}; `resources` maps file names
// (as referenced, or their base names) to byte sources, for dropped file sets; `progress` (a
// DownloadProgress) follows the files fetched. Returns {mainPath, files: [{path, bytes}], kind}.
export async function gatherScene(main, resources = {}, progress = null) {
  const files = [];
  const seen = new Set();
  const lookup = async (relPath, url) => {
    if (url) return fetchBytes(url, progress?.file(url));
    const key = [relPath, basename(relPath), decodePath(relPath), basename(decodePath(relPath))]
      .find((k) => k in resources);
    if (key === undefined) {
      throw new PenumbraError(`'${relPath}' is referenced but was not provided (drop it together ` +
                              'with the file that references it, or load from a URL)');
    }
    return toBytes(resources[key]);
  };
  // Adds a referenced file, and its own references when it is a .gltf.
  const addReference = async (fromDir, fromUrl, ref, isGltf) => {
    const path = joinPath(fromDir, decodePath(ref));
    if (path === null || seen.has(path)) return;
    seen.add(path);
    const url = fromUrl ? new URL(ref, fromUrl).href : null;
    const bytes = await lookup(ref, url);
    files.push({ path, bytes });
    if (isGltf) {
      const sniffed = sniffScene(bytes);
      if (sniffed.kind === 'gltf') {
        for (const r of gltfReferences(sniffed.json)) await addReference(dirname(path), url, r, false);
      }
    }
  };

  const sniffed = sniffScene(main.bytes);
  const ext = { glb: '.glb', gltf: '.gltf', scene: '.json' }[sniffed.kind];
  let name = basename(main.name || 'scene').replace(/[^\w.+-]/g, '_') || 'scene';
  if (ext && !name.toLowerCase().endsWith(ext)) name += ext;
  const dir = DEPTH.join('/');
  const mainPath = `${dir}/${name}`;
  files.push({ path: mainPath, bytes: main.bytes });
  seen.add(mainPath);
  if (sniffed.kind === 'gltf') {
    for (const r of gltfReferences(sniffed.json)) await addReference(dir, main.url, r, false);
  } else if (sniffed.kind === 'scene') {
    await addReference(dir, main.url, sniffed.json.gltf, true);
    for (const r of sceneFileReferences(sniffed.json)) await addReference(dir, main.url, r, false);
  }
  return { mainPath, files, kind: sniffed.kind };
}

// A display name for a source: the URL's last path segment, a File's name, or a fallback.
export function sourceName(source, fallback) {
  if (typeof source === 'string' || source instanceof URL) {
    const path = new URL(String(source), globalThis.location ? location.href : 'http://x/').pathname;
    return decodePath(basename(path)) || fallback;
  }
  if (source && typeof source.name === 'string' && source.name) return source.name;
  return fallback;
}

// The largest panorama setEnvironment takes (its pixel count is the limit). A bigger one is
// refused from its header, before its bytes reach the wasm heap: decoding 128 million pixels
// blocked the page for 20 s and ran out of memory. The wasm side applies the same limit
// (viewer_main.cpp kMaxPanoramaPixels).
export const MAX_PANORAMA = { width: 8192, height: 4096 };

// A Radiance (.hdr) file's size from its resolution line ("-Y H +X W") and whether it is a
// packed environment (penumbra-prefilter's PENUMBRA_ENV header key), or null when `bytes` are
// not one. Only the header is looked at.
export function radianceSize(bytes) {
  if (bytes.length < 2 || bytes[0] !== 0x23 || bytes[1] !== 0x3f) return null;  // "#?"
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, Math.min(bytes.length, 65536)));
  const m = /\n\n([-+]Y) (\d+) ([-+]X) (\d+)/.exec(head);
  if (!m) return null;
  const header = head.slice(0, m.index);
  return { width: Number(m[4]), height: Number(m[2]), packed: /\nPENUMBRA_ENV=/.test(header) };
}

// Panoramas of more pixels than this are decoded in steps between which the page runs.
export const STEPPED_PANORAMA_PIXELS = 1024 * 512;

// The one-line refusal of a panorama over MAX_PANORAMA's pixels, naming the file, or null.
export function panoramaTooLarge(bytes, name) {
  const size = radianceSize(bytes);
  const { width, height } = MAX_PANORAMA;
  if (!size || size.width * size.height <= width * height) return null;
  return `${name}: a ${size.width}x${size.height} panorama is more than the viewer's limit of ` +
         `${width}x${height} pixels; prefilter it with penumbra-prefilter (one small packed ` +
         'file) or downscale it';
}
