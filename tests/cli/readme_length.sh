#!/usr/bin/env bash
# The README stays short (issue #61): at most 150 lines; dated findings belong in
# docs/decisions/, docs/where-it-stands.md and CHANGELOG.md. No document under docs/ passes 600
# lines either.
# Usage: readme_length.sh <dir of libpenumbra.a> <build dir> (both unused)
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
status=0
lines=$(wc -l < "$ROOT/README.md")
if [ "$lines" -gt 150 ]; then
  echo "FAIL: README.md has $lines lines (at most 150): move dated findings to docs/decisions/ or CHANGELOG.md"
  status=1
else
  echo "ok: README.md has $lines lines"
fi
# "Where it stands" is one generated table of at most 8 lines (tools/reference/readme_table.py,
# from docs/evaluation/results.json): a hand edit or a new evaluation not carried over fails.
if ! python3 "$ROOT/tools/reference/readme_table.py" --check; then
  status=1
fi
while IFS= read -r doc; do
  n=$(wc -l < "$doc")
  if [ "$n" -gt 600 ]; then
    echo "FAIL: ${doc#"$ROOT"/} has $n lines (at most 600): split it by topic"
    status=1
  fi
done < <(find "$ROOT/docs" -name '*.md' -type f)
exit $status
