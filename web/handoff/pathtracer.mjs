// The hand-off page's path tracer: three.js + three-gpu-pathtracer (WebGLPathTracer) set up to
// render what Penumbra renders (docs/web/handoff.md, "The path-tracer hand-off"):
// - the same glTF (three's GLTFLoader), with EXT_lights_area lights as the path tracer's rect
//   lights (disks as its circular ones) of the same radiance: emission = color x intensity (nits),
//   one-sided toward the node's local -Z, sized by the node's largest axis scale;
// - lamp proxies (extras.area_light_proxy) left out of the path-traced scene: its lights are
//   what rays meet (an emissive proxy kept in it gave fireflies everywhere: bounces that hit it
//   count the light twice). Its camera rays do not see lights, so the lamp faces are drawn over
//   its image as Penumbra shows them (LampLayer): their emission, hidden where the scene's
//   geometry is in front;
// - the same environment: a uniform colour, or the same 2:1 panorama (three's equirectangular
//   mapping is Penumbra's: centre column +X), environmentIntensity, environmentRotation (degrees
//   about +Y, the same sense), shown as background when Penumbra shows it;
// - the same camera (Penumbra's camera-to-world matrix and vertical field of view);
// - exposure 2^EV before the tone mapper (three's NeutralToneMapping is Khronos PBR Neutral),
//   sRGB output.
// The path tracer is only ever loaded by this page: nothing in web/lib imports it.
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { HDRLoader } from 'three/examples/jsm/loaders/HDRLoader.js';
import { FullScreenQuad } from 'three/examples/jsm/postprocessing/Pass.js';
import { ShapedAreaLight, WebGLPathTracer } from 'three-gpu-pathtracer';

// The EXT_lights_area shapes this reader knows: renderer/src/scene/light_kinds.cpp's area rows
// (tests/cli/light_readers.sh fails when a shape there is missing here).
export const AREA_SHAPES = ['rect', 'disk'];

export const TONE_MAPPERS = {
  'pbr-neutral': THREE.NeutralToneMapping, aces: THREE.ACESFilmicToneMapping,
  reinhard: THREE.ReinhardToneMapping, none: THREE.LinearToneMapping,
};

const linear = (rgb) => new THREE.Color().setRGB(rgb[0], rgb[1], rgb[2], THREE.LinearSRGBColorSpace);

// EXT_lights_area lights become ShapedAreaLights under their nodes; their proxies leave the
// scene (into `proxies`, if given). Returns the number of lights.
export async function addAreaLights(gltf, proxies = []) {
  const json = gltf.parser.json;
  const defs = json.extensions?.EXT_lights_area?.lights || [];
  const nodes = json.nodes || [];
  gltf.scene.updateMatrixWorld(true);
  const lightNodes = new Map();
  for (let i = 0; i < nodes.length; i++) {
    const index = nodes[i].extensions?.EXT_lights_area?.light;
    if (index === undefined || !defs[index]) continue;
    const def = defs[index];
    if (!AREA_SHAPES.includes(def.type ?? 'rect')) continue;  // Penumbra rejects the file
    const node = await gltf.parser.getDependency('node', i);
    const pos = new THREE.Vector3(), quat = new THREE.Quaternion(), scl = new THREE.Vector3();
    node.matrixWorld.decompose(pos, quat, scl);
    const scale = Math.max(Math.abs(scl.x), Math.abs(scl.y), Math.abs(scl.z));
    const disk = def.type === 'disk';
    const height = scale * (def.size ?? 1);
    const width = disk ? height : height * (def.rect?.aspect ?? 1);
    const intensity = def.intensity ?? 1000;
    if (!(width > 0 && height > 0 && intensity >= 0)) continue;  // Penumbra drops these too
    const light = new ShapedAreaLight(linear(def.color || [1, 1, 1]), intensity, width, height);
    light.isCircular = disk;
    // The light's own matrix undoes the node's scale: its size is already in world units.
    light.scale.set(1 / (scl.x || 1), 1 / (scl.y || 1), 1 / (scl.z || 1));
    node.add(light);
    lightNodes.set(index, node);
  }
  for (let i = 0; i < nodes.length; i++) {
    if (!lightNodes.has(nodes[i].extras?.area_light_proxy)) continue;
    const proxy = await gltf.parser.getDependency('node', i);
    proxy.updateMatrixWorld(true);
    proxy.removeFromParent();
    proxies.push(proxy);
  }
  gltf.scene.updateMatrixWorld(true);
  return lightNodes.size;
}

// A uniform environment as a tiny equirectangular float texture.
function uniformTexture(rgb) {
  const data = new Float32Array(4 * 2 * 4);
  for (let i = 0; i < 8; i++) data.set([rgb[0], rgb[1], rgb[2], 1], i * 4);
  const t = new THREE.DataTexture(data, 4, 2, THREE.RGBAFormat, THREE.FloatType);
  t.mapping = THREE.EquirectangularReflectionMapping;
  t.colorSpace = THREE.LinearSRGBColorSpace;
  t.needsUpdate = true;
  return t;
}

// The lamp faces, drawn as Penumbra draws a proxy: its emission (emissive x strength, linear),
// depth-tested against the scene's opaque geometry. Rendered once per view into a 4x
// multisampled half-float layer (radiance, alpha = coverage), then laid over every path-traced
// image through the same exposure, tone mapper and sRGB encoding as the path tracer's own.
class LampLayer {
  #scene = new THREE.Scene();
  #target = new THREE.WebGLRenderTarget(1, 1, { type: THREE.HalfFloatType, samples: 4 });
  #quad;
  faces = 0;

  constructor(sceneRoot, proxies) {
    const depthOnly = new THREE.MeshBasicMaterial({ colorWrite: false });
    const add = (mesh, material) => {
      const c = mesh.clone(false);
      c.material = material;
      c.matrixAutoUpdate = false;
      c.matrix.copy(mesh.matrixWorld);
      this.#scene.add(c);
    };
    sceneRoot.updateMatrixWorld(true);
    sceneRoot.traverse((o) => {
      if (!o.isMesh) return;
      const m = Array.isArray(o.material) ? o.material[0] : o.material;
      if (m && (m.transparent || m.transmission > 0)) return;  // seen through: hides nothing
      add(o, depthOnly);
    });
    for (const proxy of proxies) {
      proxy.traverse((o) => {
        if (!o.isMesh) return;
        const m = Array.isArray(o.material) ? o.material[0] : o.material;
        const glow = (m?.emissive ?? new THREE.Color(0, 0, 0)).clone().multiplyScalar(m?.emissiveIntensity ?? 1);
        add(o, new THREE.MeshBasicMaterial({ color: glow, side: m?.side ?? THREE.FrontSide, toneMapped: false }));
        this.faces++;
      });
    }
    this.#scene.updateMatrixWorld(true);
    this.#quad = new FullScreenQuad(new THREE.MeshBasicMaterial({
      // The layer is premultiplied (a resolved edge pixel holds coverage x radiance): 1, 1 - a.
      map: this.#target.texture, transparent: true, blending: THREE.CustomBlending,
      blendSrc: THREE.OneFactor, blendDst: THREE.OneMinusSrcAlphaFactor, depthTest: false,
      depthWrite: false }));
  }

  // Draws the faces seen by camera into the layer (width x height: the canvas's).
  render(renderer, camera, width, height) {
    if (!this.faces) return;
    this.#target.setSize(width, height);
    const clear = renderer.getClearColor(new THREE.Color()), alpha = renderer.getClearAlpha();
    renderer.setRenderTarget(this.#target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear();
    renderer.render(this.#scene, camera);
    renderer.setRenderTarget(null);
    renderer.setClearColor(clear, alpha);
  }

  composite(renderer) {
    if (!this.faces) return;
    const autoClear = renderer.autoClear;
    renderer.autoClear = false;
    this.#quad.render(renderer);
    renderer.autoClear = autoClear;
  }
}

// The path tracer's background for Penumbra's settings: none with a transparent background
// (the path tracer then writes alpha 0 there and the page shows through, as through Penumbra's
// canvas), the environment where it is shown, else black.
export function backgroundFor(settings, texture) {
  if (settings.transparentBackground === true) return null;
  if (texture && settings.showBackground !== false) return texture;
  return new THREE.Color(0, 0, 0);
}

export class PathTracerView {
  renderer; pathTracer; scene; camera; compileMs = null; lights = 0; parallelCompile = false;
  autoTiles = true;
  #gl; #lamps; #started = false; #sampleMs = 0; #work = 0;

  // canvas: the path tracer's own canvas. gltfUrl: the glTF Penumbra renders. environment:
  // {uniform: [r, g, b]} or {file: URL} (a 2:1 panorama). settings: Penumbra's (viewer.settings).
  static async create(canvas, { gltfUrl, environment, settings, bounces = 8, tiles = 0 }) {
    const v = new PathTracerView();
    // An alpha channel only for a transparent background (read when the path tracer starts).
    const renderer = new THREE.WebGLRenderer({ canvas, antialias: false,
                                               alpha: settings.transparentBackground === true,
                                               preserveDrawingBuffer: true });
    renderer.setPixelRatio(1);
    renderer.outputColorSpace = THREE.SRGBColorSpace;
    v.renderer = renderer;
    v.#gl = renderer.getContext();
    v.parallelCompile = renderer.extensions.has('KHR_parallel_shader_compile');
    const gltf = await new GLTFLoader().loadAsync(gltfUrl);
    v.scene = new THREE.Scene();
    v.scene.add(gltf.scene);
    const proxies = [];
    v.lights = await addAreaLights(gltf, proxies);
    v.#lamps = new LampLayer(gltf.scene, proxies);
    await v.#setEnvironment(environment, settings);
    v.camera = new THREE.PerspectiveCamera();
    v.applySettings(settings);
    const pt = new WebGLPathTracer(renderer);
    Object.assign(pt, { renderDelay: 0, minSamples: 0, fadeDuration: 0, rasterizeScene: false,
                        dynamicLowRes: false, renderScale: 1, filterGlossyFactor: 0, bounces });
    const toCanvas = pt.renderToCanvasCallback;
    pt.renderToCanvasCallback = (target, r, quad) => {
      toCanvas(target, r, quad);
      v.#lamps.composite(r);
    };
    v.autoTiles = !tiles;  // 0: chosen from the measured sample time (step)
    pt.tiles.set(tiles || 1, tiles || 1);
    v.pathTracer = pt;
    return v;
  }

  async #setEnvironment(env, settings) {
    const scene = this.scene;
    let texture = null;
    if (env.file) {
      texture = await new HDRLoader().loadAsync(env.file);
      if (texture.image.width !== 2 * texture.image.height) {
        throw new Error(`${env.file}: the path tracer needs a 2:1 panorama, got ${texture.image.width}x${texture.image.height}`);
      }
      texture.mapping = THREE.EquirectangularReflectionMapping;
    } else if (env.uniform && env.uniform.some((c) => c > 0)) {
      texture = uniformTexture(env.uniform);
    }
    scene.environment = texture;  // null (black): the path tracer then samples no environment
    const rot = THREE.MathUtils.degToRad(settings.environmentRotation || 0);
    scene.environmentIntensity = settings.environmentIntensity ?? 1;
    scene.environmentRotation.set(0, rot, 0);
    scene.background = backgroundFor(settings, texture);
    if (texture && scene.background === texture) {
      scene.backgroundIntensity = scene.environmentIntensity;
      scene.backgroundRotation.set(0, rot, 0);
      scene.backgroundBlurriness = settings.backgroundBlur || 0;
    }
  }

  // Exposure and tone mapper (they change the display only, not the samples).
  applySettings(settings) {
    const tm = TONE_MAPPERS[settings.toneMapper || 'pbr-neutral'];
    if (tm === undefined) throw new Error(`the path tracer has no tone mapper '${settings.toneMapper}'`);
    this.renderer.toneMapping = tm;
    this.renderer.toneMappingExposure = 2 ** (settings.exposure || 0);
  }

  // Penumbra's camera (viewer.camera / the 'camera' event) at the drawing-buffer size.
  setCamera(cam, width, height) {
    if (cam.orthographic) throw new Error('the path tracer hand-off supports perspective cameras only');
    const c = this.camera;
    new THREE.Matrix4().fromArray(cam.world).decompose(c.position, c.quaternion, c.scale);
    c.fov = THREE.MathUtils.radToDeg(cam.yfov);
    c.aspect = width / height;
    c.near = cam.znear || 0.01;
    c.far = 1e5;
    c.updateProjectionMatrix();
    c.updateMatrixWorld(true);
    const size = this.renderer.getSize(new THREE.Vector2());
    if (size.x !== width || size.y !== height) this.renderer.setSize(width, height, false);
    this.#lamps.render(this.renderer, c, width, height);
    if (!this.#started) {
      this.#started = true;
      this.pathTracer.setScene(this.scene, c);  // builds the BVH; the shader compiles on first use
    } else {
      this.pathTracer.setCamera(c);
    }
    this.#sampleMs = 0;
    this.#work = 0;
  }

  // Renders the first sample of the view set last, which waits for the shader's compile (and
  // three's compileAsync, which polls); compileMs is then that wait.
  async compile() {
    const start = performance.now();
    while (this.pathTracer.samples === 0) {
      this.pathTracer.renderSample();
      this.#sync();
      if (this.pathTracer.samples === 0) await new Promise((r) => setTimeout(r, 10));
    }
    this.compileMs = performance.now() - start;
  }

  get samples() { return this.pathTracer.samples; }
  get lampFaces() { return this.#lamps.faces; }  // meshes drawn over the image as lamp faces
  // Milliseconds of path tracing since the last camera change (the compile is compileMs).
  get tracingMs() { return this.#sampleMs; }

  // Renders tiles until the budget is spent (at least one); each is timed with a 1-pixel
  // read-back. Calls onSample(samples) after each whole sample. Returns the whole samples done.
  // With autoTiles, a sample is split into k x k tiles, k = ceil(sqrt(sample ms / budget)) (at
  // most 8), so that one tile fits the budget and a camera move is answered within a tile.
  // compile() comes first: the compile's wait would otherwise count as tracing time.
  step(budgetMs, onSample) {
    const start = performance.now();
    let prev = start, done = 0;
    for (;;) {
      const before = this.pathTracer.samples;
      this.pathTracer.renderSample();
      this.#sync();
      const t = performance.now();
      const dt = t - prev;
      prev = t;
      const after = this.pathTracer.samples;
      if (after > before) this.#sampleMs += dt;
      this.#work += dt;
      if (Number.isInteger(after) && after > before) {
        done++;
        if (this.autoTiles) {
          const k = Math.min(8, Math.max(1, Math.ceil(Math.sqrt(this.#work / budgetMs))));
          if (k !== this.pathTracer.tiles.x) this.pathTracer.tiles.set(k, k);
        }
        this.#work = 0;
        if (onSample && onSample(after) === false) break;
      }
      if ((t - start) + dt > budgetMs) break;
    }
    return done;
  }

  // The canvas as displayed: {width, height, data} RGBA floats in [0, 1], row 0 at the top.
  readDisplay() {
    const gl = this.#gl;
    const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    const data = new Float32Array(w * h * 4);
    for (let y = 0; y < h; y++) {
      const src = (h - 1 - y) * w * 4, dst = y * w * 4;
      for (let i = 0; i < w * 4; i++) data[dst + i] = px[src + i] / 255;
    }
    return { width: w, height: h, data };
  }

  #sync() {
    const gl = this.#gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));
  }

  dispose() {
    this.pathTracer?.dispose();
    this.renderer?.dispose();
  }
}
