#!/usr/bin/env bash
# The main job: install packages, build, bake the built-in scene and render it offscreen.
# Output: out/ (override with FACET_OUT).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages "${FACET_PACKAGES[@]}"
build_facet -DFACET_BUILD_TESTS=OFF
out="${FACET_OUT:-$FACET_ROOT/out}"
"$FACET_BUILD_DIR/apps/facet-bake" builtin:sky --out "$out/sky"
echo "facet: done; images in $out/sky"
