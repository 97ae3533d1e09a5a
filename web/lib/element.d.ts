// Types of <penumbra-viewer> (element.mjs, the npm package's entry). docs/web/api.md lists every
// attribute and event.

import type { SceneInfo, Viewer } from './penumbra.js';

// Penumbra, PenumbraError, Viewer, version and the API's types, as element.mjs re-exports them.
export * from './penumbra.js';

/** detail of the 'error' event. */
export interface PenumbraViewerErrorDetail {
  /** loadfailure: src or environment-image; attribute: a bad value; startfailure: no WebGL2 or
   *  the module did not load; render: the frame loop. */
  type: 'loadfailure' | 'attribute' | 'startfailure' | 'render';
  /** The one-line message, e.g. "cannot fetch http://…/missing.glb: HTTP 404 Not Found". */
  message: string;
  sourceError: unknown;
}

/** The element's own events ('error' here is a CustomEvent, not the DOM's ErrorEvent). */
export interface PenumbraViewerEventMap {
  /** A scene from src loaded (its variant-name and camera-* applied). */
  load: CustomEvent<{ url: string; scene: SceneInfo }>;
  error: CustomEvent<PenumbraViewerErrorDetail>;
  /** A frame completed: frame of total (totalProgress: frame / total, never going back and
   *  rising at most 0.25 a frame, as the total of an automatic view is an estimate). */
  /** The download, as model-viewer's: 0 as it begins, 1 once the scene is loaded. */
  progress: CustomEvent<{ totalProgress: number }>;
  /** The refinement after each rendered frame (totalProgress never goes back). */
  'refine-progress': CustomEvent<{ frame: number; total: number; totalProgress: number }>;
  /** Once per view (scene, camera, settings that restart). */
  converged: CustomEvent<{ frame: number; total: number; milliseconds: number }>;
  /** The animation began playing (autoplay or play()), as model-viewer's. */
  play: CustomEvent<Record<string, never>>;
  /** The animation paused (pause()). */
  pause: CustomEvent<Record<string, never>>;
}

/** The attribute of a setting of the schema (occlusionDistance -> occlusion-distance;
 *  toneMapper -> tone-mapping, model-viewer's name). */
export declare function settingAttribute(key: string): string;

export declare class PenumbraViewerElement extends HTMLElement {
  /** The JS API's viewer; null before it is created (loading="lazy" off-screen) or without WebGL2. */
  readonly viewer: Viewer | null;
  /** The scene named by src is loaded and shown. */
  readonly loaded: boolean;
  /** Shows the model now (reveal="manual" or "interaction"). */
  dismissPoster(): void;

  // Properties reflecting the attributes of the same (kebab-case) name.
  src: string | null;
  alt: string | null;
  poster: string | null;
  reveal: 'auto' | 'interaction' | 'manual' | string | null;
  loading: 'eager' | 'lazy' | string | null;
  /** A URL, or "neutral" for the built-in studio. */
  environmentImage: string | null;
  skyboxImage: string | null;
  /** A linear factor, as model-viewer's (1: unchanged; the renderer's setting is EV = log2 of it). */
  exposure: number | null;
  /** auto-rotate: the view turns once left alone for auto-rotate-delay ms. */
  autoRotate: boolean;
  toneMapping: 'neutral' | 'pbr-neutral' | 'aces' | 'reinhard' | 'none' | string | null;
  cameraControls: boolean;
  /** "θ φ radius", e.g. "30deg 75deg 2m"; parts may be "auto". */
  cameraOrbit: string | null;
  /** "x y z", e.g. "0m 0.5m 0m"; parts may be "auto". */
  cameraTarget: string | null;
  /** Vertical, e.g. "45deg", or "auto". */
  fieldOfView: string | null;
  variantName: string | null;
  /** autoplay: plays animation-name (else the first) from load, looping. */
  autoplay: boolean;
  animationName: string | null;
  /** The model's animations' names. */
  readonly availableAnimations: string[];
  /** Seconds into the chosen animation (settable; wraps into [0, duration)). */
  currentTime: number;
  readonly duration: number;
  readonly paused: boolean;
  play(): void;
  pause(): void;
  frames: number | 'auto' | null;

  addEventListener<K extends keyof PenumbraViewerEventMap>(
    type: K, listener: (this: PenumbraViewerElement, ev: PenumbraViewerEventMap[K]) => unknown,
    options?: boolean | AddEventListenerOptions): void;
  addEventListener<K extends keyof HTMLElementEventMap>(
    type: K, listener: (this: PenumbraViewerElement, ev: HTMLElementEventMap[K]) => unknown,
    options?: boolean | AddEventListenerOptions): void;
  addEventListener(type: string, listener: EventListenerOrEventListenerObject,
                   options?: boolean | AddEventListenerOptions): void;
  removeEventListener<K extends keyof PenumbraViewerEventMap>(
    type: K, listener: (this: PenumbraViewerElement, ev: PenumbraViewerEventMap[K]) => unknown,
    options?: boolean | EventListenerOptions): void;
  removeEventListener<K extends keyof HTMLElementEventMap>(
    type: K, listener: (this: PenumbraViewerElement, ev: HTMLElementEventMap[K]) => unknown,
    options?: boolean | EventListenerOptions): void;
  removeEventListener(type: string, listener: EventListenerOrEventListenerObject,
                      options?: boolean | EventListenerOptions): void;
}

declare global {
  interface HTMLElementTagNameMap {
    'penumbra-viewer': PenumbraViewerElement;
  }
}
