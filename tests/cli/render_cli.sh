#!/usr/bin/env bash
# penumbra-render on the command line: bad input exits non-zero with a one-line message and
# writes nothing; normal runs write PNG and EXR, intermediate frames and a contact sheet; an
# existing output is never clobbered by a failed run.
# Usage: render_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
CORNELL="$ROOT/assets/cornell_box/cornell_box.json"
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"

printf '{"gltf": "nope.gltf"' >"$WORK/truncated.json"
printf 'glTF\x02\x00\x00\x00\x10\x00\x00\x00' >"$WORK/short.glb"
printf 'NOPE\x02\x00\x00\x00\x10\x00\x00\x00xxxx' >"$WORK/magic.glb"
echo '{"gltf": "missing.gltf"}' >"$WORK/missing-model.json"

expect_fail "missing scene file" "no such file" "$WORK/none.gltf" -o "$WORK/a.png"
expect_fail "truncated scene JSON" "not valid JSON" "$WORK/truncated.json" -o "$WORK/a.png"
expect_fail "model named by the scene file is missing" "missing.gltf" "$WORK/missing-model.json" -o "$WORK/a.png"
expect_fail "truncated glb" "short.glb" "$WORK/short.glb" -o "$WORK/a.png"
expect_fail "wrong glb magic" "magic.glb" "$WORK/magic.glb" -o "$WORK/a.png"
expect_fail "bad size" "--size" "$CORNELL" -o "$WORK/a.png" --size 12by4
expect_fail "absurd size" "invalid setting: width 100000" "$CORNELL" -o "$WORK/a.png" --size 100000x10
expect_fail "zero frames" "frames" "$CORNELL" -o "$WORK/a.png" --frames 0
expect_fail "too many frames" "frames" "$CORNELL" -o "$WORK/a.png" --frames 5000
expect_fail "bad tone mapper" "tone mapper" "$CORNELL" -o "$WORK/a.png" --tonemap filmic
expect_fail "bad GL backend" "GL backend" "$CORNELL" -o "$WORK/a.png" --gl vulkan
expect_fail "unknown camera" "camera" "$CORNELL" -o "$WORK/a.png" --camera nosuchcam
expect_fail "missing environment" "nope.hdr" "$CORNELL" -o "$WORK/a.png" --env "$WORK/nope.hdr"
expect_fail "output folder missing" "does not exist" "$CORNELL" -o "$WORK/no/dir/a.png"
expect_fail "output format" ".png, .exr" "$CORNELL" -o "$WORK/a.jpg"
expect_fail "bad shadow size" "shadowMapSize 1000 (must be a power of two" "$CORNELL" -o "$WORK/a.png" --shadow-size 1000
[ -e "$WORK/a.png" ] && fail "a failed run wrote an output"

# Normal runs.
if "$TOOL" "$CORNELL" -o "$WORK/cb.png" --size 48x48 --frames 8 --save-every 4 \
    --contact-sheet "$WORK/sheet.png" -q; then
  for f in cb.png cb_f0004.png cb_f0008.png sheet.png; do
    [ -s "$WORK/$f" ] || fail "normal run did not write $f"
  done
else
  fail "normal PNG run exited non-zero"
fi
"$TOOL" "$CORNELL" -o "$WORK/cb.exr" --size 32x32 --frames 4 -q --gl osmesa || fail "EXR run (osmesa)"
[ -s "$WORK/cb.exr" ] || fail "EXR not written"
ls "$WORK" | grep -q tmp && fail "temporary files left behind"

# A failed run keeps an output written before.
cp "$WORK/cb.png" "$WORK/keep.png"
"$TOOL" "$CORNELL" -o "$WORK/keep.png" --frames 0 2>/dev/null && fail "frames 0 accepted"
cmp -s "$WORK/cb.png" "$WORK/keep.png" || fail "a failed run changed an existing output"

# Every setting of the schema has its flag (penumbra/settings.h), --env its forms.
help=$("$TOOL" --help)
for flag in --exposure --tonemap --env-intensity --env-rotation --no-background --background-blur \
    --frames --fd --occlusion-distance --light-samples --shadow-size --no-ssgi --indirect-clamp \
    --sky-shadows --no-gi --probe-density --probes-per-frame --seed --env --camera --size \
    --memory-budget; do
  grep -q -- "$flag" <<<"$help" || fail "--help lacks $flag"
done
expect_fail "bad environment" "expected none, studio" "$CORNELL" -o "$WORK/a.png" --env 1,2
for env in none studio 0.2,0.3,0.4; do
  out=$("$TOOL" "$CORNELL" -o "$WORK/env.png" --size 16x16 --frames 2 --shadow-size 64 --info \
        --env "$env" 2>&1) || fail "--env $env exited non-zero"
  label=$env
  [ "$env" = 0.2,0.3,0.4 ] && label="uniform(0.2, 0.3, 0.4)"
  grep -qF "environment: $label" <<<"$out" || fail "--env $env: the log does not say 'environment: $label'"
done
# --sky-shadows is a switch (no value) that turns them on: the image changes (without the probe
# volume, whose light already carries the sky's visibility). --no-gi changes it too.
GLASS="$ROOT/assets/glass/glass.json"
"$TOOL" "$GLASS" -o "$WORK/gi.png" --size 32x18 --frames 6 --shadow-size 128 -q || fail "glass run"
"$TOOL" "$GLASS" -o "$WORK/nosky.png" --size 32x18 --frames 6 --shadow-size 128 -q --no-gi ||
  fail "--no-gi run"
cmp -s "$WORK/gi.png" "$WORK/nosky.png" && fail "--no-gi changed nothing"
"$TOOL" "$GLASS" -o "$WORK/sky.png" --size 32x18 --frames 6 --shadow-size 128 -q --no-gi \
  --sky-shadows || fail "--sky-shadows run"
cmp -s "$WORK/nosky.png" "$WORK/sky.png" && fail "--sky-shadows changed nothing"
# A bare model with lights gets a black world, one without gets the studio.
out=$("$TOOL" "$ROOT/assets/cornell_box/cornell_box.gltf" -o "$WORK/bare.png" --size 16x16 \
      --frames 2 --shadow-size 64 --info 2>&1) || fail "bare Cornell box exited non-zero"
grep -qF "environment: none" <<<"$out" || fail "a scene with lights did not default to no environment"

finish "render CLI"
