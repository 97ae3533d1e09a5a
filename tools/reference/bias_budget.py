"""The bias budget (issue #41): where Penumbra's converged error against Cycles sits, term by
term. Run through tools/bias-budget.

Cycles renders four path sets of each scene (tools/reference/render --bounces): direct light
only (C0: what the camera's first hit receives from the lights and the environment, lamp faces
and the environment seen directly included), the same from the scene's lights alone (C0L: the
world black, --no-world), plus one bounce (C1), and the full solution (Cf, every kind of bounce
up to 64), and the full one a second time with another seed (its noise). Penumbra renders the
matching terms: direct (P0: --no-gi --no-ssgi: analytic lights with their shadow maps, the
split-sum environment with its occlusion), the lights alone (P0L: --env-intensity 0), plus its
screen-space one-bounce indirect light (P1: --no-gi), and everything (Pf: with the probe volume).
The total error Pf - Cf is then the sum of four signed terms:

  lights            P0L - C0L                area and punctual lights with their shadows
  environment       (P0 - P0L) - (C0 - C0L)  the environment (and its sun) with its occlusion
  first bounce      (P1 - P0) - (C1 - C0)    screen-space indirect light against Cycles' 1st bounce
  further bounces   (Pf - P1) - (Cf - C1)    the probe volume against Cycles' 2nd and later

(the probe volume also brings first-bounce light from off screen; its share shows in the third
term). Per term: the signed mean (share of Cycles' mean, linear radiance) and the RMS (linear
radiance x 2^exposure, as displayed before tone mapping), with a picture of each signed
difference (red: Penumbra too bright, blue: too dark).
"""
import argparse
import datetime
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import evaluate as ev  # noqa: E402  (read_rgb, display, luma, SCENES)

import matplotlib  # noqa: E402
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The full solution follows every kind of bounce to 64: Blender's defaults end diffuse and glossy
# paths after 4, which left the Cornell box 2.0 % darker than the 64-bounce render (its walls
# reflect about half the light they get, so the 5th and later bounces still count).
FULL_BOUNCES = 64
# (name, bounces, seed, extra flags). The lights-only direct render splits the direct term into
# the lights' and the environment's (with its sun and its occlusion): direct light is linear in
# its sources, so the environment's share is the direct render minus the lights-only one.
PATH_SETS = [("cycles_b0", 0, 1, []), ("cycles_b0_lights", 0, 1, ["--no-world"]),
             ("cycles_b1", 1, 1, []), ("cycles_full", FULL_BOUNCES, 1, []),
             ("cycles_full_seed2", FULL_BOUNCES, 2, [])]
PENUMBRA_TERMS = [("penumbra_direct", ["--no-gi", "--no-ssgi"]),
                  ("penumbra_direct_lights", ["--no-gi", "--no-ssgi", "--env-intensity", "0"]),
                  ("penumbra_ssgi", ["--no-gi"]), ("penumbra_full", [])]


def scene_size(scene_file, width):
    with open(scene_file) as f:
        sf = json.load(f)
    rw, rh = sf.get("resolution", [1280, 720])
    return "%dx%d" % (width, int(round(width * rh / rw))), float(sf.get("exposure", 0.0))


def render_cycles(root, scene, cache, size, samples, force):
    for name, bounces, seed, extra in PATH_SETS:
        out = os.path.join(cache, name + ".exr")
        if os.path.exists(out) and not force:
            continue
        cmd = [os.path.join(root, "tools/reference/render"), scene, cache, "--only", "cycles",
               "--samples", str(samples), "--size", size, "--seed", str(seed), "--name", name,
               "--bounces", str(bounces)] + extra
        r = subprocess.run(cmd, cwd=root, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError("%s failed:\n%s" % (" ".join(cmd), r.stderr[-2000:]))


def render_penumbra(binary, scene, cache, size, frames):
    for name, flags in PENUMBRA_TERMS:
        out = os.path.join(cache, name + ".exr")
        cmd = ["nice", "-n", "15", binary, scene, "-o", out, "--size", size, "--frames", str(frames),
               "-q"] + flags
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError("%s failed:\n%s" % (" ".join(cmd), r.stderr[-2000:]))


def budget(cache, exposure):
    C = {n: ev.read_rgb(os.path.join(cache, n + ".exr")) for n, _, _, _ in PATH_SETS}
    P = {n: ev.read_rgb(os.path.join(cache, n + ".exr")) for n, _ in PENUMBRA_TERMS}
    k = 2.0 ** exposure
    terms = {
        "lights": P["penumbra_direct_lights"] - C["cycles_b0_lights"],
        "environment": (P["penumbra_direct"] - P["penumbra_direct_lights"])
        - (C["cycles_b0"] - C["cycles_b0_lights"]),
        "first bounce": (P["penumbra_ssgi"] - P["penumbra_direct"]) - (C["cycles_b1"] - C["cycles_b0"]),
        "further bounces": (P["penumbra_full"] - P["penumbra_ssgi"]) - (C["cycles_full"] - C["cycles_b1"]),
    }
    total = P["penumbra_full"] - C["cycles_full"]
    ref_mean = float(C["cycles_full"].mean())
    rms = lambda d: float(np.sqrt(np.mean((k * d) ** 2)))  # noqa: E731
    # Cycles' own noise in the full reference: two seeds differ by sqrt(2) x one render's noise.
    noise = rms(C["cycles_full"] - C["cycles_full_seed2"]) / np.sqrt(2.0)
    row = {
        "terms": {t: {"mean": float(d.mean()) / ref_mean, "rms": rms(d)} for t, d in terms.items()},
        "total": {"mean": float(total.mean()) / ref_mean, "rms": rms(total)},
        "cycles_noise_rms": float(noise),
        "mean": {"cycles": ref_mean, "penumbra": float(P["penumbra_full"].mean()),
                 "cycles_direct": float(C["cycles_b0"].mean()), "penumbra_direct": float(P["penumbra_direct"].mean()),
                 "cycles_lights": float(C["cycles_b0_lights"].mean()),
                 "penumbra_lights": float(P["penumbra_direct_lights"].mean()),
                 "cycles_b1": float(C["cycles_b1"].mean()), "penumbra_ssgi": float(P["penumbra_ssgi"].mean())},
    }
    return row, terms, total, C, P


def plot(path, name, terms, total, C, P, exposure):
    k = 2.0 ** exposure
    panels = [("Cycles", C["cycles_full"]), ("Penumbra", P["penumbra_full"])]
    diffs = list(terms.items()) + [("total", total)]
    lim = max(1e-3, max(float(np.percentile(np.abs(k * ev.luma(d)), 99.5)) for _, d in diffs))
    n = len(panels) + len(diffs)
    h, w = total.shape[:2]
    fig, axes = plt.subplots(1, n, figsize=(2.4 * n, 2.4 * h / w + 0.7))
    for ax, (title, lin) in zip(axes, panels):
        ax.imshow(ev.display(lin, exposure), interpolation="nearest")
        ax.set_title(title, fontsize=8)
        ax.axis("off")
    for ax, (title, d) in zip(axes[len(panels):], diffs):
        im = ax.imshow(k * ev.luma(d), cmap="coolwarm", vmin=-lim, vmax=lim, interpolation="nearest")
        ax.set_title(title, fontsize=8)
        ax.axis("off")
    fig.colorbar(im, ax=axes[-1], fraction=0.046, pad=0.02)
    fig.suptitle("%s: signed difference Penumbra - Cycles per term (luminance x 2^EV; red: too bright)" % name,
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def pct(x):
    return "%+.1f %%" % (100.0 * x)


def frames_arg(text):
    if text == "auto":
        return text
    if not text.isdigit() or int(text) < 1:
        raise argparse.ArgumentTypeError("frames: a positive number or auto, not %r" % text)
    return text


def write_report(path, results, a, when):
    L = ["# The bias budget: Penumbra's converged error against Cycles, term by term", "",
         "Generated by `tools/bias-budget --width %d --frames %s --samples %d` on %s UTC (issue #41). "
         "Each scene at %d pixels wide (its file's aspect): Cycles renders direct light only (C0), the "
         "same from the scene's lights alone (C0L), plus one bounce (C1) and the full solution (Cf: every kind of bounce up to 64; Blender's defaults, "
         "which the 1280x720 evaluation uses, end diffuse and glossy paths after 4 and leave the Cornell "
         "box 2.0 %% darker), %d samples each, with "
         "glTF's BRDF (`tools/reference/render --bounces`); Penumbra, %s frames, renders its matching "
         "terms: direct (P0: `--no-gi --no-ssgi`), the lights alone (P0L: also `--env-intensity 0`; "
         "Cycles' C0L: `--no-world`), plus screen-space indirect light (P1: `--no-gi`), "
         "everything (Pf). The total error Pf - Cf is the sum of the four signed terms:" % (
             a.width, a.frames, a.samples, when, a.width, a.samples, a.frames), "",
         "- **lights** = P0L - C0L (area and punctual lights with their shadows, lamp faces);",
         "- **environment** = (P0 - P0L) - (C0 - C0L) (the environment and its sun, with their "
         "occlusion and shadows; direct light is linear in its sources);",
         "- **first bounce** = (P1 - P0) - (C1 - C0) (screen-space indirect light against Cycles' first bounce);",
         "- **further bounces** = (Pf - P1) - (Cf - C1) (the probe volume against Cycles' second and later "
         "bounces; it also brings the first bounce from off screen, which shows here).", "",
         "Cells: signed mean as a share of Cycles' full mean radiance / RMS of the difference (linear "
         "radiance x 2^exposure). Cycles noise: the RMS of one full reference's own noise (two seeds); "
         "an RMS near it is noise, not bias.", "",
         "How the terms interact. Penumbra's diffuse occlusion ray (one direction a pixel a frame, on "
         "screen, up to the occlusion distance) decides per direction: a hit drops the environment's light "
         "there and, with screen-space indirect light on, brings the radiance found at the hit; a miss keeps "
         "the environment's irradiance, or with the probe volume on, takes the volume's irradiance instead. "
         "So where a blocker is off screen or farther than the occlusion distance (an interior's walls, a "
         "backdrop), the environment term lets sky in that Cycles blocks (positive), the first-bounce term misses "
         "that blocker's light (negative), and in the full image the probe volume replaces both with its own "
         "irradiance: it removes the environment term's excess again, which shows as a negative share of the "
         "further-bounces term. Only the total is one image's error; the terms say which part of Penumbra carries it.",
         "",
         "Why each scene's remaining error is where it is, term by term, and what would halve it: "
         "[bias-budget-reading.md](bias-budget-reading.md) (written by hand from these pictures and the "
         "A/B runs in docs/decisions; reread it when this table moves).",
         "",
         "| scene | lights | environment | first bounce | further bounces | total | Cycles noise | mean: Cycles / Penumbra |",
         "|---|---|---|---|---|---|---|---|"]
    for name, r in results.items():
        if "error" in r:
            L.append("| %s | %s | | | | | | |" % (name, r["error"]))
            continue
        t = r["terms"]
        cell = lambda x: "%s / %.4f" % (pct(x["mean"]), x["rms"])  # noqa: E731
        L.append("| %s | %s | %s | %s | %s | %s | %.4f | %.4f / %.4f |" % (
            name, cell(t["lights"]), cell(t["environment"]), cell(t["first bounce"]), cell(t["further bounces"]),
            cell(r["total"]), r["cycles_noise_rms"], r["mean"]["cycles"], r["mean"]["penumbra"]))
    L += ["", "Largest term per scene (by RMS):", ""]
    for name, r in results.items():
        if "error" in r:
            continue
        big = max(r["terms"].items(), key=lambda kv: kv[1]["rms"])
        L.append("- %s: %s (%s of the mean, RMS %.4f)" % (name, big[0], pct(big[1]["mean"]), big[1]["rms"]))
    L.append("")
    for name, r in results.items():
        if "error" not in r:
            L += ["![%s bias budget](bias_%s.png)" % (name, name), ""]
    with open(path, "w") as f:
        f.write("\n".join(L))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--scenes", default=",".join(ev.SCENES))
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--frames", type=frames_arg, default="128",
                    help="Penumbra's frames: a number, or auto (the default view: until measured converged)")
    ap.add_argument("--samples", type=int, default=256)
    ap.add_argument("--render", default="build/tools/render/penumbra-render")
    ap.add_argument("--cache", default="eval-cache")
    ap.add_argument("--out", default="docs/evaluation")
    ap.add_argument("--force", action="store_true", help="render Cycles again even where cached")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite bias-budget.md from bias_budget.json without rendering")
    a = ap.parse_args()
    root = a.root
    out = os.path.join(root, a.out)
    if a.report_only:
        with open(os.path.join(out, "bias_budget.json")) as f:
            saved = json.load(f)
        a.width, a.frames, a.samples = saved.pop("_run", [a.width, a.frames, a.samples])
        write_report(os.path.join(out, "bias-budget.md"), saved, a, saved.pop("_when", "?"))
        print("wrote %s" % os.path.join(a.out, "bias-budget.md"))
        return
    binary = os.path.join(root, a.render)
    if not os.path.exists(binary):
        sys.exit("bias-budget: %s is missing: build first (cmake --build build)" % a.render)
    os.makedirs(out, exist_ok=True)
    results = {}
    for name in a.scenes.split(","):
        if name not in ev.SCENES:
            sys.exit("bias-budget: unknown scene '%s' (one of %s)" % (name, ", ".join(ev.SCENES)))
        scene = os.path.join(root, ev.SCENES[name])
        size, exposure = scene_size(scene, a.width)
        cache = os.path.join(root, a.cache, "bias-%s-%dspp" % (size, a.samples), name)
        os.makedirs(cache, exist_ok=True)
        try:
            render_cycles(root, scene, cache, size, a.samples, a.force)
            render_penumbra(binary, scene, cache, size, a.frames)
            row, terms, total, C, P = budget(cache, exposure)
            plot(os.path.join(out, "bias_%s.png" % name), name, terms, total, C, P, exposure)
        except (RuntimeError, OSError) as e:
            row = {"error": str(e).splitlines()[0]}
        results[name] = dict(row, size=size, exposure=exposure)
        print(json.dumps({name: results[name]}), flush=True)
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M")
    with open(os.path.join(out, "bias_budget.json"), "w") as f:
        json.dump(dict(results, _run=[a.width, a.frames, a.samples], _when=when), f, indent=1)
    write_report(os.path.join(out, "bias-budget.md"), results, a, when)
    print("wrote %s" % os.path.join(a.out, "bias-budget.md"))


if __name__ == "__main__":
    main()
