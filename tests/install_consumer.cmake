# find_package(facet) from an install prefix: install, build tests/consumer, run it.
add_test(NAME install.consumer_builds_and_runs
  COMMAND ${CMAKE_COMMAND} -DBUILD_DIR=${PROJECT_BINARY_DIR}
          -DSOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR}/consumer
          -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/consumer_work
          -P ${CMAKE_CURRENT_SOURCE_DIR}/consumer/run.cmake)
set_tests_properties(install.consumer_builds_and_runs PROPERTIES LABELS install TIMEOUT 300
  ENVIRONMENT "FACET_VALIDATION=1")
