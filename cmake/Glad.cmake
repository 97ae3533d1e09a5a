# Generates the glad 2 GLES 3.0 loader at build time, offline, from Debian's python3-glad.
# Only the extensions Penumbra uses are included.
find_program(GLAD_EXECUTABLE glad PATHS /usr/bin NO_DEFAULT_PATH)
find_program(GLAD_EXECUTABLE glad)
if(NOT GLAD_EXECUTABLE)
  message(FATAL_ERROR "glad not found: run tools/setup (Debian package python3-glad)")
endif()
set(PENUMBRA_GL_EXTENSIONS
  GL_EXT_color_buffer_float GL_EXT_color_buffer_half_float GL_OES_texture_float_linear
  GL_EXT_float_blend GL_KHR_debug GL_EXT_disjoint_timer_query)
string(REPLACE ";" "," _glad_ext "${PENUMBRA_GL_EXTENSIONS}")
set(_glad_dir ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${_glad_dir}/src/gles2.c ${_glad_dir}/include/glad/gles2.h
  COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api gles2=3.0 --extensions ${_glad_ext}
          --out-path ${_glad_dir} c
  COMMENT "Generating the glad GLES 3.0 loader"
  VERBATIM)
add_library(glad STATIC ${_glad_dir}/src/gles2.c)
target_include_directories(glad SYSTEM PUBLIC $<BUILD_INTERFACE:${_glad_dir}/include>)
set_target_properties(glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
