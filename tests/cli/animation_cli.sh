#!/usr/bin/env bash
# Animated glTF on the command line: --animation NAME --time T poses the model (a still that
# converges like any other); a --batch line with "times" or "fps" and "count" renders the
# sequence in one process, each image the same bytes as a single --time render (all framed at
# rest, so the camera holds still); misuse is a one-line error. The model is made here: a box
# whose node slides along +X over 2 s (LINEAR) under a studio environment.
# Usage: animation_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"
mkdir -p "$WORK/seq" "$WORK/single"

python3 - "$WORK/slide.gltf" <<'PY'
import base64, json, struct, sys
# A unit box (12 triangles) and the animation's key times and translations.
p = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
idx = [i for a, b, c, d in faces for i in (a, b, c, a, c, d)]
blob = b"".join(struct.pack("<3f", *v) for v in p) + struct.pack("<36H", *idx)
times, moves = [0.0, 2.0], [(-1.5, 0.0, 0.0), (1.5, 0.0, 0.0)]
anim = struct.pack("<2f", *times) + b"".join(struct.pack("<3f", *m) for m in moves)
data = blob + anim
doc = {
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": len(data),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 96},
                    {"buffer": 0, "byteOffset": 96, "byteLength": 72},
                    {"buffer": 0, "byteOffset": 168, "byteLength": 8},
                    {"buffer": 0, "byteOffset": 176, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 1]},
                  {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
                  {"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR",
                   "min": [0], "max": [2]},
                  {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "nodes": [{"name": "box", "mesh": 0}],
    "scenes": [{"nodes": [0]}], "scene": 0,
    "animations": [{"name": "slide", "samplers": [{"input": 2, "output": 3}],
                    "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}]}],
}
json.dump(doc, open(sys.argv[1], "w"))
PY
M="$WORK/slide.gltf"
COMMON=(--size 48x36 --frames 4 --shadow-size 64 --env studio -q)

# Two times give two pictures; a time alone takes the first animation.
"$TOOL" "$M" -o "$WORK/single/t0.png" --animation slide --time 0 "${COMMON[@]}" || fail "--time 0"
"$TOOL" "$M" -o "$WORK/single/t1.png" --time 1.5 "${COMMON[@]}" || fail "--time 1.5"
cmp -s "$WORK/single/t0.png" "$WORK/single/t1.png" && fail "the box did not move between 0 and 1.5 s"

# The sequence in one process: the same bytes as each single render.
cat >"$WORK/jobs.jsonl" <<EOF
{"scene": "$M", "output": "$WORK/seq/slide.png", "animation": "slide", "times": [0, 1.5], "size": "48x36", "frames": 4, "shadow-size": 64, "env": "studio"}
{"scene": "$M", "output": "$WORK/seq/fps_####.png", "fps": 4, "count": 3, "size": "48x36", "frames": 4, "shadow-size": 64, "env": "studio"}
EOF
if ! "$TOOL" --batch "$WORK/jobs.jsonl" -q; then fail "the sequence batch failed"; fi
cmp -s "$WORK/seq/slide_0000.png" "$WORK/single/t0.png" || fail "sequence time 0 differs from --time 0"
cmp -s "$WORK/seq/slide_0001.png" "$WORK/single/t1.png" || fail "sequence time 1.5 differs from --time 1.5"
for i in 0000 0001 0002; do [ -s "$WORK/seq/fps_$i.png" ] || fail "fps sequence: fps_$i.png missing"; done
n=$(grep -c '"time"' "$WORK/jobs.results.jsonl")
[ "$n" = 5 ] || fail "results: $n lines with a time (expected 5)"

expect_fail "unknown animation" "no animation 'jump'; available: 0: 'slide'" "$M" -o "$WORK/x.png" --animation jump
expect_fail "time on a still model" "the file has none" "$ROOT/assets/cornell_box/cornell_box.gltf" -o "$WORK/x.png" --time 1
finish "animation"
