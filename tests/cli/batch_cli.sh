#!/usr/bin/env bash
# penumbra-render --batch: every job of the file renders in one process, each image the same
# bytes as a process of its own would write; a broken job is recorded as failed and the others
# finish; the results file has one JSON line per job; a job's "variant" renders as --variant; a
# rerun skips outputs that exist (--force renders them again); shards split the jobs round
# robin; the command line's options apply under each line's; misuse is a one-line error.
# Usage: batch_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
A="$ROOT/assets"
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"
mkdir -p "$WORK/out" "$WORK/single" "$WORK/shard"

# field FILE N KEY: KEY of the N-th (1-based) results line.
field() {
  python3 -c 'import json,sys; print(json.loads(open(sys.argv[1]).read().splitlines()[int(sys.argv[2])-1]).get(sys.argv[3], ""))' "$@"
}
statuses() {
  python3 -c 'import json,sys; print(" ".join(json.loads(l)["status"] for l in open(sys.argv[1])))' "$1"
}

JOBS="$WORK/jobs.jsonl"
cat >"$JOBS" <<EOF
{"scene": "$A/cornell_box/cornell_box.json", "output": "$WORK/out/cornell.png", "size": "64x48", "frames": 8}
{"scene": "$A/material_grid/material_grid.json", "output": "$WORK/out/grid.png", "size": [64, 48], "frames": 8}

{"scene": "$WORK/missing.gltf", "output": "$WORK/out/missing.png"}
{"scene": "$A/cornell_box/cornell_box.gltf", "output": "$WORK/out/cornell-studio.png", "size": "48x32", "frames": 4, "env": "studio"}
not json
{"scene": "$A/glass/glass.json", "output": "$WORK/out/glass.png", "size": "48x48", "frames": 6, "tonemap": "aces"}
EOF

"$TOOL" --batch "$JOBS" -q 2>"$WORK/err.txt"
rc=$?
[ "$rc" = 1 ] || fail "a batch with failing jobs exited $rc, not 1"
RESULTS="$WORK/jobs.results.jsonl"
[ -f "$RESULTS" ] || fail "no results file $RESULTS"
[ "$(statuses "$RESULTS")" = "ok ok failed ok failed ok" ] ||
  fail "statuses: $(statuses "$RESULTS")"
[ "$(field "$RESULTS" 3 line)" = 4 ] || fail "the missing scene's line is $(field "$RESULTS" 3 line)"
field "$RESULTS" 3 error | grep -q "missing.gltf" || fail "the missing scene's error: $(field "$RESULTS" 3 error)"
field "$RESULTS" 5 error | grep -q "line 6: not valid JSON" || fail "bad line's error: $(field "$RESULTS" 5 error)"
[ "$(field "$RESULTS" 1 frames)" = 8 ] || fail "cornell frames: $(field "$RESULTS" 1 frames)"
[ -f "$WORK/out/missing.png" ] && fail "a failed job wrote an image"
echo "ok: batch of 6 -> $(statuses "$RESULTS")"

# The same bytes as one process per job.
single() { "$TOOL" -q "$@" || fail "single render $* failed"; }
single "$A/cornell_box/cornell_box.json" -o "$WORK/single/cornell.png" --size 64x48 --frames 8
single "$A/material_grid/material_grid.json" -o "$WORK/single/grid.png" --size 64x48 --frames 8
single "$A/cornell_box/cornell_box.gltf" -o "$WORK/single/cornell-studio.png" --size 48x32 \
  --frames 4 --env studio
single "$A/glass/glass.json" -o "$WORK/single/glass.png" --size 48x48 --frames 6 --tonemap aces
for f in cornell grid cornell-studio glass; do
  if cmp -s "$WORK/out/$f.png" "$WORK/single/$f.png"; then
    echo "ok: $f.png from the batch is the single render's"
  else
    fail "$f.png from the batch differs from a process of its own"
  fi
done

# A job's "variant" (KHR_materials_variants) as --variant: the material grid with a variant that
# moves every sphere's material.
mkdir -p "$WORK/variants"
cp "$A/material_grid/material_grid.bin" "$WORK/variants/"
python3 - "$A/material_grid/material_grid.gltf" "$WORK/variants/grid.gltf" <<'EOF2'
import json, sys
doc = json.load(open(sys.argv[1]))
n = len(doc["materials"])
doc.setdefault("extensionsUsed", []).append("KHR_materials_variants")
doc.setdefault("extensions", {})["KHR_materials_variants"] = {"variants": [{"name": "shifted"}]}
for mesh in doc["meshes"]:
    for p in mesh["primitives"]:
        p.setdefault("extensions", {})["KHR_materials_variants"] = {
            "mappings": [{"material": (p.get("material", 0) + 12) % n, "variants": [0]}]}
json.dump(doc, open(sys.argv[2], "w"))
EOF2
echo "{\"scene\": \"$WORK/variants/grid.gltf\", \"output\": \"$WORK/variants/batch.png\", \"size\": \"48x32\", \"frames\": 4, \"variant\": \"shifted\"}" >"$WORK/variant.jsonl"
"$TOOL" --batch "$WORK/variant.jsonl" -q || fail "the variant batch failed"
single "$WORK/variants/grid.gltf" -o "$WORK/variants/single.png" --size 48x32 --frames 4 --variant shifted
single "$WORK/variants/grid.gltf" -o "$WORK/variants/default.png" --size 48x32 --frames 4
cmp -s "$WORK/variants/batch.png" "$WORK/variants/single.png" ||
  fail "a batch job's variant differs from --variant"
cmp -s "$WORK/variants/batch.png" "$WORK/variants/default.png" &&
  fail "a batch job's variant is the default materials"
echo "ok: a job's \"variant\" renders as --variant does"

# A rerun skips what exists; --force renders again.
before=$(stat -c %Y.%s "$WORK/out/grid.png")
sleep 1
"$TOOL" --batch "$JOBS" -q 2>/dev/null
[ "$(statuses "$RESULTS")" = "skipped skipped failed skipped failed skipped" ] ||
  fail "rerun statuses: $(statuses "$RESULTS")"
[ "$(stat -c %Y.%s "$WORK/out/grid.png")" = "$before" ] || fail "the rerun rewrote grid.png"
"$TOOL" --batch "$JOBS" -q --force --results "$WORK/forced.jsonl" 2>/dev/null
[ "$(statuses "$WORK/forced.jsonl")" = "ok ok failed ok failed ok" ] ||
  fail "--force statuses: $(statuses "$WORK/forced.jsonl")"
echo "ok: rerun skipped, --force rendered again"

# Shards, and the command line's options under each line's (frames 5 unless a line says).
cat >"$WORK/four.jsonl" <<EOF
{"scene": "$A/cornell_box/cornell_box.json", "output": "$WORK/shard/a.png"}
{"scene": "$A/cornell_box/cornell_box.json", "output": "$WORK/shard/b.png", "frames": 3}
{"scene": "$A/cornell_box/cornell_box.json", "output": "$WORK/shard/c.png"}
{"scene": "$A/cornell_box/cornell_box.json", "output": "$WORK/shard/d.png"}
EOF
for i in 0 1; do
  "$TOOL" --batch "$WORK/four.jsonl" --shard "$i/2" --size 32x24 --frames 5 -q ||
    fail "shard $i/2 failed"
done
[ "$(ls "$WORK/shard" | tr '\n' ' ')" = "a.png b.png c.png d.png " ] ||
  fail "shard outputs: $(ls "$WORK/shard" | tr '\n' ' ')"
S0="$WORK/four.results.0-of-2.jsonl" S1="$WORK/four.results.1-of-2.jsonl"
[ "$(field "$S0" 1 line) $(field "$S0" 2 line)" = "1 3" ] || fail "shard 0 took lines $(field "$S0" 1 line) $(field "$S0" 2 line)"
[ "$(field "$S1" 1 line) $(field "$S1" 2 line)" = "2 4" ] || fail "shard 1 took lines $(field "$S1" 1 line) $(field "$S1" 2 line)"
[ "$(field "$S0" 1 frames) $(field "$S1" 1 frames)" = "5 3" ] ||
  fail "frames from the command line under the line's: $(field "$S0" 1 frames) $(field "$S1" 1 frames)"
[ "$(field "$S0" 1 size)" = "[32, 24]" ] || fail "size from the command line: $(field "$S0" 1 size)"
echo "ok: shards 0/2 and 1/2 rendered lines 1 3 and 2 4"

# Misuse: one line on stderr, non-zero.
expect_fail "missing job file" "cannot read job file" --batch "$WORK/none.jsonl"
expect_fail "batch and a scene" "no scene or -o" --batch "$JOBS" "$A/cornell_box/cornell_box.json"
expect_fail "bad shard" "--shard must be I/N" --batch "$JOBS" --shard 2/2
expect_fail "shard without batch" "apply to --batch only" "$A/cornell_box/cornell_box.json" \
  -o "$WORK/x.png" --shard 0/2
expect_fail "no scene at all" "give a scene and -o"
expect_fail "results folder missing" "cannot write results file" --batch "$JOBS" \
  --results "$WORK/nope/r.jsonl"

finish "batch"
