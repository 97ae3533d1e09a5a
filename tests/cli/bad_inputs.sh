#!/usr/bin/env bash
# The bad-input catalogue (tests/bad-inputs/cases.tsv, docs/bad-inputs.md) through the real
# command-line tools: every refusal exits with the expected status and exactly one stderr line
# "penumbra-<tool>: error: ..." containing the expected fragment; every graceful fallback exits
# 0 with the documented warning (or none) and writes its output.
# Usage: bad_inputs.sh <dir of libpenumbra.a> <build dir>
set -uo pipefail
BUILD="$(cd "$2" && pwd)"
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
declare -A TOOLS=([render]="$BUILD/tools/render/penumbra-render"
                  [prefilter]="$BUILD/tools/prefilter/penumbra-prefilter")
for t in "${TOOLS[@]}"; do [ -x "$t" ] || { echo "FAIL: $t not built"; exit 1; }; done
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
W="$WORK/in"
python3 "$ROOT/tests/bad-inputs/generate.py" "$W" || { echo "FAIL: generate.py"; exit 1; }
failures=0
cases=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

while IFS=$'\t' read -r id tool want fragment args; do
  [[ -z "$id" || "$id" == \#* ]] && continue
  cases=$((cases + 1))
  O="$WORK/out-$id"
  mkdir -p "$O"
  args="${args//\$W/$W}"
  args="${args//\$A/$ROOT/assets}"
  args="${args//\$O/$O}"
  read -r -a argv <<<"$args"
  err=$(cd "$W" && timeout 120 "${TOOLS[$tool]}" "${argv[@]}" 2>&1 >/dev/null)
  rc=$?
  if [ "$rc" != "$want" ]; then fail "$id: exit $rc, expected $want: $err"; continue; fi
  if [ "$fragment" != "-" ] && ! grep -qF -- "$fragment" <<<"$err"; then
    fail "$id: output '$err' lacks '$fragment'"; continue
  fi
  if [ "$want" != 0 ]; then
    lines=$(grep -c . <<<"$err")
    [ "$lines" = 1 ] || { fail "$id: $lines lines of error output: $err"; continue; }
    grep -q "^penumbra-$tool: error: " <<<"$err" || { fail "$id: not an error line: $err"; continue; }
    [ -z "$(find "$O" -type f)" ] || { fail "$id: a refused run wrote files: $(find "$O" -type f)"; continue; }
  else
    grep -q ": error:" <<<"$err" && { fail "$id: exit 0 but printed an error: $err"; continue; }
    if [ "$fragment" = "-" ] && grep -q ": warning:" <<<"$err"; then
      fail "$id: unexpected warning: $err"; continue
    fi
    [ -n "$(find "$O" -type f)" ] || { fail "$id: exit 0 but wrote nothing"; continue; }
  fi
  echo "ok: $id -> $(grep -v ' frames at ' <<<"$err" | head -1)"
done <"$ROOT/tests/bad-inputs/cases.tsv"

[ "$cases" -ge 25 ] || fail "only $cases cases in cases.tsv"
if [ "$failures" -gt 0 ]; then echo "$failures of $cases bad-input case(s) failed"; exit 1; fi
echo "all $cases bad-input cases passed"
