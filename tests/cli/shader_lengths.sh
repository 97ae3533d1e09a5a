#!/usr/bin/env bash
# No shader file over 250 lines (issue #61): one program per output, sharing chunks
# (glsl/chunks/lighting_common.glsl), so a new feature lands in a file a reader can hold.
# Usage: shader_lengths.sh <dir of libpenumbra.a> <build dir> (both unused)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
status=0
count=0
while IFS= read -r file; do
  count=$((count + 1))
  n=$(wc -l < "$file")
  if [ "$n" -gt 250 ]; then
    echo "FAIL: ${file#"$ROOT"/} has $n lines (at most 250): split it into chunks or programs"
    status=1
  fi
done < <(find "$ROOT/glsl" -type f \( -name '*.glsl' -o -name '*.frag' -o -name '*.vert' \))
if [ "$count" -eq 0 ]; then
  echo "FAIL: no shader files under glsl/"
  exit 1
fi
[ "$status" -eq 0 ] && echo "ok: $count shader files, none over 250 lines"
exit $status
