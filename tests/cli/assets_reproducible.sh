#!/usr/bin/env bash
# Every file under assets/ that a generator owns must be reproduced byte for byte by
# tools/assets/generate_all, and every generated glTF / HDR must pass check_gltf.py.
# Usage (ctest): bash tests/cli/assets_reproducible.sh <libdir> <builddir>  (both unused)
set -u
src="${PENUMBRA_SOURCE_DIR:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}"
py="${PYTHON:-python3}"
tools="$src/tools/assets"

if ! command -v "$py" >/dev/null 2>&1; then
  echo "FAIL: '$py' not found; the asset generators need Python 3 (standard library only)"
  exit 1
fi
tmp="$(mktemp -d "${TMPDIR:-/tmp}/penumbra-assets.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT

# Which generator writes which asset folder (for the failure message).
generator_for() {
  case "$1" in
    cornell_box/*) echo "gen_cornell_box.py" ;;
    material_grid/*) echo "gen_material_grid.py" ;;
    env/*) echo "gen_environment.py" ;;
    kitchen/*) echo "gen_kitchen.py" ;;
    product/*) echo "gen_product.py" ;;
    dense/*) echo "gen_dense.py" ;;
    glass/*) echo "gen_glass.py" ;;
    room_cm/*) echo "gen_room_cm.py" ;;
    *) echo "" ;;
  esac
}

if ! PYTHON="$py" bash "$tools/generate_all" "$tmp" >"$tmp.log" 2>&1; then
  cat "$tmp.log"; rm -f "$tmp.log"
  echo "FAIL: tools/assets/generate_all did not run to completion (log above)"
  exit 1
fi
rm -f "$tmp.log"

fail=0
count=0
while IFS= read -r -d '' f; do
  rel="${f#"$tmp"/}"
  count=$((count + 1))
  gen="$(generator_for "$rel")"
  if [ ! -f "$src/assets/$rel" ]; then
    echo "FAIL: assets/$rel is generated but not committed;" \
         "run: python3 tools/assets/$gen  (or bash tools/assets/generate_all)"
    fail=1
  elif ! cmp -s "$f" "$src/assets/$rel"; then
    echo "FAIL: assets/$rel differs from a fresh generation;" \
         "regenerate with: python3 tools/assets/$gen  (or bash tools/assets/generate_all)"
    fail=1
  fi
done < <(find "$tmp" -type f -print0 | sort -z)

# Committed files in generated folders that no generator writes any more (stale).
while IFS= read -r -d '' f; do
  rel="${f#"$src/assets"/}"
  # Scene files (*.json) are written by hand, not generated.
  case "$rel" in README.md|*/README.md|.gitattributes|*.json) continue ;; esac
  if [ ! -f "$tmp/$rel" ]; then
    echo "FAIL: assets/$rel is committed but no generator in tools/assets/generate_all writes it"
    fail=1
  fi
done < <(find "$src/assets" -type f -print0 | sort -z)

# Structural validity of the fresh outputs.
mapfile -d '' checkable < <(find "$tmp" -type f \( -name '*.gltf' -o -name '*.glb' -o -name '*.hdr' \) -print0 | sort -z)
if ! "$py" "$tools/check_gltf.py" "${checkable[@]}"; then
  echo "FAIL: tools/assets/check_gltf.py reported errors in the generated assets (above)"
  fail=1
fi

if [ "$fail" -ne 0 ]; then
  exit 1
fi
echo "OK: $count generated asset files match the committed ones"
