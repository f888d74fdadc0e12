# One fuzz target as a ctest (cmake -P), MODE fuzz or replay:
#   fuzz:   FACET_FUZZ_SECONDS (default 20) of fuzzing; new inputs go to WORK/corpus/NAME,
#           seeded from SOURCE/corpus/NAME and SOURCE/regressions/NAME (read only), plus
#           the shared test data when FACET_FUZZ_SHARED_SEEDS=1 (scripts/fuzz.sh).
#   replay: every file of SOURCE/regressions/NAME once.
# Any crash, leak, sanitizer report, timeout (10 s) or RSS above 2 GB fails the test; the
# input is kept in WORK/artifacts/NAME.
set(seeds ${SOURCE}/corpus/${NAME})
set(regressions ${SOURCE}/regressions/${NAME})
set(artifacts ${WORK}/artifacts/${NAME})
file(MAKE_DIRECTORY ${artifacts})
set(options -rss_limit_mb=2048 -timeout=10 -max_len=${MAX_LEN} -artifact_prefix=${artifacts}/)
if(DICT)
  list(APPEND options -dict=${DICT})
endif()
# Leaks inside Debian's libraries that Facet cannot fix; full stacks so that they match.
# Function names in reports need the symbolizer, which clang does not bring on its own.
if(NOT DEFINED ENV{ASAN_SYMBOLIZER_PATH} AND EXISTS /usr/lib/llvm-14/bin/llvm-symbolizer)
  set(ENV{ASAN_SYMBOLIZER_PATH} /usr/lib/llvm-14/bin/llvm-symbolizer)
endif()
if(EXISTS ${SOURCE}/${NAME}.supp)
  set(ENV{ASAN_OPTIONS} "fast_unwind_on_malloc=0:$ENV{ASAN_OPTIONS}")
  set(ENV{LSAN_OPTIONS} "suppressions=${SOURCE}/${NAME}.supp:$ENV{LSAN_OPTIONS}")
endif()

if(MODE STREQUAL "replay")
  file(GLOB inputs LIST_DIRECTORIES false ${regressions}/*)
  list(FILTER inputs EXCLUDE REGEX "/README[^/]*$")
  if(NOT inputs)
    message(STATUS "fuzz_${NAME}: no regression inputs in ${regressions}")
    return()
  endif()
  list(LENGTH inputs count)
  message(STATUS "fuzz_${NAME}: replaying ${count} regression inputs")
  execute_process(COMMAND ${FUZZER} ${options} ${inputs} RESULT_VARIABLE status)
else()
  set(seconds $ENV{FACET_FUZZ_SECONDS})
  if(NOT seconds)
    set(seconds 20)
  endif()
  set(corpus ${WORK}/corpus/${NAME})
  file(MAKE_DIRECTORY ${corpus})
  set(dirs ${corpus} ${seeds})
  if(EXISTS ${regressions})
    list(APPEND dirs ${regressions})
  endif()
  if("$ENV{FACET_FUZZ_SHARED_SEEDS}" STREQUAL "1")
    if(NAME STREQUAL "gltf" AND EXISTS ${SHARED_DATA}/models)
      list(APPEND dirs ${SHARED_DATA}/models)
    elseif(NAME STREQUAL "environment" AND EXISTS ${SHARED_DATA}/env)
      list(APPEND dirs ${SHARED_DATA}/env)
    endif()
  endif()
  message(STATUS "fuzz_${NAME}: ${seconds} s on ${dirs}")
  execute_process(COMMAND ${FUZZER} ${options} -max_total_time=${seconds} -print_final_stats=1 ${dirs}
                  RESULT_VARIABLE status)
endif()

if(NOT status EQUAL 0)
  message(FATAL_ERROR "fuzz_${NAME} failed (${status}); the input is in ${artifacts}/. Reproduce with\n"
                      "  ${FUZZER} ${artifacts}/<file>\n"
                      "fix the parser, then keep the input in ${regressions}/ (README: Fuzzing).")
endif()
