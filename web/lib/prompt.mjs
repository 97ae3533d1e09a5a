// model-viewer's interaction prompt for <penumbra-viewer> (element.mjs): with camera-controls,
// once the model is shown and nobody has touched it for interaction-prompt-threshold ms (3000),
// a hand appears (part="default-interaction-prompt"; slot="interaction-prompt" replaces it),
// swaying from side to side (interaction-prompt-style="wiggle", the default) or still ("basic");
// the first pointer or key on the element takes it away for that model. interaction-prompt=
// "none" turns it off. Unlike model-viewer's "wiggle", the view does not turn with the hand: a
// turning view would restart the accumulation.
export const PROMPT_TEMPLATE = `<div class="prompt" part="interaction-prompt-frame" hidden><slot
  name="interaction-prompt"><svg part="default-interaction-prompt" viewBox="0 0 24 24" width="48"
  height="48" aria-hidden="true"><path fill="rgba(0,0,0,0.55)" stroke="white" stroke-width="0.8"
  d="M9 11V5.5a1.5 1.5 0 0 1 3 0V10h.5V8.5a1.5 1.5 0 0 1 3 0V10h.5V9.5a1.5 1.5 0 0 1 3 0V15a6 6 0
  0 1-6 6h-1a6 6 0 0 1-5-2.7L4.2 14a1.5 1.5 0 0 1 2.5-1.6L9 15z"/></svg></slot></div>`;
export const PROMPT_STYLE = `
  .prompt { position: absolute; left: 50%; bottom: 15%; transform: translateX(-50%);
            pointer-events: none; }
  .prompt.wiggle { animation: penumbra-wiggle 2s ease-in-out infinite; }
  @keyframes penumbra-wiggle { 0%, 100% { margin-left: -24px; } 50% { margin-left: 24px; } }`;
const DEFAULT_THRESHOLD_MS = 3000;

export class InteractionPrompt {
  #element; #frame; #timer = 0; #touched = false;

  constructor(element, shadowRoot) {
    this.#element = element;
    this.#frame = shadowRoot.querySelector('.prompt');
  }

  get shown() { return !this.#frame.hidden; }

  // The model is shown (or not): the wait starts, for this model, unless it was touched.
  update(modelShown) {
    clearTimeout(this.#timer);
    const el = this.#element;
    const on = modelShown && !this.#touched && el.hasAttribute('camera-controls') &&
      el.getAttribute('interaction-prompt') !== 'none';
    if (!on) {
      this.#frame.hidden = true;
      return;
    }
    const given = Number(el.getAttribute('interaction-prompt-threshold'));
    const ms = el.hasAttribute('interaction-prompt-threshold') && given >= 0 ? given
      : DEFAULT_THRESHOLD_MS;
    this.#timer = setTimeout(() => {
      this.#frame.classList.toggle('wiggle', el.getAttribute('interaction-prompt-style') !== 'basic');
      this.#frame.hidden = false;
    }, ms);
  }

  // The user acted on the element: no prompt for this model any more.
  touched() {
    this.#touched = true;
    this.update(false);
  }

  // Another model: it may prompt again.
  reset() {
    this.#touched = false;
    this.update(false);
  }
}
