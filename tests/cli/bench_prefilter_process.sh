#!/usr/bin/env bash
# penumbra-bench-prefilter --process keeps working (its figures are read by people, not
# asserted): a small panorama through the whole penumbra-prefilter process prints a time and a
# peak RSS and exits 0; a missing prefilter binary is a one-line error and exit 1.
# Usage: bench_prefilter_process.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail
BENCH="$2/tools/bench-prefilter/penumbra-bench-prefilter"
[ -x "$BENCH" ] || { echo "FAIL: $BENCH not built"; exit 1; }
out=$("$BENCH" --process --repeat 2 --width 64 --size 16 --samples 8 2>&1) || {
  echo "FAIL: exit $?: $out"; exit 1; }
echo "$out"
grep -Eq '^  seconds: best [0-9.]+, median [0-9.]+, mean [0-9.]+ over 2 runs' <<<"$out" || { echo "FAIL: no timing line"; exit 1; }
grep -Eq '^  peak RSS: [0-9.]+ MiB' <<<"$out" || { echo "FAIL: no peak RSS line"; exit 1; }
err=$("$BENCH" --prefilter /nonexistent/penumbra-prefilter --repeat 1 --width 64 --size 16 2>&1)
rc=$?
[ "$rc" = 1 ] || { echo "FAIL: missing binary exited $rc: $err"; exit 1; }
[ "$(grep -c . <<<"$err")" = 1 ] || { echo "FAIL: not one line: $err"; exit 1; }
echo "ok: $err"
