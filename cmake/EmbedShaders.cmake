# penumbra_embed_shaders(TARGET DIR): embeds every file under DIR (GLSL sources) into TARGET as
# a generated C++ table, so that no shader is ever read from disk at run time.
function(penumbra_embed_shaders target dir)
  file(GLOB_RECURSE _files CONFIGURE_DEPENDS RELATIVE ${dir} ${dir}/*.glsl ${dir}/*.vert ${dir}/*.frag)
  list(SORT _files)
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp)
  set(_abs)
  foreach(f IN LISTS _files)
    list(APPEND _abs ${dir}/${f})
  endforeach()
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${_out} -DBASE=${dir} "-DFILES=${_files}"
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    DEPENDS ${_abs} ${PROJECT_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    COMMENT "Embedding GLSL sources"
    VERBATIM)
  target_sources(${target} PRIVATE ${_out})
endfunction()

# penumbra_embed_binary(TARGET FILE SYMBOL): compiles the bytes of FILE into TARGET as
# penumbra::embedded::SYMBOL() (a std::span<const unsigned char>), for small assets the
# library must carry (read nowhere at run time).
function(penumbra_embed_binary target file symbol)
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/embedded_${symbol}.cpp)
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DINPUT=${file} -DOUTPUT=${_out} -DSYMBOL=${symbol}
            -P ${PROJECT_SOURCE_DIR}/cmake/EmbedBinaryScript.cmake
    DEPENDS ${file} ${PROJECT_SOURCE_DIR}/cmake/EmbedBinaryScript.cmake
    COMMENT "Embedding ${file}"
    VERBATIM)
  target_sources(${target} PRIVATE ${_out})
endfunction()
