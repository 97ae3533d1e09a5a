// Decoders for compressed glTF meshes (KHR_draco_mesh_compression, EXT_meshopt_compression)
// and textures (KHR_texture_basisu: KTX2), loaded only when a scene's glTF names one of the
// extensions, so the core module stays small; and meshoptimizer's simplifier, for a glTF with
// a primitive large enough for a capture stand-in (renderer/src/scene/mesh_lod.h). The
// simplifier is optional: if it cannot load, the scene loads and its meshes are captured whole.
// They are the decoders their authors publish on npm, copied by tools/build-web from
// web/node_modules (pinned by web/package-lock.json) into lib/decoders/ next to this file:
//   meshopt_decoder.mjs, meshopt_simplifier.mjs           meshoptimizer (ES modules)
//   draco_decoder_gltf_nodejs.js + draco_decoder_gltf.wasm  Google's Draco glTF decoder
//                                  (draco3dgltf; an Emscripten UMD script that also runs in a page)
//   basis_transcoder.js + .wasm    Binomial's Basis Universal transcoder, as three.js ships it
//                                  (three/examples/jsm/libs/basis; a UMD script defining BASIS)
// The wasm loader calls them synchronously from C++ (renderer/src/scene/mesh_decode_web.cpp)
// through Module.penumbraDecoders, where the native build calls libdraco and meshoptimizer: the
// checks, conversions and error messages around the decoding are the same C++ in both builds.
// KTX2 images are transcoded to RGBA8 (renderer/src/scene/ktx2_web.cpp); the native build has
// no transcoder and takes a texture's fallback image.
import { PenumbraError } from './staging.mjs';

export const DRACO = 'KHR_draco_mesh_compression';
export const MESHOPT = 'EXT_meshopt_compression';
export const BASISU = 'KHR_texture_basisu';
const BASE = new URL('./decoders/', import.meta.url);
const text = new TextDecoder();

let draco = null;    // promise of the Draco decoder module, once asked for
let basis = null;    // promise of the Basis Universal transcoder module, once asked for

// renderer/src/scene/mesh_lod.h kCaptureLodMinTriangles: a primitive with fewer triangles is
// never simplified, so a file without a primitive of that many indices (or vertices, when it
// has no indices) needs no simplifier.
const CAPTURE_LOD_MIN_INDICES = 3 * 1024;

function hasLargePrimitive(json) {
  try {
    const gltf = JSON.parse(json);
    const accessors = Array.isArray(gltf.accessors) ? gltf.accessors : [];
    const count = (i) => Number(accessors[i]?.count) || 0;
    return (Array.isArray(gltf.meshes) ? gltf.meshes : []).some((m) =>
      (Array.isArray(m?.primitives) ? m.primitives : []).some((p) =>
        (p?.indices !== undefined ? count(p.indices) : count(p?.attributes?.POSITION)) >=
          CAPTURE_LOD_MIN_INDICES));
  } catch {
    return false;  // the loader reports malformed JSON itself
  }
}

// The glTF JSON of a staged file: a .glb's first (JSON) chunk, or a .gltf's text; '' otherwise.
function gltfJsonText(bytes) {
  if (bytes.length >= 20 && bytes[0] === 0x67 && bytes[1] === 0x6c && bytes[2] === 0x54 &&
      bytes[3] === 0x46) {
    const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
    const length = view.getUint32(12, true);
    return view.getUint32(16, true) === 0x4e4f534a && 20 + length <= bytes.length
      ? text.decode(bytes.subarray(20, 20 + length)) : '';
  }
  let i = 0;
  while (i < bytes.length && i < 64 && bytes[i] <= 0x20) i++;
  return bytes[i] === 0x7b ? text.decode(bytes) : '';  // '{': a .gltf or a scene file
}

// Which decoders the staged files need: those whose extension a glTF's JSON names (in
// extensionsUsed/Required or on a primitive or buffer view).
export function neededDecoders(files) {
  const need = { draco: false, meshopt: false, basis: false, simplifier: false };
  for (const f of files) {
    if (!/\.(glb|gltf)$/i.test(f.path)) continue;
    const json = gltfJsonText(f.bytes);
    need.draco ||= json.includes(DRACO);
    need.meshopt ||= json.includes(MESHOPT);
    need.basis ||= json.includes(BASISU);
    need.simplifier ||= hasLargePrimitive(json);
  }
  return need;
}

const why = (e) => String(e && e.message ? e.message : e).split('\n')[0];

// meshoptimizer's ES modules (decoder, simplifier): the export `name` once its `ready` resolves,
// loaded at most once per page (a failed load may be tried again).
const meshoptModules = new Map();
function loadMeshoptModule(file, name, what) {
  const url = new URL(file, BASE).href;
  if (!meshoptModules.has(file)) {
    meshoptModules.set(file, import(url).then(async (m) => {
      await m[name].ready;
      return m[name];
    }).catch((e) => {
      meshoptModules.delete(file);
      throw new PenumbraError(`cannot load the ${what} (${url}): ${why(e)}`);
    }));
  }
  return meshoptModules.get(file);
}
const loadMeshopt = () => loadMeshoptModule('meshopt_decoder.mjs', 'MeshoptDecoder',
                                            'meshopt decoder');
const loadSimplifier = () => loadMeshoptModule('meshopt_simplifier.mjs', 'MeshoptSimplifier',
                                               'meshopt simplifier');

// A classic script that defines a global factory (Emscripten's UMD output), added once.
function loadScript(url, global) {
  return new Promise((resolve, reject) => {
    if (typeof globalThis[global] === 'function') {
      resolve();
      return;
    }
    const script = document.createElement('script');
    script.src = url;
    script.onload = () => resolve();
    script.onerror = () => reject(new Error('the script did not load'));
    document.head.appendChild(script);
  }).then(() => {
    if (typeof globalThis[global] !== 'function') {
      throw new Error(`the script defines no ${global}`);
    }
    return globalThis[global];
  });
}

function loadDraco() {
  const url = new URL('draco_decoder_gltf_nodejs.js', BASE).href;
  draco ||= loadScript(url, 'DracoDecoderModule').then((factory) => new Promise((resolve, reject) => {
    factory({
      locateFile: (f) => new URL(f, BASE).href,
      onAbort: (what) => reject(new Error(`aborted: ${what}`)),
      print: () => {},
      printErr: (t) => console.warn(`[penumbra] draco: ${t}`),
    }).then(resolve, reject);
  })).catch((e) => {
    draco = null;
    throw new PenumbraError(`cannot load the Draco decoder (${url}): ${why(e)}`);
  });
  return draco;
}

function loadBasis() {
  const url = new URL('basis_transcoder.js', BASE).href;
  basis ||= loadScript(url, 'BASIS').then((factory) => factory({
    locateFile: (f) => new URL(f, BASE).href,
    print: () => {},
    printErr: (t) => console.warn(`[penumbra] basis: ${t}`),
  })).then((module) => {
    module.initializeBasis();
    return module;
  }).catch((e) => {
    basis = null;
    throw new PenumbraError(`cannot load the KTX2 transcoder (${url}): ${why(e)}`);
  });
  return basis;
}

// Loads the decoders the staged files need (each at most once per page) and hands them to the
// wasm module, before its synchronous load runs. Rejects with a one-line PenumbraError (not
// for the simplifier, which is optional).
export async function provideDecoders(mod, files) {
  const need = neededDecoders(files);
  if (!need.draco && !need.meshopt && !need.basis && !need.simplifier) return;
  const [m, d, b, s] = await Promise.all([need.meshopt ? loadMeshopt() : null,
                                          need.draco ? loadDraco() : null,
                                          need.basis ? loadBasis() : null,
                                          need.simplifier ? loadSimplifier().catch((e) => {
                                            console.warn(`[penumbra] ${why(e)}: meshes are ` +
                                                         'captured whole');
                                            return null;
                                          }) : null]);
  mod.penumbraDecoders = { ...mod.penumbraDecoders };
  if (m) mod.penumbraDecoders.meshopt = m;
  if (d) mod.penumbraDecoders.draco = d;
  if (b) mod.penumbraDecoders.basis = b;
  if (s) mod.penumbraDecoders.simplifier = s;
}
