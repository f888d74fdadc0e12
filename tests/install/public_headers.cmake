# Every public header compiles on its own with only include/ (and the dependencies'
# headers) on the path: a build-time check, one translation unit per header, so a header
# that leans on a private one or on an include it forgot fails the build.
file(GLOB_RECURSE FACET_PUBLIC_HEADERS CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/include
     ${PROJECT_SOURCE_DIR}/include/facet/*.h)
set(_units)
foreach(h IN LISTS FACET_PUBLIC_HEADERS)
  string(MAKE_C_IDENTIFIER ${h} id)
  set(unit ${CMAKE_CURRENT_BINARY_DIR}/public_headers/${id}.cpp)
  file(CONFIGURE OUTPUT ${unit} CONTENT "#include <${h}>\n")
  list(APPEND _units ${unit})
endforeach()
add_library(facet_public_headers_check OBJECT ${_units})
target_include_directories(facet_public_headers_check PRIVATE ${PROJECT_SOURCE_DIR}/include)
target_link_libraries(facet_public_headers_check PRIVATE Vulkan::Headers glm::glm)
target_compile_features(facet_public_headers_check PRIVATE cxx_std_20)
