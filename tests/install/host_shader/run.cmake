# ctest driver: install Facet into a fresh prefix and compile a host's shader that includes
# "facet/shading.glsl" with only the installed share/facet/shaders on its include path.
# -DBUILD_DIR=<facet build> -DSHADER=<host.frag> -DWORK_DIR=<scratch> -DVALIDATOR=<glslangValidator>
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
execute_process(COMMAND ${VALIDATOR} -V --target-env vulkan1.3 -I${WORK_DIR}/prefix/share/facet/shaders
                        ${SHADER} -o ${WORK_DIR}/host.spv
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the host shader does not compile against the installed shading include (${rc})")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
