# Shared by scripts/main.sh and scripts/test.sh: Debian packages and the build.
set -euo pipefail

FACET_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
FACET_BUILD_DIR="${FACET_BUILD_DIR:-$FACET_ROOT/build/release}"
FACET_FUZZ_BUILD_DIR="${FACET_FUZZ_BUILD_DIR:-$FACET_ROOT/build/fuzz}"
FACET_JOBS="${FACET_JOBS:-$(nproc)}"

# Everything Facet builds and runs with (design.md); the tests add their own few.
# glslang-tools: bookworm's glslang CMake config imports /usr/bin/glslangValidator and
# fails without it (glslang-dev only suggests the package).
FACET_PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools libglfw3-dev libglm-dev libtinygltf-dev libopenimageio-dev libimgui-dev
  libmeshoptimizer-dev libdraco-dev zlib1g-dev
)
# python3-matplotlib: facet-bench sweep's charts (scripts/chart.py), drawn in a test.
# xvfb: the viewer's tests start their own X server.
# clang-14, libclang-rt-14-dev: the fuzz targets (libFuzzer, ASan and UBSan runtimes are in
# libclang-rt-14-dev, which clang-14 only recommends). llvm-14: llvm-symbolizer, which
# names the functions in sanitizer reports (the fuzz suppressions match by function).
FACET_TEST_PACKAGES=(libgtest-dev libgmock-dev libbenchmark-dev xvfb python3-matplotlib clang-14 libclang-rt-14-dev llvm-14)

# Installs the packages that are missing; apt-get update runs only when needed.
install_packages() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "facet: Debian packages present"
    return
  fi
  echo "facet: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

build_facet() {
  cmake -S "$FACET_ROOT" -B "$FACET_BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
  cmake --build "$FACET_BUILD_DIR" -j "$FACET_JOBS"
}

# The fuzz targets (tests/fuzz): the parsers alone, built by clang with libFuzzer, ASan
# and UBSan.
build_fuzz() {
  CC=clang-14 CXX=clang++-14 cmake -S "$FACET_ROOT" -B "$FACET_FUZZ_BUILD_DIR" -G Ninja \
    -DFACET_BUILD_FUZZ=ON -DFACET_BUILD_APPS=OFF -DFACET_BUILD_TESTS=OFF
  cmake --build "$FACET_FUZZ_BUILD_DIR" -j "$FACET_JOBS"
}
