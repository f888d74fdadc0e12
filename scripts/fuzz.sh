#!/usr/bin/env bash
# Fuzzing by hand: every target of tests/fuzz for SECONDS each (default 600), one at a
# time, seeded also from ../shared/data. New inputs collect in build/fuzz/tests/fuzz/corpus/<target>
# (kept between runs); a crash stops its target, with the input in
# build/fuzz/tests/fuzz/artifacts/<target>/ (README: Fuzzing).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

seconds="${1:-600}"
install_packages "${FACET_PACKAGES[@]}" clang-14 libclang-rt-14-dev
build_fuzz
cd "$FACET_FUZZ_BUILD_DIR"
status=0
FACET_FUZZ_SECONDS="$seconds" FACET_FUZZ_SHARED_SEEDS=1 \
  ctest --output-on-failure --timeout $((seconds + 300)) -L fuzz || status=$?
# What each run did: executions, coverage (cov: edges, ft: features), corpus size.
grep -E "^-- fuzz_|stat::|DONE +cov" Testing/Temporary/LastTest.log || true
exit $status
