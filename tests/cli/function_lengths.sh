#!/usr/bin/env bash
# The kitchen's rule (issue #37): no function in renderer/src longer than 120 lines, none in
# glsl/ longer than 100 (tools/function-lengths).
# Usage (ctest): bash tests/cli/function_lengths.sh <libdir> <builddir>  (both unused)
set -u
src="${PENUMBRA_SOURCE_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
if ! python3 "$src/tools/function-lengths" --limit 120 --top 3 "$src/renderer/src"; then
  echo "FAIL: a function in renderer/src is longer than 120 lines (split it)"
  exit 1
fi
if ! python3 "$src/tools/function-lengths" --limit 100 --top 3 "$src/glsl"; then
  echo "FAIL: a function in glsl/ is longer than 100 lines (split it)"
  exit 1
fi
echo "PASS: no function in renderer/src over 120 lines, none in glsl/ over 100"
