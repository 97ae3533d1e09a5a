// The one place that includes the OpenGL ES 3.0 API: the glad-generated loader natively,
// Emscripten's GLES3 headers in the browser. Only renderer/src/gl and platform include it.
#pragma once

#ifdef __EMSCRIPTEN__
// gl2ext.h needs gl3.h's types: keep this order (separate blocks so clang-format keeps it).
#include <GLES3/gl3.h>

#include <GLES2/gl2ext.h>
#else
#include <glad/gles2.h>
#endif

// Desktop-GL enums used when the context is OSMesa (not in the ES headers).
#ifndef GL_TEXTURE_CUBE_MAP_SEAMLESS
#define GL_TEXTURE_CUBE_MAP_SEAMLESS 0x884F
#endif
#ifndef GL_TIME_ELAPSED_EXT
#define GL_TIME_ELAPSED_EXT 0x88BF
#endif
#ifndef GL_GPU_DISJOINT_EXT
#define GL_GPU_DISJOINT_EXT 0x8FBB
#endif
