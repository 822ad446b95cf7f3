#!/usr/bin/env bash
# One-command set-up for a fresh Debian machine: installs what is missing (apt-get), builds,
# then either runs the default scenario as a multi-process cluster or runs the whole test suite.
#
#   ./setup.sh run [wsntrack run options]   # install, build what a run needs, run scenarios/oh_quadrants.yaml
#   ./setup.sh test [ctest options]         # install, build everything, run every test (unit + cluster)
#   ./setup.sh build                        # install and build everything (tests, benchmarks) only
set -euo pipefail
cd "$(dirname "$0")"

usage() { sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'; }
mode="${1:-}"
case "$mode" in
  run|test|build) shift ;;
  -h|--help|help) usage; exit 0 ;;
  *) usage >&2; exit 2 ;;
esac

packages=(build-essential cmake pkg-config git cyclonedds-dev cyclonedds-tools libeigen3-dev
          libboost-program-options-dev catch2 libyaml-cpp-dev libbenchmark-dev nlohmann-json3-dev libssl-dev
          libcpp-httplib-dev
          procps python3 python3-numpy python3-matplotlib python3-pil python3-yaml python3-scipy python3-distributed
          python3-pandas ffmpeg ninja-build ccache clang libclang-rt-14-dev python3-hypothesis)
# The browser map's test drives a real headless Chromium: only the test suite needs it.
[ "$mode" != run ] && packages+=(chromium chromium-driver python3-selenium)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

build_dir="${WSN_BUILD_DIR:-build}"
jobs="$(nproc 2>/dev/null || echo 2)"
# The checked build (build, test) treats warnings as errors; `run` keeps whatever the build dir has.
config=(-DCMAKE_BUILD_TYPE=RelWithDebInfo)
[ "$mode" != run ] && config+=(-DWSN_WERROR=ON -DBUILD_TESTING=ON)
# Ninja for a new build tree (an existing one keeps the generator it was made with). ccache, which
# the package list installs, is picked up by CMake (cmake/WsnCompilerCache.cmake).
[ -f "$build_dir/CMakeCache.txt" ] || config+=(-G Ninja)
cmake -S . -B "$build_dir" "${config[@]}" >/dev/null
# A run needs only wsntrack, which depends on the role executables and the plot script; the tests
# and benchmarks are built by `build` and `test`.
targets=()
[ "$mode" = run ] && targets=(--target wsntrack)
cmake --build "$build_dir" -j"$jobs" "${targets[@]}"

case "$mode" in
  run) exec "$build_dir/bin/wsntrack" run scenarios/oh_quadrants.yaml "$@" ;;
  test) cd "$build_dir" && exec ctest --output-on-failure --no-tests=error -j"$jobs" "$@" ;;
  build) ;;
esac
