# The installed shading include stands alone: a host's shader compiles against
# share/facet/shaders (with glslang's own compiler, when the system has it).
find_program(FACET_GLSLANG_VALIDATOR glslangValidator)
if(FACET_GLSLANG_VALIDATOR)
  add_test(NAME install.host_shader_compiles
    COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
            -DSHADER=${CMAKE_CURRENT_LIST_DIR}/host_shader/host.frag
            -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/host_shader_work
            -DVALIDATOR=${FACET_GLSLANG_VALIDATOR}
            -P ${CMAKE_CURRENT_LIST_DIR}/host_shader/run.cmake)
  set_tests_properties(install.host_shader_compiles PROPERTIES LABELS install TIMEOUT 120)
endif()
