"""Evaluation of Penumbra against Cycles (reference) and Eevee (peer). Run through tools/evaluate."""
import argparse
import datetime
import json
import os
import re
import shlex
import subprocess
import sys
import time

import numpy as np

from image_metrics import luma, pbr_neutral, ssim  # shared with fidelity_blender.py
import OpenImageIO as oiio
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

# name -> scene file
SCENES = {
    "cornell_box": "assets/cornell_box/cornell_box.json",
    "material_grid": "assets/material_grid/material_grid.json",
    "kitchen": "assets/kitchen/kitchen.json",
    "product": "assets/product/product.json",
    "dense": "assets/dense/dense.json",
    "glass": "assets/glass/glass.json",
    "room_cm": "assets/room_cm/room_cm.json",  # modelled in centimetres (issue #14)
    "showroom": "assets/showroom/showroom.json",  # clearcoat, glass, sheen (issue #17)
    # iridescence, anisotropy, diffuse transmission, dispersion (issue #38); Blender 3.4 has no
    # thin film and no dispersion: the reference lacks those two (gltf_brdf.py)
    "extensions": "assets/extensions/extensions.json",
}
# Scenes whose reference needs more than Blender's default light paths (12 bounces, 4 of them
# diffuse): an interior loses light when paths end at the fourth diffuse bounce, which the probe
# volume carries on (the room (cm)'s mean 0.637 at 4, 0.669 at 64, 4.8 %; the kitchen's 0.163
# and 0.167, 2.6 %). Their references are cached apart, in <scene>_b<N>.
REF_BOUNCES = {"room_cm": 64, "kitchen": 64}
SIZE = "1280x720"
CYCLES_SAMPLES = 128  # the reference (seed 2)
CYCLES_CHECK_SAMPLES = 32  # an independent Cycles render (seed 1): the path tracer at a budget
EEVEE_SAMPLES = 64


# ---------------------------------------------------------------- images and metrics
def read_rgb(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError("cannot read %s: %s" % (path, oiio.geterror()))
    a = np.asarray(inp.read_image(format="float"), dtype=np.float64)
    inp.close()
    if a.ndim == 2:
        a = a[..., None]
    if a.shape[2] == 1:
        a = np.repeat(a, 3, axis=2)
    return a[..., :3]


def write_png(path, rgb01):
    a = (np.clip(rgb01, 0, 1) * 255 + 0.5).astype(np.uint8)
    out = oiio.ImageOutput.create(path)
    out.open(path, oiio.ImageSpec(a.shape[1], a.shape[0], a.shape[2], "uint8"))
    out.write_image(a)
    out.close()


def srgb_encode(x):
    x = np.clip(x, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)


def display(lin, exposure):
    return srgb_encode(pbr_neutral(lin * 2.0 ** exposure))


def metrics(img, ref, exposure):
    rmse = float(np.sqrt(np.mean((img - ref) ** 2)))
    di, dr = display(img, exposure), display(ref, exposure)
    mae = float(np.mean(np.abs(di - dr)))
    return {"rmse": rmse, "mae_tm": mae, "ssim": ssim(luma(di), luma(dr))}


# ---------------------------------------------------------------- rendering
def run_penumbra(binary, scene, out, size, frames, seed=1):
    """Renders one image; returns its wall time and, for frames "auto", the frames it took."""
    cmd = [binary, scene, "-o", out, "--size", size, "--frames", str(frames), "--seed", str(seed)]
    if frames != "auto":
        cmd.append("-q")  # an automatic view's summary line says how many frames it took
    t0 = time.monotonic()
    r = subprocess.run(["nice", "-n", "15"] + cmd, capture_output=True, text=True)
    dt = time.monotonic() - t0
    if r.returncode != 0:
        raise RuntimeError("penumbra-render failed: %s\n%s" % (" ".join(cmd), r.stderr))
    if frames != "auto":
        return dt, frames
    m = re.search(r"(\d+) frames at \d+x\d+", r.stdout + r.stderr)
    if not m:
        raise RuntimeError("penumbra-render printed no frame count: %s" % " ".join(cmd))
    return dt, int(m.group(1))


def ref_commands(scene, cache_dir, size, samples=CYCLES_SAMPLES, bounces=None):
    """The Blender runs behind one scene's cache: reference, independent Cycles, Eevee."""
    base = "tools/reference/render %s %s --size %s " % (scene, cache_dir, size)
    paths = "--bounces %d " % bounces if bounces else ""
    return [base + paths + "--only cycles --samples %d --seed 2" % samples,
            base + paths + "--only cycles --samples %d --seed 1 --name cycles_seed2" % CYCLES_CHECK_SAMPLES,
            base + "--only eevee --eevee-samples %d" % EEVEE_SAMPLES]


# ---------------------------------------------------------------- figures
def plot_error_time(path, name, rows, cycles_s):
    fig, axes = plt.subplots(1, 3, figsize=(12, 3.4))
    pen = [r for r in rows if r["renderer"] == "penumbra" and not r.get("auto")]
    auto = [r for r in rows if r["renderer"] == "penumbra" and r.get("auto")]
    c2 = [r for r in rows if r["renderer"] == "cycles2"]
    eev = [r for r in rows if r["renderer"] == "eevee"]
    for ax, key, label in zip(axes, ("rmse", "mae_tm", "ssim"),
                              ("RMSE, linear RGB", "MAE, tone-mapped sRGB", "SSIM, tone-mapped luminance")):
        ax.plot([r["seconds"] for r in pen], [r[key] for r in pen], "o-", color="tab:orange", label="Penumbra")
        for r in pen:
            ax.annotate("%d" % r["frames"], (r["seconds"], r[key]), textcoords="offset points",
                        xytext=(4, 4), fontsize=8)
        if auto:
            ax.plot([auto[0]["seconds"]], [auto[0][key]], "*", color="tab:red", markersize=10,
                    label="Penumbra auto (%d frames)" % auto[0]["frames"])
        if eev:
            ax.plot([r["seconds"] for r in eev], [r[key] for r in eev], "s", color="tab:blue",
                    label="Eevee %d" % EEVEE_SAMPLES)
        if c2:
            ax.plot([c2[0]["seconds"]], [c2[0][key]], "^", color="tab:green",
                    label="Cycles %d spp, independent" % c2[0]["frames"])
        ax.axvline(cycles_s, color="grey", ls="--", label="Cycles (reference) time")
        ax.set_xscale("log")
        if key != "ssim":
            ax.set_yscale("log")
        ax.set_xlabel("seconds (wall)")
        ax.set_title(label, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(name)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)


def plot_strip(path, name, panels, diff, exposure):
    n = len(panels) + 1
    h, w = diff.shape
    fig, axes = plt.subplots(1, n, figsize=(2.6 * n, 2.6 * h / w + 0.5))
    for ax, (title, lin) in zip(axes, panels):
        ax.imshow(display(lin, exposure), interpolation="nearest")
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    im = axes[-1].imshow(diff, cmap="inferno", vmin=0, vmax=max(0.05, float(np.percentile(diff, 99.5))),
                         interpolation="nearest")
    axes[-1].set_title("|%s - Cycles|, displayed" % panels[len(panels) - 3][0], fontsize=9)
    axes[-1].axis("off")
    fig.colorbar(im, ax=axes[-1], fraction=0.046, pad=0.02)
    fig.suptitle(name, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--frames", default="1,16,64,128")
    ap.add_argument("--render-refs", action="store_true", help="make missing Blender renders")
    ap.add_argument("--render", default=None, help="penumbra-render binary")
    ap.add_argument("--out", default="docs/evaluation")
    ap.add_argument("--cache", default="eval-cache")
    ap.add_argument("--size", default=SIZE, help="image size WxH (the cache has one folder per size)")
    ap.add_argument("--report-only", action="store_true",
                    help="redraw the curves and rewrite README.md from the last run's results.json (no rendering)")
    a = ap.parse_args()
    os.chdir(a.root)
    if a.report_only:
        with open(os.path.join(a.out, "results.json")) as f:
            saved = json.load(f)
        for name, r in saved["scenes"].items():  # the curves need only the saved rows
            plot_error_time(os.path.join(a.out, "%s_error_time.png" % name), name, r["rows"],
                            r["cycles"]["render_seconds"])
        write_report(a, saved["scenes"], saved["skipped"], saved["frames"], saved.get("when"))
        return
    binary = a.render or next((p for p in ("build/tools/render/penumbra-render",
                                           "build-eval/tools/render/penumbra-render") if os.path.exists(p)), None)
    if not binary:
        sys.exit("evaluate: no penumbra-render; build it or pass --render")
    # "auto": the default view, until measured converged (issue #36's time to converged)
    frames = [f if f == "auto" else int(f) for f in a.frames.split(",")]
    counts = [f for f in frames if f != "auto"]
    os.makedirs(a.out, exist_ok=True)
    results = {}
    skipped = []
    # one untimed warm-up so Mesa's shader cache is filled (timings are warm)
    first = SCENES[a.scenes.split(",")[0]]
    run_penumbra(binary, first, "/tmp/penumbra_eval_warmup.exr", "64x64", 1)
    size = a.size
    for name in a.scenes.split(","):
        scene = SCENES[name]
        bounces = REF_BOUNCES.get(name)
        cache = os.path.join(a.cache, size, name + ("_b%d" % bounces if bounces else ""))
        outputs = [os.path.join(cache, f + ".exr") for f in ("cycles", "cycles_seed2", "eevee")]
        cyc, eev = outputs[0], outputs[2]
        if a.render_refs:  # whatever of the three is missing
            for out, cmd in zip(outputs, ref_commands(scene, cache, size, bounces=bounces)):
                if not os.path.exists(out):
                    subprocess.run(shlex.split(cmd), check=True)
        if not os.path.exists(cyc) or not os.path.exists(eev):
            skipped.append(name)
            print("evaluate: %s: no cached reference in %s, skipped (--render-refs makes it)" % (name, cache))
            continue
        with open(scene) as f:
            exposure = float(json.load(f).get("exposure", 0.0))
        ref = read_rgb(cyc)
        cinfo = json.load(open(os.path.join(cache, "cycles.json")))
        einfo = json.load(open(os.path.join(cache, "eevee.json")))
        rows = []
        images = {}
        for k in frames:
            out = os.path.join(cache, "penumbra_%s.exr" % ("auto" if k == "auto" else "f%04d" % k))
            dt, taken = run_penumbra(binary, scene, out, size, k)
            img = read_rgb(out)
            if img.shape != ref.shape:
                raise RuntimeError("%s: size mismatch %s vs %s" % (name, img.shape, ref.shape))
            images[k] = img
            rows.append(dict(renderer="penumbra", frames=taken, seconds=dt, auto=k == "auto",
                             **metrics(img, ref, exposure)))
            print("%s penumbra %4d frames%s %6.2f s  %s" % (name, taken, " (auto)" if k == "auto" else "",
                                                         dt, rows[-1]))
        final = images[max(counts)]
        for row, k in zip(rows, frames):  # convergence: distance to Penumbra's own longest render
            row["rmse_self"] = float(np.sqrt(np.mean((images[k] - final) ** 2)))
        eimg = read_rgb(eev)
        rows.append(dict(renderer="eevee", frames=einfo["samples"], seconds=einfo["render_seconds"],
                         **metrics(eimg, ref, exposure)))
        c2 = os.path.join(cache, "cycles_seed2.exr")
        if os.path.exists(c2):  # Cycles' own noise: a second render with another seed
            c2info = json.load(open(os.path.join(cache, "cycles_seed2.json")))
            rows.append(dict(renderer="cycles2", frames=c2info["samples"], seconds=c2info["render_seconds"],
                             **metrics(read_rgb(c2), ref, exposure)))
        rows.append(dict(renderer="cycles", frames=cinfo["samples"], seconds=cinfo["render_seconds"],
                         rmse=0.0, mae_tm=0.0, ssim=1.0))
        results[name] = {"scene": scene, "size": size, "exposure": exposure, "rows": rows,
                         "cycles": cinfo, "eevee": einfo,
                         "ref_commands": ref_commands(scene, cache, size, cinfo["samples"], bounces),
                         "ref_mean": [float(v) for v in ref.mean(axis=(0, 1))],
                         "pen_mean": [float(v) for v in images[max(counts)].mean(axis=(0, 1))],
                         "eevee_mean": [float(v) for v in eimg.mean(axis=(0, 1))]}
        plot_error_time(os.path.join(a.out, "%s_error_time.png" % name), name, rows, cinfo["render_seconds"])
        strip_frames = [k for k in (1, 16, 128) if k in images]
        panels = [("Penumbra %d frames" % k, images[k]) for k in strip_frames]
        panels += [("Eevee %d samples" % einfo["samples"], eimg), ("Cycles %d spp" % cinfo["samples"], ref)]
        last = images[max(counts)]
        diff = luma(np.abs(display(last, exposure) - display(ref, exposure)))
        plot_strip(os.path.join(a.out, "%s_strip.png" % name), name, panels, diff, exposure)
    when = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M")
    # A run over some scenes keeps the saved rows of the others (each row says when it ran).
    for r in results.values():
        r["when"] = when
    saved_path = os.path.join(a.out, "results.json")
    if os.path.exists(saved_path):
        with open(saved_path) as f:
            saved = json.load(f)
        for name, r in saved["scenes"].items():
            if name not in results and name in SCENES:
                r.setdefault("when", saved.get("when"))
                results[name] = r
        results = {n: results[n] for n in SCENES if n in results}
        skipped = [n for n in skipped if n not in results]
    with open(saved_path, "w") as f:
        json.dump({"scenes": results, "skipped": skipped, "frames": frames, "when": when}, f, indent=1)
    write_report(a, results, skipped, frames, when)


def fmt_mean(v):
    return "(%.3f, %.3f, %.3f)" % tuple(v)


def write_report(a, results, skipped, frames, when):
    L = []
    L.append("# Evaluation: Penumbra against Cycles and Eevee")
    L.append("")
    L.append("Generated by `tools/evaluate` on %s UTC. Regenerate with one command from the cached "
             "Blender renders in `%s/`:" % (when, a.cache))
    L.append("")
    L.append("```\ntools/evaluate            # --render-refs also makes missing references\n```")
    L.append("")
    L.append("**The probe volume.** Every scene with and without Penumbra's probe volume (on by "
             "default since issue #14), at 16 and 128 frames against the same Cycles and Eevee "
             "renders: [probe-volume.md](probe-volume.md) (`tools/gi-eval --size WxH`, from the "
             "references cached here).")
    L.append("")
    L.append("**The bias budget.** Where the converged error against Cycles sits, term by term (the "
             "lights, the environment, the first bounce, further bounces), with Cycles rendering the "
             "matching path sets: [bias-budget.md](bias-budget.md) (`tools/bias-budget`, issue #41), and "
             "why each scene's remaining error is there and what would halve it: "
             "[bias-budget-reading.md](bias-budget-reading.md).")
    L.append("")
    L.append("**Render fidelity on real models.** The 55 public glTF sample models (Khronos; "
             "`../shared/gltf-sample-assets`), each rendered by Penumbra and by Cycles from the same "
             "camera under the same panorama at 320x240, RMSE and SSIM per model, a contact sheet "
             "(Penumbra | Cycles | difference) and the models Blender cannot import faithfully marked "
             "with the reason: [fidelity.md](fidelity.md) (`tools/fidelity`, issue #60).")
    L.append("")
    L.append("The browser's path-tracer hand-off (Penumbra against three-gpu-pathtracer at the moment "
             "the path tracer takes over) has its own table: [handoff.md](handoff.md) "
             "(`node tools/handoff-eval.mjs`).")
    L.append("")
    sizes = " and ".join(sorted({r["size"] for r in results.values()}))
    L.append("**Setup.** Every scene is rendered at %s on this 2-core machine (everything ran "
             "under `nice -n 15` on an otherwise lightly used machine; timings vary by about 20 %%). "
             "Penumbra runs `penumbra-render SCENE --size WxH --frames K` once per K (a K-frame "
             "budget is a complete progressive render of K frames, not frame K of a longer one) on "
             "llvmpipe (software GL, EGL surfaceless), writing linear EXR; its time is the wall time "
             "of the whole process (start-up, scene and environment loading, prefiltering, shader "
             "set-up and K frames), with the Mesa shader cache warm. Blender's times are "
             "`bpy.ops.render.render` only (Blender start-up and glTF import excluded), 2 threads. "
             "Both Blender engines render glTF's BRDF (Lambert diffuse, GGX specular, Fresnel mix, "
             "metallic mix; `tools/reference/gltf_brdf.py`) instead of the importer's Principled "
             "BSDF, whose Disney diffuse is not glTF's, so the numbers compare rendering, not "
             "material models. The material extensions (showroom) are rebuilt from the file's "
             "values: ior in the Fresnel node, transmission as a Refraction BSDF through the closed "
             "mesh with a Volume Absorption for KHR_materials_volume (a Transparent BSDF tinted by "
             "the base colour where thin-walled), clearcoat as a second GGX layer; Blender 3.4 has "
             "no Charlie sheen, so sheen is a Velvet BSDF added over the base, an approximation: "
             "the velvet cushion's difference is partly the reference's. The later extensions "
             "(extensions): diffuse transmission as a Translucent BSDF mixed into the diffuse base, "
             "anisotropy as Anisotropic BSDFs (GGX, the UV tangent, Cycles' roughness and "
             "anisotropy solved for glTF's two alphas, the texture's strength); Blender 3.4 has "
             "no thin film and no dispersion, so the film sphere and the prism are plain in the "
             "reference and their difference is the reference's. Eevee refracts in screen "
             "space. The reference is Cycles (CPU, no denoiser, box filter 1 px, default "
             "light paths: 12 bounces, 4 of them diffuse, indirect clamp 10; 64 bounces for the two interiors, "
             "the kitchen and the room (cm), which lose 2.6 and 4.8 %% of their light when paths end at the fourth diffuse bounce); the peer is Eevee at %d samples with "
             "soft shadows, GTAO (distance = the scene's occlusion distance) and screen-space "
             "reflections, without a baked light cache (so no indirect diffuse light). A second, "
             "independent Cycles render (another seed, fewer samples) shows what the path tracer "
             "itself reaches in about Penumbra's time, and bounds how much of every error is the "
             "reference's own noise." % (sizes, EEVEE_SAMPLES))
    L.append("")
    L.append("**Metrics** against the Cycles image: RMSE of linear RGB radiance; MAE of the displayed "
             "images (scene exposure, Khronos PBR Neutral, sRGB; 0..1); SSIM (11x11 Gaussian window, "
             "sigma 1.5) on the luminance of the displayed images. The Cycles image carries its own "
             "Monte Carlo noise, so no renderer can reach RMSE 0 / SSIM 1. "
             "The last column (Penumbra only) is the RMSE to Penumbra's own longest render: how far "
             "it still is from what it converges to, apart from its bias.")
    L.append("")
    for name, r in results.items():
        L.append("## %s (%s, exposure %+.1f EV)" % (name, r["size"], r["exposure"]))
        L.append("")
        if r.get("when") and r["when"] != when:
            L.append("Rendered on %s UTC (a later run covered other scenes)." % r["when"])
            L.append("")
        longest = max(f for f in frames if f != "auto")
        L.append("| renderer | frames / samples | time (s) | RMSE linear | MAE tone-mapped | SSIM | RMSE to own %d-frame image |" % longest)
        L.append("|---|---:|---:|---:|---:|---:|---:|")
        for row in r["rows"]:
            if row["renderer"] == "cycles":
                L.append("| Cycles (reference) | %d spp | %.1f | - | - | - | |" % (row["frames"], row["seconds"]))
            else:
                L.append("| %s | %s | %.1f | %.4f | %.4f | %.3f | %s |" % (
                    {"penumbra": "Penumbra", "eevee": "Eevee",
                     "cycles2": "Cycles, independent render"}[row["renderer"]],
                    "%d (auto: converged)" % row["frames"] if row.get("auto") else "%d" % row["frames"],
                    row["seconds"], row["rmse"], row["mae_tm"], row["ssim"],
                    "%.4f" % row["rmse_self"] if "rmse_self" in row else ""))
        L.append("")
        L.append("Mean radiance (linear RGB): Cycles %s, Penumbra %d frames %s, Eevee %s." % (
            fmt_mean(r["ref_mean"]), longest, fmt_mean(r["pen_mean"]), fmt_mean(r["eevee_mean"])))
        L.append("")
        L.append("![%s error versus time](%s_error_time.png)" % (name, name))
        L.append("")
        L.append("![%s: Penumbra 1/16/128 frames, Eevee, Cycles, difference](%s_strip.png)" % (name, name))
        L.append("")
        cmds = r.get("ref_commands") or [r["ref_command"]]
        L.append("Blender renders: " + "; ".join("`%s`" % c for c in cmds))
        L.append("")
    if skipped:
        L.append("Not evaluated (no cached reference): %s." % ", ".join(skipped))
        L.append("")
    notes = os.path.join(os.path.dirname(os.path.abspath(__file__)), "evaluation-notes.md")
    if os.path.exists(notes):
        L.append(open(notes).read().rstrip())
        L.append("")
    unit = unit_check(a)
    if unit:
        L.append(unit)
    with open(os.path.join(a.out, "README.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    print("evaluate: wrote %s" % os.path.join(a.out, "README.md"))
    # The project README's "Where it stands" block, when these are the project's results.
    readme = os.path.join(a.root, "README.md")
    if os.path.abspath(a.out) == os.path.join(os.path.abspath(a.root), "docs", "evaluation"):
        subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                     "readme_table.py"),
                        "--results", os.path.join(a.out, "results.json"), "--readme", readme],
                       check=True)


def unit_check(a):
    d = os.path.join(a.cache, "unit")
    p, c = os.path.join(d, "penumbra.exr"), os.path.join(d, "cycles.exr")
    if not (os.path.exists(p) and os.path.exists(c)):
        return ""
    def centre(path):
        img = read_rgb(path)
        h, w = img.shape[:2]
        return float(img[h // 2 - 4:h // 2 + 4, w // 2 - 4:w // 2 + 4].mean())
    vp, vc = centre(p), centre(c)
    ve = centre(os.path.join(d, "eevee.exr")) if os.path.exists(os.path.join(d, "eevee.exr")) else None
    import math
    A = B = 0.5
    f = 4 * (A / math.sqrt(1 + A * A) * math.atan(B / math.sqrt(1 + A * A))
             + B / math.sqrt(1 + B * B) * math.atan(A / math.sqrt(1 + B * B))) / (2 * math.pi)
    s = ["## Light-unit check", "",
         "A white plane (base colour 1, metallic 0, roughness 1) 1 m under a 1 x 1 m `EXT_lights_area` "
         "rect light of L = 10 nits, black environment; radiance at the point under the light's centre "
         "(mean of the 8 x 8 central pixels of a 64 x 64 image from a camera looking straight down):", "",
         "| | radiance |", "|---|---:|",
         "| Lambert, closed form (L x form factor %.5f) | %.4f |" % (f, 10 * f),
         "| Penumbra (64 frames) | %.4f |" % vp,
         "| Cycles (P = 4 L A = 40 W, 256 spp) | %.4f |" % vc]
    if ve is not None:
        s.append("| Eevee (64 samples) | %.4f |" % ve)
    s += ["", "Penumbra / Cycles = %.4f. Both Blender renders use glTF's BRDF rebuilt from nodes "
          "(`tools/reference/gltf_brdf.py`: Lambert diffuse and a GGX layer mixed by the Fresnel "
          "term at the shading normal), so neither is pure Lambert: the plane keeps 96 %% of the "
          "Lambert value as diffuse and adds a rough specular lobe, which Penumbra's split-sum "
          "albedo scaling and Blender's Fresnel mix weigh slightly differently (percent level); "
          "a unit error would be a factor of 4/pi = 1.27 or pi. Remake: "
          "`/usr/bin/python3 tools/reference/make_unit_scene.py eval-cache/unit && "
          "build/tools/render/penumbra-render eval-cache/unit/unit.json -o eval-cache/unit/penumbra.exr && "
          "tools/reference/render eval-cache/unit/unit.json eval-cache/unit --samples 256`." % (vp / vc), ""]
    sky = [os.path.join(d, "sky_%s.exr" % k) for k in ("penumbra", "cycles", "eevee")]
    if all(os.path.exists(x) for x in sky):
        env = read_rgb(os.path.join(a.root, "assets", "env", "studio_sky.hdr"))
        H, W = env.shape[:2]
        el = np.pi * (0.5 - (np.arange(H) + 0.5) / H)
        wgt = np.maximum(np.sin(el), 0) * np.cos(el) * (np.pi / H) * (2 * np.pi / W)
        lam = (env * wgt[:, None, None]).sum(axis=(0, 1)) / np.pi
        def centre3(path):
            img = read_rgb(path)
            h, w = img.shape[:2]
            return img[h // 2 - 4:h // 2 + 4, w // 2 - 4:w // 2 + 4].mean(axis=(0, 1))
        vals = [centre3(x) for x in sky]
        f3 = lambda v: "(%.3f, %.3f, %.3f)" % tuple(v)
        s += ["Environment energy: the same plane with the light at 0 nits under `studio_sky.hdr` "
              "(`eval-cache/unit/sky.json`), radiance (RGB) at the centre:", "",
              "| | radiance |", "|---|---:|",
              "| Lambert, closed form (irradiance of the panorama / pi) | %s |" % f3(lam),
              "| Penumbra (64 frames) | %s |" % f3(vals[0]),
              "| Cycles (256 spp) | %s |" % f3(vals[1]),
              "| Eevee (64 samples) | %s |" % f3(vals[2]), "",
              "Remake: `build/tools/render/penumbra-render eval-cache/unit/sky.json -o "
              "eval-cache/unit/sky_penumbra.exr && tools/reference/render eval-cache/unit/sky.json "
              "eval-cache/unit --samples 256 --only cycles --name sky_cycles && tools/reference/render "
              "eval-cache/unit/sky.json eval-cache/unit --only eevee --name sky_eevee`.", ""]
    return "\n".join(s)


if __name__ == "__main__":
    main()
