#!/usr/bin/env node
// Compressed copies of the product scene for the web build's tests and demos, made with the
// encoders their authors publish on npm (web/node_modules, pinned by web/package-lock.json):
//   product_draco.glb    every primitive KHR_draco_mesh_compression (Edgebreaker, positions
//                        14 bits, normals 10, uvs 12), no uncompressed accessors at all
//   product_meshopt.glb  every buffer view EXT_meshopt_compression (vertex codec v0, which
//                        Debian's meshoptimizer 0.18 reads; TRIANGLES indices; normals as
//                        8-bit octahedral with KHR_mesh_quantization); the fallback buffer
//                        has no data
//   product_{draco,meshopt}.json  scene files as assets/product/product.json, for these files
//   glass_ktx2.gltf      the glass scene (assets/glass) with its lattice texture as a KTX2 file
//                        (lattice.ktx2: UASTC, Binomial's Basis Universal encoder as packaged by
//                        ktx2-encoder) under KHR_texture_basisu, with no PNG fallback
//   layers_ktx2.gltf     the layers scene (assets/layers) with all five of its textures, every
//                        one an extension texture, as KTX2 files (UASTC) likewise
// Every extension is in extensionsRequired: nothing renders without decoding it.
// tools/build-web runs it into web/dist/assets/compressed/ (the environment resolves to
// ../env/studio_sky.hdr there). Usage: node tools/assets/gen_compressed.mjs --out-dir DIR
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { inflateSync } from 'node:zlib';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const modules = join(root, 'web/node_modules');
const args = process.argv.slice(2);
const outIndex = args.indexOf('--out-dir');
if (outIndex < 0 || !args[outIndex + 1]) {
  console.error('usage: gen_compressed.mjs --out-dir DIR');
  process.exit(2);
}
const outDir = resolve(args[outIndex + 1]);

const draco3d = createRequire(import.meta.url)(join(modules, 'draco3dgltf/draco3dgltf.js'));
const { MeshoptEncoder } = await import(
  pathToFileURL(join(modules, 'meshoptimizer/meshopt_encoder.js')).href);
const { encodeToKTX2 } = await import(
  pathToFileURL(join(modules, 'ktx2-encoder/dist/node/index.js')).href);

const srcDir = join(root, 'assets/product');
const source = JSON.parse(readFileSync(join(srcDir, 'product.gltf'), 'utf8'));
const bin = readFileSync(join(srcDir, source.buffers[0].uri));
const SIZES = { 5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4 };
const COMPS = { SCALAR: 1, VEC2: 2, VEC3: 3, VEC4: 4 };
const ARRAYS = { 5123: Uint16Array, 5125: Uint32Array, 5126: Float32Array };

// The tightly packed values of an accessor (the source assets use one packed view each).
function read(index) {
  const a = source.accessors[index];
  const v = source.bufferViews[a.bufferView];
  if (v.byteStride || a.sparse) throw new Error(`accessor ${index}: strided or sparse`);
  const T = ARRAYS[a.componentType];
  const n = a.count * COMPS[a.type];
  const off = (v.byteOffset || 0) + (a.byteOffset || 0);
  return new T(bin.buffer.slice(bin.byteOffset + off, bin.byteOffset + off + n * T.BYTES_PER_ELEMENT));
}

const clone = (o) => JSON.parse(JSON.stringify(o));
const pad4 = (n) => (n + 3) & ~3;
const require = (json, ext) => {
  json.extensionsUsed = [...new Set([...(json.extensionsUsed || []), ext])];
  json.extensionsRequired = [...new Set([...(json.extensionsRequired || []), ext])];
};

// A .glb of `json` with `chunks` (Uint8Arrays, each 4-byte aligned) as its BIN chunk.
function glb(json, chunks) {
  let jsonBytes = Buffer.from(JSON.stringify(json));
  jsonBytes = Buffer.concat([jsonBytes, Buffer.alloc(pad4(jsonBytes.length) - jsonBytes.length, 0x20)]);
  const body = Buffer.concat(chunks.map((c) => Buffer.concat([Buffer.from(c), Buffer.alloc(pad4(c.length) - c.length)])));
  const header = Buffer.alloc(12);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + jsonBytes.length + 8 + body.length, 8);
  const chunk = (type, data) => {
    const h = Buffer.alloc(8);
    h.writeUInt32LE(data.length, 0);
    h.write(type, 4);
    return Buffer.concat([h, data]);
  };
  return Buffer.concat([header, chunk('JSON', jsonBytes), chunk('BIN\0', body)]);
}

async function dracoFile() {
  const enc = await draco3d.createEncoderModule({});
  const dec = await draco3d.createDecoderModule({});
  const json = clone(source);
  json.accessors = [];
  json.bufferViews = [];
  const chunks = [];
  let offset = 0;
  const SEMANTIC = { POSITION: enc.POSITION, NORMAL: enc.NORMAL, TEXCOORD_0: enc.TEX_COORD };
  for (const mesh of json.meshes) {
    for (const prim of mesh.primitives) {
      if ((prim.mode ?? 4) !== 4) throw new Error('only triangle lists');
      const indices = Uint32Array.from(read(prim.indices));
      const builder = new enc.MeshBuilder();
      const m = new enc.Mesh();
      builder.AddFacesToMesh(m, indices.length / 3, indices);
      const ids = {};
      for (const [name, acc] of Object.entries(prim.attributes)) {
        const a = source.accessors[acc];
        ids[name] = builder.AddFloatAttributeToMesh(m, SEMANTIC[name], a.count, COMPS[a.type], read(acc));
      }
      const encoder = new enc.Encoder();
      encoder.SetAttributeQuantization(enc.POSITION, 14);
      encoder.SetAttributeQuantization(enc.NORMAL, 10);
      encoder.SetAttributeQuantization(enc.TEX_COORD, 12);
      encoder.SetEncodingMethod(enc.MESH_EDGEBREAKER_ENCODING);
      const out = new enc.DracoInt8Array();
      const length = encoder.EncodeMeshToDracoBuffer(m, out);
      if (!length) throw new Error('Draco encoding failed');
      const bytes = new Uint8Array(length);
      for (let i = 0; i < length; i++) bytes[i] = out.GetValue(i) & 0xff;
      [out, encoder, m, builder].forEach((o) => enc.destroy(o));

      // Accessor counts and POSITION bounds are those of the decoded mesh (Draco reorders).
      const decoder = new dec.Decoder();
      const decoded = new dec.Mesh();
      const status = decoder.DecodeArrayToMesh(new Int8Array(bytes.buffer), length, decoded);
      if (!status.ok()) throw new Error(`Draco round trip: ${status.error_msg()}`);
      const points = decoded.num_points();
      const posAttr = decoder.GetAttributeByUniqueId(decoded, ids.POSITION);
      const pos = new dec.DracoFloat32Array();
      decoder.GetAttributeFloatForAllPoints(decoded, posAttr, pos);
      const min = [Infinity, Infinity, Infinity], max = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < points * 3; i++) {
        min[i % 3] = Math.min(min[i % 3], pos.GetValue(i));
        max[i % 3] = Math.max(max[i % 3], pos.GetValue(i));
      }
      const faces = decoded.num_faces();
      [pos, status, decoded, decoder].forEach((o) => dec.destroy(o));

      json.bufferViews.push({ buffer: 0, byteOffset: offset, byteLength: length });
      chunks.push(bytes);
      offset += pad4(length);
      const attributes = {};
      for (const name of Object.keys(prim.attributes)) {
        const a = source.accessors[prim.attributes[name]];
        attributes[name] = json.accessors.length;
        json.accessors.push({ componentType: 5126, count: points, type: a.type,
                              ...(name === 'POSITION' ? { min, max } : {}) });
      }
      prim.attributes = attributes;
      prim.indices = json.accessors.length;
      json.accessors.push({ componentType: points > 65535 ? 5125 : 5123, count: faces * 3,
                            type: 'SCALAR' });
      prim.extensions = { ...prim.extensions,
                          KHR_draco_mesh_compression: { bufferView: json.bufferViews.length - 1,
                                                        attributes: ids } };
    }
  }
  json.buffers = [{ byteLength: offset }];
  require(json, 'KHR_draco_mesh_compression');
  return glb(json, chunks);
}

async function meshoptFile() {
  await MeshoptEncoder.ready;
  const json = clone(source);
  const indexViews = new Set(), normalAccessors = new Set();
  for (const mesh of json.meshes) {
    for (const prim of mesh.primitives) {
      indexViews.add(source.accessors[prim.indices].bufferView);
      if (prim.attributes.NORMAL !== undefined) normalAccessors.add(prim.attributes.NORMAL);
    }
  }
  // Normals become 8-bit octahedral (4 bytes a vertex): BYTE, normalized (KHR_mesh_quantization).
  const octViews = new Map();
  for (const acc of normalAccessors) {
    const a = json.accessors[acc];
    const n = read(acc);
    const padded = new Float32Array(a.count * 4);
    for (let i = 0; i < a.count; i++) padded.set(n.subarray(i * 3, i * 3 + 3), i * 4);
    octViews.set(a.bufferView, MeshoptEncoder.encodeFilterOct(padded, a.count, 4, 8));
    Object.assign(a, { componentType: 5120, normalized: true, byteOffset: 0 });
  }
  const chunks = [];
  let compressed = 0, fallback = 0;
  json.bufferViews = source.bufferViews.map((v, index) => {
    const a = source.accessors.find((x) => x.bufferView === index);
    let count = a.count, stride = SIZES[a.componentType] * COMPS[a.type];
    let data = new Uint8Array(bin.buffer, bin.byteOffset + (v.byteOffset || 0), v.byteLength);
    let mode = 'ATTRIBUTES', filter;
    if (indexViews.has(index)) mode = 'TRIANGLES';
    if (octViews.has(index)) {
      data = octViews.get(index);
      stride = 4;
      filter = 'OCTAHEDRAL';
    }
    const encoded = MeshoptEncoder.encodeGltfBuffer(data, count, stride, mode);
    chunks.push(encoded);
    const view = { buffer: 1, byteOffset: fallback, byteLength: count * stride,
                   ...(mode === 'ATTRIBUTES' ? { byteStride: stride } : {}),
                   ...(v.target ? { target: v.target } : {}),
                   extensions: { EXT_meshopt_compression: {
                     buffer: 0, byteOffset: compressed, byteLength: encoded.length,
                     byteStride: stride, count, mode, ...(filter ? { filter } : {}) } } };
    compressed += pad4(encoded.length);
    fallback += pad4(count * stride);
    return view;
  });
  json.buffers = [{ byteLength: compressed },
                  { byteLength: fallback, extensions: { EXT_meshopt_compression: { fallback: true } } }];
  require(json, 'EXT_meshopt_compression');
  require(json, 'KHR_mesh_quantization');
  return glb(json, chunks);
}

mkdirSync(outDir, { recursive: true });
const scene = JSON.parse(readFileSync(join(srcDir, 'product.json'), 'utf8'));
for (const [name, make] of [['product_draco', dracoFile], ['product_meshopt', meshoptFile]]) {
  const bytes = await make();
  writeFileSync(join(outDir, `${name}.glb`), bytes);
  writeFileSync(join(outDir, `${name}.json`),
                `${JSON.stringify({ ...scene, comment: `${scene.comment} (${name}.glb: ` +
                                    'compressed by tools/assets/gen_compressed.mjs)',
                                    gltf: `${name}.glb` }, null, 2)}\n`);
  console.log(`gen_compressed: ${name}.glb ${bytes.length} B`);
}

// A PNG as tools/assets/gen_glass.py's png_rgba writes it (8-bit RGBA, one IDAT, filter 0 on
// every row) as RGBA8 pixels.
function pngPixels(path) {
  const png = readFileSync(path);
  const width = png.readUInt32BE(16), height = png.readUInt32BE(20);
  if (png[24] !== 8 || png[25] !== 6) throw new Error(`${path}: not 8-bit RGBA`);
  let at = 8;
  const idat = [];
  while (at < png.length) {
    const length = png.readUInt32BE(at);
    if (png.toString('latin1', at + 4, at + 8) === 'IDAT') idat.push(png.subarray(at + 8, at + 8 + length));
    at += 12 + length;
  }
  const raw = inflateSync(Buffer.concat(idat));
  const data = new Uint8Array(width * height * 4);
  for (let y = 0; y < height; ++y) {
    if (raw[y * (width * 4 + 1)] !== 0) throw new Error(`${path}: a filtered row`);
    data.set(raw.subarray(y * (width * 4 + 1) + 1, (y + 1) * (width * 4 + 1)), y * width * 4);
  }
  return { width, height, data };
}

async function glassKtx2() {
  const glassDir = join(root, 'assets/glass');
  const json = JSON.parse(readFileSync(join(glassDir, 'glass.gltf'), 'utf8'));
  const pixels = pngPixels(join(glassDir, 'lattice.png'));
  // UASTC (near-lossless) with the sRGB transfer function, no mip levels (nearest filtering).
  const ktx2 = await encodeToKTX2(new Uint8Array(0), {
    isUASTC: true, isSetKTX2SRGBTransferFunc: true, generateMipmap: false, isKTX2File: true,
    imageDecoder: async () => pixels,
  });
  json.buffers = json.buffers.map((b) => ({ ...b, uri: `../glass/${b.uri}` }));
  json.images = [{ uri: 'lattice.ktx2', mimeType: 'image/ktx2' }];
  json.textures = json.textures.map(({ source, ...t }) => ({
    ...t, extensions: { KHR_texture_basisu: { source } } }));
  require(json, 'KHR_texture_basisu');
  writeFileSync(join(outDir, 'lattice.ktx2'), ktx2);
  writeFileSync(join(outDir, 'glass_ktx2.gltf'), `${JSON.stringify(json, null, 1)}\n`);
  const scene = JSON.parse(readFileSync(join(glassDir, 'glass.json'), 'utf8'));
  writeFileSync(join(outDir, 'glass_ktx2.json'),
                `${JSON.stringify({ ...scene, comment: `${scene.comment} (glass_ktx2.gltf: the ` +
                                    'lattice as KTX2, by tools/assets/gen_compressed.mjs)',
                                    gltf: 'glass_ktx2.gltf' }, null, 2)}\n`);
  console.log(`gen_compressed: lattice.ktx2 ${ktx2.length} B`);
}
await glassKtx2();

// The layers scene with each PNG as a UASTC KTX2 file (their extension slots make the browser
// transcode them to RGBA8: gpu/gpu_scene.h).
async function layersKtx2() {
  const dir = join(root, 'assets/layers');
  const json = JSON.parse(readFileSync(join(dir, 'layers.gltf'), 'utf8'));
  let total = 0;
  json.images = await Promise.all(json.images.map(async ({ uri }) => {
    const pixels = pngPixels(join(dir, uri));
    const ktx2 = await encodeToKTX2(new Uint8Array(0), {
      isUASTC: true, generateMipmap: false, isKTX2File: true, imageDecoder: async () => pixels,
    });
    const name = `layers_${uri.replace(/\.png$/, '.ktx2')}`;
    writeFileSync(join(outDir, name), ktx2);
    total += ktx2.length;
    return { uri: name, mimeType: 'image/ktx2' };
  }));
  json.buffers = json.buffers.map((b) => ({ ...b, uri: `../layers/${b.uri}` }));
  json.textures = json.textures.map(({ source, ...t }) => ({
    ...t, extensions: { KHR_texture_basisu: { source } } }));
  require(json, 'KHR_texture_basisu');
  writeFileSync(join(outDir, 'layers_ktx2.gltf'), `${JSON.stringify(json, null, 1)}\n`);
  const scene = JSON.parse(readFileSync(join(dir, 'layers.json'), 'utf8'));
  writeFileSync(join(outDir, 'layers_ktx2.json'),
                `${JSON.stringify({ ...scene, comment: `${scene.comment} (layers_ktx2.gltf: its ` +
                                    'textures as KTX2, by tools/assets/gen_compressed.mjs)',
                                    gltf: 'layers_ktx2.gltf' }, null, 2)}\n`);
  console.log(`gen_compressed: layers' five textures as KTX2, ${total} B`);
}
await layersKtx2();
