# find_package(facet) from an install prefix: install, build tests/install/consumer, run it
# (with this build's compiler flags, so that sanitizer builds link; and its linker).
set(consumer_link_flags "${CMAKE_EXE_LINKER_FLAGS}")
if(FACET_HAVE_GOLD)
  string(APPEND consumer_link_flags " -fuse-ld=gold")
endif()
add_test(NAME install.consumer_builds_and_runs
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DSOURCE_DIR=${CMAKE_CURRENT_LIST_DIR}/consumer
          -DPUBLIC_DIR=${PROJECT_SOURCE_DIR}/include
          -DHOST_EXAMPLE_DIR=${PROJECT_SOURCE_DIR}/examples/host_engine
          -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer_work
          "-DCXX_FLAGS=${CMAKE_CXX_FLAGS}" "-DEXE_LINKER_FLAGS=${consumer_link_flags}"
          -P ${CMAKE_CURRENT_LIST_DIR}/consumer/run.cmake)
set_tests_properties(install.consumer_builds_and_runs PROPERTIES LABELS install TIMEOUT 300
  ENVIRONMENT "FACET_VALIDATION=1")
