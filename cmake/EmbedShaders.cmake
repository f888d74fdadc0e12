# Embeds every shader source under `dir` into `target` at build time, keyed by its path
# relative to `dir`, so programs compile GLSL at run time without finding files on disk.
# EXTRA name path ...: files from elsewhere embedded under `name` (the header of constants
# shared with C++, include/facet/core/shared_constants.h, as "facet/shared_constants.h").
function(facet_embed_shaders target dir)
  cmake_parse_arguments(PARSE_ARGV 2 _arg "" "" "EXTRA")
  file(GLOB_RECURSE _shaders CONFIGURE_DEPENDS
    ${dir}/*.glsl ${dir}/*.comp ${dir}/*.vert ${dir}/*.frag)
  list(SORT _shaders)
  set(_extra_files)
  set(_extra_arg)
  while(_arg_EXTRA)
    list(POP_FRONT _arg_EXTRA _name _path)
    list(APPEND _extra_files ${_path})
    string(APPEND _extra_arg "${_name}=${_path}|")
  endwhile()
  set(_out ${CMAKE_CURRENT_BINARY_DIR}/facet_embedded_shaders.cpp)
  # The list of names is a dependency too: a removed or renamed shader changes it (the
  # glob re-runs at build time), while file times alone would not re-embed.
  set(_list ${CMAKE_CURRENT_BINARY_DIR}/facet_embedded_shaders.list)
  string(REPLACE ";" "\n" _names "${_shaders}")
  file(CONFIGURE OUTPUT ${_list} CONTENT "${_names}\n")
  add_custom_command(
    OUTPUT ${_out}
    COMMAND ${CMAKE_COMMAND} -DSHADER_DIR=${dir} -DOUTPUT=${_out} "-DEXTRA=${_extra_arg}"
            -P ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_generate.cmake
    DEPENDS ${_shaders} ${_extra_files} ${_list} ${PROJECT_SOURCE_DIR}/cmake/embed_shaders_generate.cmake
    COMMENT "Embedding shaders from ${dir}"
    VERBATIM)
  target_sources(${target} PRIVATE ${_out})
endfunction()
