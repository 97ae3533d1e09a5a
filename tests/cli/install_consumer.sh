#!/usr/bin/env bash
# The installed package, as a C++ host uses it: `cmake --install` the build, then configure and
# build tools/host-example on its own against it (find_package(Penumbra CONFIG)), run it (its
# own EGL context and framebuffer, Penumbra drawn into a viewport, host GL state checked) and
# compare its image with penumbra-render's for the same scene and settings. The pkg-config
# file is checked by compiling and linking a small program with its flags.
# Usage (ctest): bash tests/cli/install_consumer.sh <libdir> <build dir>
set -u
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
BUILD="$(cd "$2" && pwd)"
WORK="$(mktemp -d "${TMPDIR:-/tmp}/penumbra-install.XXXXXX")"
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$BUILD" --prefix "$WORK/prefix" >"$WORK/install.log" 2>&1 ||
  { cat "$WORK/install.log"; fail "cmake --install"; }
[ -f "$WORK/prefix/include/penumbra/render_job.h" ] || fail "public headers not installed"
[ -e "$WORK/prefix/include/penumbra/../../src" ] && fail "private sources installed"
config=$(find "$WORK/prefix" -name PenumbraConfig.cmake | head -1)
[ -n "$config" ] || fail "no PenumbraConfig.cmake installed"

gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
cmake -S "$ROOT/tools/host-example" -B "$WORK/host" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$WORK/prefix" >"$WORK/configure.log" 2>&1 ||
  { cat "$WORK/configure.log"; fail "configuring the consumer against the installed package"; }
cmake --build "$WORK/host" -j 2 >"$WORK/build.log" 2>&1 ||
  { cat "$WORK/build.log"; fail "building the consumer"; }

scene="$ROOT/assets/cornell_box/cornell_box.json"
"$BUILD/tools/render/penumbra-render" "$scene" -o "$WORK/ref.png" --size 96x64 --frames 8 \
  --shadow-size 256 -q || fail "penumbra-render"
# Same scene, settings and code: the images should agree to rounding.
"$WORK/host/penumbra-host-example" "$scene" -o "$WORK/host.png" --set width=96 --set height=64 \
  --set frames=8 --set shadowMapSize=256 --reference "$WORK/ref.png" --max-diff 0.02 \
  --mean-diff 0.001 || fail "the host example (installed package)"

pc=$(find "$WORK/prefix" -name penumbra.pc | head -1)
[ -n "$pc" ] || fail "no penumbra.pc installed"
cat >"$WORK/pc.cpp" <<'CPP'
#include <cstdio>
#include "penumbra/settings.h"
#include "penumbra/version.h"
int main() { std::printf("%s %zu\n", penumbra::version(), penumbra::settingsSchema().size()); }
CPP
flags=$(PKG_CONFIG_PATH="$(dirname "$pc")" pkg-config --static --cflags --libs penumbra) ||
  fail "pkg-config penumbra"
# shellcheck disable=SC2086
c++ -std=c++20 "$WORK/pc.cpp" -o "$WORK/pc" $flags >"$WORK/pc.log" 2>&1 ||
  { cat "$WORK/pc.log"; fail "compiling against pkg-config's flags"; }
"$WORK/pc" | grep -q "^0\." || fail "the pkg-config program did not run"
echo "installed package: find_package consumer and pkg-config program work"
