#!/usr/bin/env bash
# The tests: install packages, build, run every ctest suite on lavapipe with the
# Khronos validation layer (any validation message fails a test), then the fuzz targets.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages "${FACET_PACKAGES[@]}" "${FACET_TEST_PACKAGES[@]}"
build_facet -DFACET_BUILD_TESTS=ON
(cd "$FACET_BUILD_DIR" && ctest --output-on-failure --timeout 600 -j "$FACET_JOBS" "$@")
# Then the fuzz build (clang, sanitizers): every target replays its regression inputs and
# fuzzes for a short bounded run, FACET_FUZZ_SECONDS (5 s each unless set: a smoke run;
# scripts/fuzz.sh runs them for minutes).
export FACET_FUZZ_SECONDS="${FACET_FUZZ_SECONDS:-5}"
build_fuzz
cd "$FACET_FUZZ_BUILD_DIR"
ctest --output-on-failure --timeout 600 -j "$FACET_JOBS" -L fuzz
