#!/usr/bin/env bash
# tools/fidelity (issue #60) without Blender: `--no-reference` renders two sample models with
# penumbra-render --batch and writes the table (both rows, finite Penumbra times, empty
# reference columns), the JSON and the contact sheet; without the sample set it says so in one
# line and exits 0. Skipped (exit 77) where ../shared/gltf-sample-assets is absent.
# Usage: fidelity_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
ASSETS="$ROOT/../shared/gltf-sample-assets"
if [ ! -f "$ASSETS/CATALOG.tsv" ]; then
  echo "SKIP: no glTF sample assets at $ASSETS"
  exit 77
fi
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"

OUT="$WORK/out"
if ! "$ROOT/tools/fidelity" --no-reference --models Box,BoxTextured --size 64x48 \
    --render "$TOOL" --assets "$ASSETS" --out "$OUT" >"$WORK/log.txt" 2>&1; then
  cat "$WORK/log.txt"
  fail "tools/fidelity --no-reference exited non-zero"
fi
MD="$OUT/fidelity.md"
[ -f "$MD" ] || fail "no $MD"
[ -f "$OUT/fidelity.json" ] || fail "no fidelity.json"
for m in Box BoxTextured; do
  # | # | model | RMSE | SSIM | noise | mean | Penumbra s | Cycles s | notes |
  row=$(grep -E "^\| [0-9]+ \| $m \|" "$MD")
  [ -n "$row" ] || { fail "no table row for $m"; continue; }
  secs=$(awk -F'|' '{gsub(/ /, "", $8); print $8}' <<<"$row")
  python3 -c 'import math,sys; v=float(sys.argv[1]); sys.exit(0 if math.isfinite(v) and v > 0 else 1)' \
    "$secs" 2>/dev/null || fail "$m: Penumbra seconds '$secs' not a finite positive number"
  rmse=$(awk -F'|' '{gsub(/ /, "", $4); print $4}' <<<"$row")
  [ -z "$rmse" ] || fail "$m: an RMSE ($rmse) without a reference"
  for ext in png exr; do
    [ -s "$OUT/fidelity-work/penumbra/$m.$ext" ] || fail "no Penumbra $ext for $m"
  done
done
[ "$(grep -cE '^\| [0-9]+ \| ' "$MD")" = 2 ] || fail "the table has not exactly 2 rows"
python3 -c '
import json, sys
r = json.load(open(sys.argv[1]))
names = sorted(m["name"] for m in r["models"])
assert names == ["Box", "BoxTextured"], names
assert all(m["penumbra"]["status"] == "ok" for m in r["models"])
assert r["reference"] is False and r["sheets"] == ["fidelity_sheet1.png"]
' "$OUT/fidelity.json" || fail "fidelity.json: unexpected content"
sheet="$OUT/fidelity_sheet1.png"
if [ -s "$sheet" ]; then
  [ "$(head -c 8 "$sheet" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "$sheet is not a PNG"
else
  fail "no contact sheet $sheet"
fi
echo "ok: --no-reference wrote 2 rows, the JSON and $(basename "$sheet")"

# Without the sample set: one line, exit 0.
msg=$(PENUMBRA_SAMPLE_ASSETS="$WORK/none" "$ROOT/tools/fidelity" --no-reference --out "$WORK/skip" 2>&1)
rc=$?
[ "$rc" = 0 ] || fail "without assets: exit $rc, not 0"
[ "$(grep -c . <<<"$msg")" = 1 ] && grep -q "no glTF sample assets" <<<"$msg" ||
  fail "without assets: '$msg' is not one line naming the missing sample set"
[ -e "$WORK/skip/fidelity.md" ] && fail "without assets: a table was written"
echo "ok: without the sample set -> $msg"

finish "fidelity"
