#!/usr/bin/env bash
# penumbra-oracle on the command line: a small run prints the oracle and the stop side by side
# (the stop at or after a frame where the picture is acceptable), writes the reference and stop
# images; bad input exits non-zero with a one-line message.
# Usage: oracle_cli.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail

TOOL="$2/tools/oracle/penumbra-oracle"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
CORNELL="$ROOT/assets/cornell_box/cornell_box.json"
[ -x "$TOOL" ] || { echo "FAIL: $TOOL not built"; exit 1; }
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
. "$ROOT/tests/support/cli_checks.sh"

expect_fail "missing scene" "no such file" --scene "$WORK/none.gltf" --size 32x32 --frames 16
expect_fail "bad size" "bad size" --scene "$CORNELL" --size 12by4
expect_fail "bad --set" "KEY=VALUE" --scene "$CORNELL" --size 32x32 --set frames

# 64x36, 64 frames: seconds. The row: scene | oracle | stop | ratio | ... (markdown).
if ! out=$("$TOOL" --scene "$CORNELL" --size 64x36 --frames 64 --images "$WORK" 2>&1); then
  fail "small run exited non-zero: $out"
else
  echo "$out"
  row=$(grep '^| cornell_box.json |' <<<"$out")
  oracle=$(cut -d'|' -f3 <<<"$row" | tr -d ' ')
  stop=$(cut -d'|' -f4 <<<"$row" | tr -d ' ')
  if ! [[ "$oracle" =~ ^[0-9]+$ && "$stop" =~ ^[0-9]+$ ]]; then
    fail "no oracle and stop in '$row'"
  elif [ "$oracle" -lt 1 ] || [ "$oracle" -gt 64 ] || [ "$stop" -lt 1 ] || [ "$stop" -gt 64 ]; then
    fail "oracle $oracle and stop $stop outside 1..64"
  fi
  for f in cornell_box.json_reference.png cornell_box.json_stop.png; do
    [ -s "$WORK/$f" ] || fail "no $f written"
  done
fi
finish "penumbra-oracle"
