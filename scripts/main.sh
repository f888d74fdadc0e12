#!/usr/bin/env bash
# The main job: install packages, build, bake the built-in scene and render it offscreen.
# Output: out/ (override with FACET_OUT).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

install_packages "${FACET_PACKAGES[@]}"
build_facet -DFACET_BUILD_TESTS=OFF
out="${FACET_OUT:-$FACET_ROOT/out}"
"$FACET_BUILD_DIR/apps/facet-bake" builtin:sky --out "$out/sky"
"$FACET_BUILD_DIR/apps/facet-render" --model builtin:spheres --env builtin:sky --out "$out/spheres.png" \
  --aov normal,position,basecolor,metallic,roughness,D,F,G,diffuse,specular
"$FACET_BUILD_DIR/apps/facet-render" --model builtin:spheres --env builtin:sky --out "$out/spheres.exr"
echo "facet: done; IBL data in $out/sky, images in $out/spheres.png (.exr, .json, .<view>.exr)"
