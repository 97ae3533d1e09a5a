# Shared by the command-line tests (tests/cli/*.sh), which source it after setting TOOL:
#   fail MESSAGE              counts a failure and prints it
#   expect_fail NAME FRAGMENT ARGS...
#                             runs "$TOOL" ARGS: a non-zero exit and one line on stderr that
#                             contains FRAGMENT
#   finish NAME               exits 1 after any failure, else says that NAME passed
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

expect_fail() {
  local name="$1" fragment="$2"
  shift 2
  local err
  if err=$("$TOOL" "$@" 2>&1 >/dev/null); then
    fail "$name: exited 0"
    return
  fi
  if ! grep -qF -- "$fragment" <<<"$err"; then fail "$name: message '$err' lacks '$fragment'"; fi
  local lines
  lines=$(grep -c . <<<"$err")
  if [ "$lines" != 1 ]; then fail "$name: $lines lines of error output: $err"; fi
  echo "ok: $name -> $err"
}

finish() {
  if [ "$failures" -ne 0 ]; then
    echo "$failures failure(s)"
    exit 1
  fi
  echo "all $1 checks passed"
}
