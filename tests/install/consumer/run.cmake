# ctest driver: install Facet into a fresh prefix, build the consumer against it, run it.
# -DBUILD_DIR=<facet build> -DSOURCE_DIR=<tests/install/consumer> -DWORK_DIR=<scratch>
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
# The installed include folder holds facet/ alone, and only the public headers.
file(GLOB top RELATIVE ${WORK_DIR}/prefix/include ${WORK_DIR}/prefix/include/*)
if(NOT top STREQUAL "facet")
  message(FATAL_ERROR "the installed include folder holds '${top}', not just 'facet'")
endif()
file(GLOB_RECURSE installed RELATIVE ${WORK_DIR}/prefix/include/facet ${WORK_DIR}/prefix/include/facet/*)
file(GLOB_RECURSE public RELATIVE ${PUBLIC_DIR}/facet ${PUBLIC_DIR}/facet/*.h)
list(SORT installed)
list(SORT public)
if(NOT installed STREQUAL public)
  message(FATAL_ERROR "installed headers differ from include/facet:\n installed: ${installed}\n public: ${public}")
endif()
# One translation unit including every installed header: none needs a private one.
set(all "")
foreach(h IN LISTS installed)
  string(APPEND all "#include <facet/${h}>\n")
endforeach()
file(WRITE ${WORK_DIR}/all_headers.cpp "${all}")
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                        -DFACET_ALL_HEADERS=${WORK_DIR}/all_headers.cpp
                        "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer against the installed package failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed (${rc})")
endif()
execute_process(COMMAND ${WORK_DIR}/build/facet_consumer RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the consumer failed (${rc})")
endif()
# The host engine example builds against the installed package as well.
execute_process(COMMAND ${CMAKE_COMMAND} -S ${HOST_EXAMPLE_DIR} -B ${WORK_DIR}/host_engine -G Ninja
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
                        "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}"
                RESULT_VARIABLE rc)
if(rc EQUAL 0)
  execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/host_engine RESULT_VARIABLE rc)
endif()
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building examples/host_engine against the installed package failed (${rc})")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
