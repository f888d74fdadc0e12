# Embeds every shader source under `dir` into `target` at build time, keyed by its path
# relative to `dir`, so programs compile GLSL at run time without finding files on disk.
function(facet_embed_shaders target dir)
  file(GLOB_RECURSE _shaders CONFIGURE_DEPENDS
    ${dir}/*.glsl ${dir}/*.comp ${dir}/*.vert ${dir}/*.frag)
  list(SORT _shaders)
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/facet_embedded_shaders.cpp)
  # The list of names is a dependency too: a removed or renamed shader changes it (the
  # glob re-runs at build time), while file times alone would not re-embed.
  set(_list ${CMAKE_CURRENT_BINARY_DIR}/facet_embedded_shaders.list)
  string(REPLACE ";" "\n" _names "${_shaders}")
  file(CONFIGURE OUTPUT ${_list} CONTENT "${_names}\n")
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${dir} -DOUTPUT=${_out}
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_generate.cmake
    DEPENDS ${_shaders} ${_list} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_generate.cmake
    COMMENT "Embedding shaders from ${dir}"
    VERBATIM)
  target_sources(${target} PRIVATE ${_out})
endfunction()
