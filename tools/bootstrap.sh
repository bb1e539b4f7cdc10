#!/usr/bin/env bash
# Set up rockfit on Debian 12 and either run the main job or the tests.
#
#   tools/bootstrap.sh run    install what is missing, build, analyse the bundled sample campaign
#   tools/bootstrap.sh test   install what is missing, build, run every test
#
# Installs missing Debian packages with --no-install-recommends (as root, or through sudo). clang and
# libclang-rt-14-dev are for the libFuzzer targets of tests/fuzz (tools/fuzz.sh); the build itself uses g++.
# libopenmpi-dev and openmpi-bin give `rockfit fragility` its MPI ranks (CMake option ROCKFIT_WITH_MPI).
# chromium, chromium-driver and python3-selenium run the test of `rockfit report` in a real (headless) browser.
# Environment: BUILD_DIR (default build), JOBS (default: number of cores), CMAKE_ARGS (extra).
set -euo pipefail

mode="${1:-run}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${BUILD_DIR:-$here/build}"
jobs="${JOBS:-$(nproc)}"

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libnlopt-cxx-dev libgsl-dev libhdf5-dev
  libgtest-dev libgmock-dev libbenchmark-dev libmujoco-dev
  libcli11-dev libfmt-dev libtomlplusplus-dev nlohmann-json3-dev libtbb-dev
  libopenmpi-dev openmpi-bin
  gnuplot-nox python3 python3-h5py python3-numpy ccache
  python3-dev python3-pybind11 pybind11-dev python3-pytest python3-matplotlib
  clang libclang-rt-14-dev
  chromium chromium-driver python3-selenium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "rockfit: installing missing Debian packages: ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "rockfit: not root and no sudo; install as root: apt-get install --no-install-recommends ${missing[*]}" >&2; exit 1; }
    sudo="sudo"
  fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# ccache makes repeated builds cheap; paths are hashed relative to the checkout so that two clones share hits.
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$here" CCACHE_NOHASHDIR=true
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi

cmake -S "$here" -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" ${CMAKE_ARGS:-}
cmake --build "$build_dir" -j "$jobs"

case "$mode" in
  run)
    exec "$here/tools/main_job.sh" "$build_dir/tools/rockfit"
    ;;
  test)
    cd "$build_dir"
    ctest --output-on-failure -j "$jobs"
    ;;
  *)
    echo "usage: tools/bootstrap.sh run|test" >&2
    exit 1
    ;;
esac
