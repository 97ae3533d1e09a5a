#!/usr/bin/env bash
# penumbra-prefilter on the command line: every kind of bad input exits non-zero with its own
# one-line message; NaN/Inf/negative pixels are clamped with one warning line; normal runs
# write the documented files and leave no temporary files behind.
# Usage: prefilter_bad_input.sh <dir of libpenumbra.a> <build dir>
set -euo pipefail

BUILD_DIR="$2"
TOOL="$BUILD_DIR/tools/prefilter/penumbra-prefilter"
if [ ! -x "$TOOL" ]; then
  echo "FAIL: $TOOL not built" >&2
  exit 1
fi
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
failures=0

# Inputs: Portable Float Maps (Penumbra reads them; they can hold NaN, Inf and negatives).
python3 - "$WORK" <<'EOF'
import struct, sys
work = sys.argv[1]
def pfm(name, w, h, pixel):
    with open(f"{work}/{name}", "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (w, h))
        for y in range(h):
            for x in range(w):
                f.write(struct.pack("<3f", *pixel(x, y)))
pfm("pano.pfm", 64, 32, lambda x, y: (0.2 + x / 64.0, 0.5, 1.0 + y / 32.0))
pfm("wide.pfm", 20, 14, lambda x, y: (1.0, 1.0, 1.0))
bad = {(1, 1): (float("nan"), 1.0, 1.0), (2, 2): (float("inf"), 1.0, 1.0),
       (3, 3): (-1.0, 1.0, 1.0)}
pfm("nan.pfm", 32, 16, lambda x, y: bad.get((x, y), (1.0, 1.0, 1.0)))
open(f"{work}/garbage.hdr", "wb").write(b"#?RADIANCE\nthis is not an image\n")
open(f"{work}/a-file", "w").write("not a folder")
EOF

# expect_fail NAME EXPECTED-MESSAGE-FRAGMENT ARGS...
expect_fail() {
  local name="$1" fragment="$2"
  shift 2
  local status=0
  "$TOOL" "$@" >"$WORK/out.txt" 2>"$WORK/err.txt" || status=$?
  local lines
  lines=$(wc -l <"$WORK/err.txt")
  if [ "$status" -eq 0 ]; then
    echo "FAIL [$name]: exit status 0, expected an error" >&2
    failures=$((failures + 1))
  elif ! grep -qF -- "$fragment" "$WORK/err.txt"; then
    echo "FAIL [$name]: stderr lacks '$fragment':" >&2
    cat "$WORK/err.txt" >&2
    failures=$((failures + 1))
  elif [ "$lines" -ne 1 ]; then
    echo "FAIL [$name]: expected one line on stderr, got $lines" >&2
    cat "$WORK/err.txt" >&2
    failures=$((failures + 1))
  else
    echo "ok   [$name] exit $status: $(cat "$WORK/err.txt")"
  fi
}

expect_fail missing-file "cannot read '$WORK/nope.hdr': no such file" "$WORK/nope.hdr" -o "$WORK/o1"
expect_fail unreadable-file "cannot read '$WORK/garbage.hdr'" "$WORK/garbage.hdr" -o "$WORK/o2"
expect_fail not-2-to-1 "expected a 2:1 equirectangular panorama, got 20x14" "$WORK/wide.pfm" -o "$WORK/o3"
expect_fail size-not-pow2 "--size must be a power of two between 4 and 4096, got 300" \
  "$WORK/pano.pfm" -o "$WORK/o4" --size 300
expect_fail size-too-small "--size must be a power of two" "$WORK/pano.pfm" -o "$WORK/o5" --size 2
expect_fail bad-samples "--samples must be between" "$WORK/pano.pfm" -o "$WORK/o6" --samples 0
expect_fail unwritable-output "cannot write to output folder '$WORK/a-file/out'" \
  "$WORK/pano.pfm" -o "$WORK/a-file/out"
expect_fail bad-format "--format" "$WORK/pano.pfm" -o "$WORK/o7" --format jpeg
expect_fail no-output "--output" "$WORK/pano.pfm"

# NaN / Inf / negative pixels: clamped, counted in one warning line, still a success.
if "$TOOL" "$WORK/nan.pfm" -o "$WORK/nan" --size 8 --samples 8 --lut-size 8 -q 2>"$WORK/err.txt"; then
  if grep -q "warning: .*nan.pfm: replaced 3 of .* pixels (1 NaN, 1 infinite, 1 negative" "$WORK/err.txt" &&
     [ "$(wc -l <"$WORK/err.txt")" -eq 1 ]; then
    echo "ok   [nan-inf-negative] $(cat "$WORK/err.txt")"
  else
    echo "FAIL [nan-inf-negative]: unexpected stderr:" >&2
    cat "$WORK/err.txt" >&2
    failures=$((failures + 1))
  fi
else
  echo "FAIL [nan-inf-negative]: non-zero exit" >&2
  failures=$((failures + 1))
fi

# --gpu without any usable GL context falls back to the CPU path with a warning.
if PENUMBRA_GL=none "$TOOL" "$WORK/pano.pfm" -o "$WORK/gpu-fallback" --size 8 --samples 8 --lut-size 8 --gpu -q 2>"$WORK/err.txt" &&
   grep -q "no GL context for --gpu" "$WORK/err.txt"; then
  echo "ok   [gpu-fallback]"
else
  echo "FAIL [gpu-fallback]" >&2
  cat "$WORK/err.txt" >&2
  failures=$((failures + 1))
fi

# The default run writes the packed environment and its manifest, nothing else.
if "$TOOL" "$WORK/pano.pfm" -o "$WORK/default" --size 16 --samples 16 -q 2>"$WORK/err.txt"; then
  got=$(cd "$WORK/default" && find . -type f | sort | tr '\n' ' ')
  if [ "$got" = "./environment.hdr ./environment.json " ]; then
    echo "ok   [default-outputs]"
  else
    echo "FAIL [default-outputs]: wrote $got" >&2
    failures=$((failures + 1))
  fi
else
  echo "FAIL [default-outputs]: non-zero exit" >&2
  cat "$WORK/err.txt" >&2
  failures=$((failures + 1))
fi

# A normal run with every output format.
OUT="$WORK/all"
if ! "$TOOL" "$WORK/pano.pfm" -o "$OUT" --size 16 --samples 16 --lut-size 16 --format all --threads 2 \
     >"$WORK/out.txt" 2>"$WORK/err.txt"; then
  echo "FAIL [normal-run]: non-zero exit" >&2
  cat "$WORK/err.txt" >&2
  failures=$((failures + 1))
else
  expected=(environment.hdr environment.json environment.ktx2 brdf_lut.exr brdf_lut.png sh.json
            preview/mip0.png preview/mip1.png preview/mip2.png)
  for m in 0 1 2; do
    for f in px nx py ny pz nz; do
      for ext in exr hdr png; do expected+=("faces/mip${m}_${f}.${ext}"); done
    done
  done
  missing=0
  for f in "${expected[@]}"; do
    if [ ! -s "$OUT/$f" ]; then
      echo "FAIL [normal-run]: missing $OUT/$f" >&2
      missing=1
    fi
  done
  if [ -e "$OUT/faces/mip3_px.exr" ]; then
    echo "FAIL [normal-run]: a 16-pixel chain should stop at 4-pixel faces (mip 2)" >&2
    missing=1
  fi
  leftovers=$(find "$OUT" -name '*.tmp-*' -o -name '.penumbra-write-test*' | wc -l)
  if [ "$leftovers" -ne 0 ]; then
    echo "FAIL [normal-run]: temporary files left behind" >&2
    missing=1
  fi
  if ! head -c 4096 "$OUT/environment.hdr" | grep -qa '^PENUMBRA_ENV={"format":"penumbra-packed-environment"'; then
    echo "FAIL [normal-run]: environment.hdr lacks the PENUMBRA_ENV header line" >&2
    missing=1
  fi
  if ! python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['faceSize']==16 and j['mipCount']==3 and len(j['sh']['coefficients'])==9" "$OUT/environment.json"; then
    echo "FAIL [normal-run]: environment.json is not the expected manifest" >&2
    missing=1
  fi
  if [ "$missing" -eq 0 ]; then
    echo "ok   [normal-run] $(tail -n 1 "$WORK/out.txt")"
  else
    failures=$((failures + 1))
  fi
fi

# The GPU path (forced) writes the same packed file layout and says which path ran.
if "$TOOL" "$WORK/pano.pfm" -o "$WORK/gpu" --size 16 --samples 32 --gpu >"$WORK/gpu.txt" 2>&1 &&
    [ -s "$WORK/gpu/environment.hdr" ] && grep -q "GPU path" "$WORK/gpu.txt"; then
  echo "ok   [gpu-run]"
else
  echo "FAIL [gpu-run]: $(cat "$WORK/gpu.txt")" >&2
  failures=$((failures + 1))
fi

# KTX2 for other engines beside the packed file (one prefilter), and several panoramas per call,
# each into a folder named after it; one bad panorama fails alone.
if "$TOOL" "$WORK/pano.pfm" -o "$WORK/ktx" --size 16 --samples 8 --format packed,ktx2 -q 2>"$WORK/err.txt" &&
   [ -s "$WORK/ktx/environment.hdr" ] && [ -s "$WORK/ktx/environment.ktx2" ] &&
   [ "$(head -c 12 "$WORK/ktx/environment.ktx2" | od -An -tx1 | tr -d ' \n')" = "ab4b5458203230bb0d0a1a0a" ]; then
  echo "ok   [ktx2]"
else
  echo "FAIL [ktx2]: $(cat "$WORK/err.txt"; ls "$WORK/ktx" 2>&1)" >&2
  failures=$((failures + 1))
fi
cp "$WORK/pano.pfm" "$WORK/second.pfm"
if "$TOOL" "$WORK/pano.pfm" "$WORK/second.pfm" -o "$WORK/many" --size 8 --samples 8 -q 2>"$WORK/err.txt" &&
   [ -s "$WORK/many/pano/environment.hdr" ] && [ -s "$WORK/many/second/environment.hdr" ] &&
   cmp -s "$WORK/many/pano/environment.hdr" "$WORK/many/second/environment.hdr"; then
  echo "ok   [several-inputs]"
else
  echo "FAIL [several-inputs]: $(cat "$WORK/err.txt"; find "$WORK/many" -type f)" >&2
  failures=$((failures + 1))
fi
status=0
"$TOOL" "$WORK/wide.pfm" "$WORK/second.pfm" -o "$WORK/partly" --size 8 --samples 8 -q 2>"$WORK/err.txt" || status=$?
if [ "$status" -ne 0 ] && [ -s "$WORK/partly/second/environment.hdr" ] &&
   grep -q "wide.pfm: expected a 2:1 equirectangular panorama" "$WORK/err.txt" &&
   grep -q "1 of 2 panoramas failed" "$WORK/err.txt"; then
  echo "ok   [one-bad-input-of-two]"
else
  echo "FAIL [one-bad-input-of-two]: exit $status, $(cat "$WORK/err.txt")" >&2
  failures=$((failures + 1))
fi
mkdir -p "$WORK/other"
cp "$WORK/pano.pfm" "$WORK/other/pano.pfm"
expect_fail same-names "share the output folder" "$WORK/pano.pfm" "$WORK/other/pano.pfm" -o "$WORK/o8"

if [ "$failures" -ne 0 ]; then
  echo "$failures case(s) failed" >&2
  exit 1
fi
echo "all prefilter command-line cases passed"
