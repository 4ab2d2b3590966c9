# Embeds every file under shaders/ into a generated C++ source as a path -> text table, so that
# the binaries need no shader files at run time. The renderer resolves `#include "lib/x.glsl"`
# from this table (renderer/shader_sources.cpp); C++ tests include the same files directly.
function(glint_embed_shaders target shader_dir)
  file(GLOB_RECURSE _files CONFIGURE_DEPENDS RELATIVE "${shader_dir}" "${shader_dir}/*.glsl"
       "${shader_dir}/*.vert" "${shader_dir}/*.frag" "${shader_dir}/*.comp")
  set(_out "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  set(_abs)
  foreach(f IN LISTS _files)
    list(APPEND _abs "${shader_dir}/${f}")
  endforeach()
  add_custom_command(
    OUTPUT "${_out}"
    COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${shader_dir} -DOUT=${_out} -P "${CMAKE_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
    DEPENDS ${_abs} "${CMAKE_SOURCE_DIR}/cmake/EmbedShadersScript.cmake"
    COMMENT "Embedding shaders")
  target_sources(${target} PRIVATE "${_out}")
endfunction()
