# Web (Emscripten) build settings, included by the top-level CMakeLists.txt under EMSCRIPTEN.
#
# penumbra_web_deps: INTERFACE target with the header-only dependencies (glm, nlohmann/json,
#   tinygltf, stb_image, stb_image_write, stb_image_resize). emcc must never see -I/usr/include (it would pick up
#   the host's libc headers), so at configure time we make a folder of symlinks to just those
#   headers and put that folder on the include path.
# penumbra_web_app: INTERFACE target with the link flags of a browser module (WebGL2 only, full
#   ES3 emulation, growable memory, ES6 module factory). Link it into every web executable.

set(PENUMBRA_WEB_INCLUDE_DIR ${CMAKE_BINARY_DIR}/web-deps/include)
file(MAKE_DIRECTORY ${PENUMBRA_WEB_INCLUDE_DIR})
# name in the folder -> host path. stb headers sit at the top level because the sources and
# Debian's patched tiny_gltf.h include them as <stb_image.h>.
set(_penumbra_web_headers
  "glm=/usr/include/glm"
  "nlohmann=/usr/include/nlohmann"
  "tiny_gltf.h=/usr/include/tiny_gltf.h"
  "stb_image.h=/usr/include/stb/stb_image.h"
  "stb_image_write.h=/usr/include/stb/stb_image_write.h"
  "stb_image_resize.h=/usr/include/stb/stb_image_resize.h")
foreach(_entry IN LISTS _penumbra_web_headers)
  string(REPLACE "=" ";" _pair "${_entry}")
  list(GET _pair 0 _name)
  list(GET _pair 1 _target)
  if(NOT EXISTS ${_target})
    message(FATAL_ERROR "Web build: ${_target} is missing (run tools/setup: libglm-dev, "
                        "nlohmann-json3-dev, libtinygltf-dev, libstb-dev)")
  endif()
  file(CREATE_LINK ${_target} ${PENUMBRA_WEB_INCLUDE_DIR}/${_name} SYMBOLIC)
endforeach()

add_library(penumbra_web_deps INTERFACE)
# SYSTEM: third-party headers must not trip our warning set.
target_include_directories(penumbra_web_deps SYSTEM INTERFACE ${PENUMBRA_WEB_INCLUDE_DIR})

# Release optimisation level, replacing CMake's -O3 (see docs/web/measurements.md for measured sizes). The
# flag also reaches the link step, where emcc runs wasm-opt and the JS minifier at that level.
# -Os since the core crossed 1.5 MB at -O2 (1,506,536 B); the IBL sources stay at -O2
# (renderer/CMakeLists.txt).
set(PENUMBRA_WEB_OPT "-Os" CACHE STRING "Optimisation level of the web Release build (-O2, -Os, -Oz)")
set(CMAKE_C_FLAGS_RELEASE "${PENUMBRA_WEB_OPT} -DNDEBUG" CACHE STRING "" FORCE)
set(CMAKE_CXX_FLAGS_RELEASE "${PENUMBRA_WEB_OPT} -DNDEBUG" CACHE STRING "" FORCE)

# Link-time optimisation (Emscripten's LTO system libraries are in Debian's prebuilt cache): the
# viewer module 1,624,064 -> 1,429,308 B (wasm 1,468,304 -> 1,279,818), back under the 1.5 MB
# target (docs/web/measurements.md); the whole web build took 58 s instead of about 69.
add_compile_options(-flto)
add_link_options(-flto)

# Exceptions are off by default in Emscripten, where a throw aborts the whole module; tinygltf
# and nlohmann throw on malformed JSON, and the loader catches that. Exceptions must be enabled
# at both compile and link time, in every object, so this is global for the web build.
add_compile_options(-fexceptions)
add_link_options(-fexceptions)

# cmake/Warnings.cmake uses GCC's -Wshadow=local, which em++ (clang) does not know; without this
# every object prints "unknown warning option".
add_compile_options(-Wno-unknown-warning-option)

add_library(penumbra_web_app INTERFACE)
# specialHTMLTargets: Emscripten finds a canvas by document.querySelector, which cannot see into a
# shadow root (<penumbra-viewer>'s canvas); the JS API registers its canvas there by selector.
target_link_options(penumbra_web_app INTERFACE
  -sMIN_WEBGL_VERSION=2 -sMAX_WEBGL_VERSION=2 -sFULL_ES3=1
  -sALLOW_MEMORY_GROWTH=1 -sENVIRONMENT=web
  -sMODULARIZE=1 -sEXPORT_ES6=1
  "-sEXPORTED_RUNTIME_METHODS=['ccall','cwrap','UTF8ToString','specialHTMLTargets']")
