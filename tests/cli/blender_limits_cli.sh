#!/usr/bin/env bash
# tools/blender-limits (issue #60) without Blender: `--no-blender` writes the minimal files and
# renders Penumbra's side of each, failing unless Penumbra honours the feature (four instanced
# copies drawn, the thin film and the sheen change the quad, a KTX2 image named in a warning);
# the KTX2 cases need the sample set's KTX2 image and are left out without it.
# Usage: blender_limits_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/render/penumbra-render"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"

if ! "$ROOT/tools/blender-limits" --no-blender --render "$TOOL" --work "$WORK" >"$WORK/log.txt" 2>&1; then
  fail "tools/blender-limits --no-blender exited non-zero"
fi
cat "$WORK/log.txt"
for c in instancing "thin film" sheen; do
  grep -q "^blender-limits: Penumbra, $c (.*): ok:" "$WORK/log.txt" || fail "no passing line for $c"
done
for f in instancing.gltf iridescence.gltf iridescence_plain.gltf sheen.gltf sheen_plain.gltf; do
  [ -s "$WORK/$f" ] || fail "no $f written"
done

finish "blender_limits"
