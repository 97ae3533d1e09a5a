#!/usr/bin/env bash
# Files a reader can hold (issue #61): no shader over 250 lines (one program per output, sharing
# chunks: glsl/chunks/lighting_common.glsl), no C++ source or header and no web module over 600,
# no document over 600 (docs/, split by topic as docs/web/ is).
# Usage: file_lengths.sh <dir of libpenumbra.a> <build dir> (both unused)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
status=0
check() {  # limit, what, then find's arguments
  local limit=$1 what=$2 count=0 n file
  shift 2
  while IFS= read -r file; do
    count=$((count + 1))
    n=$(wc -l < "$file")
    if [ "$n" -gt "$limit" ]; then
      echo "FAIL: ${file#"$ROOT"/} has $n lines (at most $limit): split it"
      status=1
    fi
  done < <(find "$@" -type f)
  if [ "$count" -eq 0 ]; then
    echo "FAIL: no $what found"
    status=1
  else
    echo "checked $count $what (at most $limit lines each)"
  fi
}
check 250 "shader files" "$ROOT/glsl" \( -name '*.glsl' -o -name '*.frag' -o -name '*.vert' \)
check 600 "C++ files" "$ROOT/renderer" "$ROOT/tools" "$ROOT/web/src" "$ROOT/tests" \
  \( -name '*.cpp' -o -name '*.h' \)
check 599 "web modules" "$ROOT/web/lib" -maxdepth 1 -name '*.mjs'
check 600 "documents" "$ROOT/docs" "$ROOT/README.md" "$ROOT/CHANGELOG.md" -name '*.md'
exit $status
