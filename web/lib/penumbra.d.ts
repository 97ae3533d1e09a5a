// Types of Penumbra's JavaScript API (penumbra.mjs). docs/web/api.md describes the behaviour.

export declare const version: string;

/** Every rejected promise of the API carries one: `message` is the one-line C++ message. */
export declare class PenumbraError extends Error {
  name: 'PenumbraError';
}

export type ToneMapper = 'pbr-neutral' | 'aces' | 'reinhard' | 'none';

/** Everything setSettings() accepts; all optional. */
export interface Settings {
  /** m, the number of intermediate frames to accumulate (1..4096), or "auto" (the default):
   *  until the displayed image is measured converged, at most maxFrames. */
  frames?: number | 'auto';
  /** The most frames an automatic view draws (16..4096, default 1024). */
  maxFrames?: number;
  /** Automatic views stop when the displayed image's estimated RMS error is under this many
   *  8-bit steps and 99 % of its 8x8 tiles are under three times it (default 1). */
  convergenceThreshold?: number;
  /** Automatic views: 8x8 tiles measured converged stop being shaded, so later frames go to
   *  the regions still changing (default true). */
  skipConvergedTiles?: boolean;
  /** f_d: direct-light samples start at frame floor(m * fd) (0..1). */
  fd?: number;
  /** d_occ, the screen-space occlusion distance in scene units (metres). */
  occlusionDistance?: number;
  /** Exposure in EV: the image is scaled by 2^exposure before tone mapping. */
  exposure?: number;
  toneMapper?: ToneMapper;
  /** Bloom: the share of the displayed image's light spread by a wide blur (glare around
   *  emissive surfaces and highlights; the mean is kept). 0 (the default) is off; 0..1. */
  bloom?: number;
  /** One-bounce screen-space indirect light. */
  screenSpaceIndirect?: boolean;
  /** Sky shadows: one environment direction a frame (by luminance, above the horizon) casts a
   * shadow-mapped shadow on the diffuse environment light (default false: without multi-bounce
   * indirect light it only darkens). */
  skyShadows?: boolean;
  /** Probe volume: multi-bounce indirect light from irradiance probes over the scene, filled a
   * few captures per frame; it survives camera moves (default true). */
  probeVolume?: boolean;
  /** Probes along the longest side of the scene's bounds (1..64; default 4). */
  probeDensity?: number;
  /** Probes buried in geometry or at a wall's nose move within their cells at their first
   * capture (default true). */
  probeRelocation?: boolean;
  /** Probe captures per intermediate frame (1..64; default 2). */
  probesPerFrame?: number;
  /** Largest radiance a screen-space indirect sample brings back (0 = no limit; default 10). */
  indirectClamp?: number;
  /** Early frames' diffuse rays averaged with their neighbours' on the same surface, fading to none by this frame (less grain than one ray a pixel); 0 off. Default 16. */
  rayFilterFrames?: number;
  /** Shadow-map samples per area light; 0 = automatic. */
  lightSamples?: number;
  shadowMapSize?: number;
  /** Angular diameter of directional lights in degrees (0..30; default 0.53, the sun's). */
  directionalAngle?: number;
  /** Rotates every sample sequence. */
  seed?: number;
  environmentIntensity?: number;
  /** Degrees about +Y. */
  environmentRotation?: number;
  /** A panorama's sun: luminance above which its brightest compact region becomes a
   *  shadow-casting light; -1 automatic (default), 0 off. Applies when an environment loads. */
  sunThreshold?: number;
  showBackground?: boolean;
  /** The page shows through where the scene is not (the canvas's alpha is its coverage). */
  transparentBackground?: boolean;
  /** A shadow-catching ground under the scene: 0 (off) to 1, model-viewer's shadow-intensity. */
  shadowIntensity?: number;
  /** 0 = sharp, 1 = the roughest prefiltered mip. */
  backgroundBlur?: number;
  /** Milliseconds per animation frame spent on intermediate frames (default 12). */
  budgetMs?: number;
  /** Render resolution / canvas resolution when the camera is still (0.1..2, default 1): an
   *  upper bound, which adaptiveResolution may lower. */
  resolutionScale?: number;
  /** Lower the still resolution (never below the canvas's CSS size, or minStillScale if
   *  higher) when a frame costs more than maxSplit budgets on this device (default true;
   *  false: always resolutionScale). */
  adaptiveResolution?: boolean;
  /** Most parts (bands of the image) a frame too slow for the budget is split into, drawn over
   *  several animation frames (1..64, default 8; 1: never split). */
  maxSplit?: number;
  /** A still view done below the drawing buffer's pixels (a phone: the CSS size) renders again
   *  at them, shown once done there ('sharpened'; state.stage). Default true. */
  devicePixels?: boolean;
}

/** One row of the settings schema (the renderer's table, penumbra/settings.h). */
export interface SettingSchemaEntry {
  key: keyof Settings;
  type: 'bool' | 'integer' | 'number' | 'toneMapper';
  min?: number;
  max?: number;
  default: boolean | number | ToneMapper;
  /** The accepted values, as text ("1..4096", "[0, 1)", "true or false", ...). */
  range: string;
  help: string;
}

/** The full set in effect (setSettings() resolves to it). */
export type EffectiveSettings = Required<Settings>;

export interface CreateOptions extends Settings {
  /** Accumulate in RGBA16F even where RGBA32F is renderable (the weak-device path). */
  forceHalfFloat?: boolean;
  /** Orbit / pan / zoom with mouse and touch (default true). */
  controls?: boolean;
  /** Keep the drawing buffer at the canvas's CSS size x pixelRatio (default true). */
  autoResize?: boolean;
  /** Default min(devicePixelRatio, maxPixelRatio). */
  pixelRatio?: number;
  /** Caps devicePixelRatio when pixelRatio is not given (default 2). */
  maxPixelRatio?: number;
  /** Lowest resolution scale adaptiveResolution picks for the still image (default 0.5); the
   *  canvas's CSS size is the floor when it is higher (a desktop at pixel ratio 1: 1). */
  minStillScale?: number;
  /** Lowest resolution scale used while the camera moves (default 0.25). */
  minMotionScale?: number;
  /** The camera counts as still this long after the last change (ms, default 200). */
  stillMs?: number;
}

export type Vec3 = [number, number, number];
export type ByteSource = ArrayBuffer | ArrayBufferView | Blob;
export type Source = string | URL | ByteSource;

export interface Bounds { min: Vec3; max: Vec3; }

export interface SceneInfo {
  name: string;
  /** A scene file (.json): it brought its camera, environment and settings. */
  sceneFile: boolean;
  triangles: number;
  lights: number;
  cameras: string[];
  /** KHR_materials_variants: the variants' names (empty without the extension). */
  variants: string[];
  /** The variant shown; null for the primitives' own materials. */
  variant: string | null;
  warnings: string[];
  bounds: Bounds;
  environment: string;
  /** The file's glTF animations, in its order. */
  animations: { name: string; duration: number }[];
}

/** viewer.animation (animation.mjs): the loaded model's animations played on the GPU. */
export interface AnimationPlayer {
  readonly animations: { name: string; duration: number }[];
  /** The chosen animation's index (-1: none, the rest pose). */
  readonly index: number;
  /** Seconds into it. */
  readonly time: number;
  readonly playing: boolean;
  readonly duration: number;
  /** An animation chosen while another plays fades in over this many ms (300). */
  crossfadeMs: number;
  /** By name or index; null: the first. Throws naming the model's animations. */
  select(name: string | number | null): number;
  play(): boolean;
  pause(): void;
  /** Wraps into [0, duration). */
  seek(seconds: number): void;
  /** The rest pose: no animation chosen. */
  rest(): void;
}

export interface CameraSpec {
  eye: Vec3;
  target: Vec3;
  /** Default [0, 1, 0]. */
  up?: Vec3;
  /** Vertical field of view in radians; default: the current one. */
  yfov?: number;
}

/** The camera in use (viewer.camera, the 'camera' event). */
export interface CameraInfo {
  name: string;
  /** Column-major camera-to-world matrix (the camera looks down its -Z, +Y up). */
  world: number[];
  eye: Vec3;
  forward: Vec3;
  up: Vec3;
  /** Vertical field of view in radians, and the near plane. */
  yfov: number;
  znear: number;
  orthographic: boolean;
  ymag: number;
}

/** A read-back of the last complete frame at the render size: RGBA floats, row 0 at the top. */
export interface PixelsResult {
  /** The render size: the canvas's drawing buffer at rest on a desktop; on a high-DPR phone
   * it may be lower (never below the canvas's CSS size), and lower still while moving. */
  width: number;
  height: number;
  /** The canvas's drawing-buffer size at rest, which `present` fills (filtered upscaling). */
  canvasWidth: number;
  canvasHeight: number;
  /** Frames accumulated in it. */
  frames: number;
  data: Float32Array;
}

export interface ViewerState {
  frame: number;
  /** m, or an automatic view's expected frames (from its last measured checkpoint; the cap
   *  before one): (total - frame) x frameMs is the time left. */
  total: number;
  converged: boolean;
  /** 'css': the still view (and its 'converged'); 'sharpening': done there and going on at the
   *  drawing buffer's (device) pixels, still showing the CSS-size image; 'device': shown there. */
  stage: 'css' | 'sharpening' | 'device';
  /** Milliseconds of the last intermediate frame (its parts' time), and of the last frame 1. */
  frameMs: number;
  frame1Ms: number;
  /** Milliseconds of the view's first picture (frame 1 at the preview's size, out of the mean). */
  previewMs: number;
  /** Frames completed and parts drawn in the last animation frame that stepped. */
  stepsPerTick: number;
  partsPerTick: number;
  /** Bands of the frame being drawn (1: whole frames), and the parts of the last frame. */
  split: number;
  parts: number;
  /** Measured cost of a still frame (median of the last three), null before one is measured. */
  msPerMegapixel: number | null;
  /** The still image's resolution scale (resolutionScale, or lower by adaptiveResolution). */
  stillScale: number;
  /** Canvas pixels per CSS pixel in effect. */
  pixelRatio: number;
  /** performance.now() of the last restart, and the time from it to convergence. */
  restartedAt: number;
  convergedMs: number;
  lost: boolean;
  moving: boolean;
  renderWidth: number;
  renderHeight: number;
  /** The drawing buffer: CSS size x pixelRatio, or the render size while a moving preview is
   *  shown (the browser scales it up). */
  canvasWidth: number;
  canvasHeight: number;
  motionScale: number;
  /** pause() is in effect. */
  paused: boolean;
  /** An animation frame is scheduled: false once converged with nothing new to show (the loop
   *  sleeps until a change), and while paused. */
  looping: boolean;
  /** GPU memory held by the renderer's textures, renderbuffers and buffers, from their sizes
   *  and formats (what the browser keeps beside them is not counted); 0 while the context is
   *  lost or after the module aborted. */
  gpuMemoryBytes: number;
}

export interface BenchmarkResult {
  frames: number;
  width: number;
  height: number;
  /** Back to back, one read-back at the end (throughput). */
  msPerFrame: number;
  /** With a read-back after every frame (what the time budget sees). */
  msPerFrameSynced: number;
  totalMs: number;
}

export interface ViewerEvents {
  progress: { frame: number; total: number };
  converged: { frame: number; total: number; milliseconds: number };
  /** The still view reached the drawing buffer's pixels (devicePixels): shown from now on. */
  sharpened: { frame: number; total: number; width: number; height: number; milliseconds: number };
  error: Error;
  contextlost: Record<string, never>;
  contextrestored: Record<string, never>;
  /** The camera changed: accumulation restarts. source: 'user-interaction' (the orbit
   *  controls), 'automatic' (auto-rotate) or 'none' (setCamera), as model-viewer's camera-change. */
  camera: CameraInfo & { source: 'user-interaction' | 'automatic' | 'none' };
}

export declare class Viewer {
  static create(canvas: HTMLCanvasElement, options?: CreateOptions): Promise<Viewer>;
  readonly canvas: HTMLCanvasElement;
  readonly info: { context: string; report: string; scene: SceneInfo | null };
  readonly state: ViewerState;
  readonly settings: EffectiveSettings;
  /** The camera in use. */
  readonly camera: CameraInfo;
  /** Every key setSettings() takes, from the renderer's settings schema plus budgetMs and resolutionScale. */
  readonly settingsSchema: SettingSchemaEntry[];
  /**
   * A scene file (.json), .gltf or .glb. `resources` supplies a .gltf's external files by name.
   * Draco- or meshopt-compressed meshes first fetch their decoder from `decoders/` next to this
   * module (once per page; rejects with a PenumbraError if it cannot be fetched).
   */
  /** onProgress: the download's progress, 0 to under 1, never going back (model-viewer's totalProgress). */
  loadScene(source: Source, options?: { name?: string; resources?: Record<string, ByteSource>;
                                        onProgress?: (progress: number) => void }): Promise<SceneInfo>;
  /**
   * Packed .hdr (penumbra-prefilter), a panorama (.hdr/.png, prefiltered on load), [r, g, b],
   * 'studio' (the built-in neutral studio), or null: forget the environment set here and light
   * by the rule (black for a scene with area lights, else the studio).
   */
  setEnvironment(source: Source | Vec3 | 'studio' | null, options?: { name?: string }): Promise<void>;
  /** model-viewer's skybox-image: the background from another environment file, lighting nothing; null: the environment's. */
  setSkybox(source: Source | null, options?: { name?: string }): Promise<void>;
  /**
   * KHR_materials_variants: shows a variant of the loaded scene by name (or index); null or
   * 'default' for the primitives' own materials. Restarts the view. Returns the variant shown.
   */
  setVariant(name: string | number | null): string | null;
  /** The loaded model's animations (autoplay, animation-name and play() of the element). */
  readonly animation: AnimationPlayer;
  /** A look-at camera, or 'reset' for the scene's own camera. */
  setCamera(camera: CameraSpec | 'reset'): Promise<void>;
  /** Auto-rotate (model-viewer's defaults: pi/32 rad a second after 3000 ms left alone): the view turns about the target's vertical axis; an interaction restarts the delay. */
  setAutoRotate(options: { enabled?: boolean; speed?: number; delayMs?: number }): void;
  setSettings(changes: Settings): Promise<EffectiveSettings>;
  restart(): void;
  /** Stops drawing (an off-screen view) until resume(); what accumulated stays. */
  pause(): void;
  resume(): void;
  on<K extends keyof ViewerEvents>(event: K, handler: (detail: ViewerEvents[K]) => void): () => void;
  off<K extends keyof ViewerEvents>(event: K, handler: (detail: ViewerEvents[K]) => void): void;
  /** The canvas as PNG. */
  screenshot(): Promise<Blob>;
  /**
   * The last complete frame: linear radiance before exposure, or with `display: true` the image
   * as displayed (exposure, tone mapping, sRGB; values in [0, 1]).
   */
  readPixels(options?: { display?: boolean }): Promise<PixelsResult>;
  benchmark(options?: { frames?: number }): Promise<BenchmarkResult>;
  dispose(): void;
}

export declare const Penumbra: {
  create(canvas: HTMLCanvasElement, options?: CreateOptions): Promise<Viewer>;
  version: string;
};
export default Penumbra;
