#!/usr/bin/env bash
# Set up, build and (optionally) run rolypoly on Debian/Ubuntu.
#
#   bash tools/setup.sh            check/install packages, build Release into build/ (every target)
#   bash tools/setup.sh demo       ... building only build/rolypoly, then render the demo headless:
#                                  out/frame_0000.png
#   bash tools/setup.sh test       ... then run the whole test suite (ctest, all labels)
#   bash tools/setup.sh test-sanitize  build with AddressSanitizer + UBSan into build-asan/
#                                  and run the tests except the oclgrind and soak labels
#   bash tools/setup.sh --werror   any mode, with compiler warnings as errors (also when CI=true)
#
# Missing Debian packages are installed with apt-get when run as root; otherwise the exact
# apt-get command is printed and the script stops.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Build tools, OpenCL (PoCL CPU driver, headers, ICD loader, oclgrind for the kernel checks),
# libraries, a virtual X server with software OpenGL for the window tests, and xdotool to close
# a window from outside (the window-closed-mid-run test). mesa-opencl-icd is the second OpenCL
# implementation (Mesa rusticl on llvmpipe, devices with RUSTICL_ENABLE=llvmpipe): the
# `rusticl` test label renders on it.
PACKAGES=(
  cmake make g++ pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo oclgrind
  mesa-opencl-icd
  libglm-dev libglfw3-dev libgl-dev libstb-dev libembree-dev libtinygltf-dev
  libgtest-dev libcli11-dev nlohmann-json3-dev libopenexr-dev
  xvfb xauth libgl1-mesa-dri xdotool ffmpeg
  clang libclang-rt-14-dev
)

mode=build
werror=OFF
[[ "${CI:-}" == "true" ]] && werror=ON
for arg in "$@"; do
  case "$arg" in
    build|demo|test|test-sanitize) mode="$arg" ;;
    --werror) werror=ON ;;
    -h|--help) sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown argument '$arg' (expected build, demo, test, test-sanitize or --werror)" >&2; exit 2 ;;
  esac
done

# ---- packages ----
if command -v dpkg-query >/dev/null 2>&1; then
  missing=()
  for p in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if ((${#missing[@]})); then
    install_cmd="DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${missing[*]}"
    if [[ $(id -u) -eq 0 ]]; then
      echo "setup.sh: installing ${missing[*]}"
      apt-get update
      eval "$install_cmd"
    else
      echo "setup.sh: missing Debian packages: ${missing[*]}" >&2
      echo "Install them as root, then run this script again:" >&2
      echo "  sudo apt-get update && sudo $install_cmd" >&2
      exit 1
    fi
  else
    echo "setup.sh: all ${#PACKAGES[@]} required packages are installed"
  fi
else
  echo "setup.sh: no dpkg-query (not Debian/Ubuntu?); make sure the equivalents of these are" \
       "installed: ${PACKAGES[*]}" >&2
fi

# ---- build ----
jobs=$(nproc 2>/dev/null || echo 2)
if [[ "$mode" == test-sanitize ]]; then
  # -O2 -g with ASan + UBSan (ROLYPOLY_SANITIZE; UBSan findings abort the test).
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROLYPOLY_SANITIZE=ON \
    -DROLYPOLY_WERROR="$werror"
  cmake --build build-asan -j"$jobs"
else
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DROLYPOLY_WERROR="$werror"
  # The demo needs the binary alone; the tests and tools are built by `build` and `test`.
  targets=()
  [[ "$mode" == demo ]] && targets=(--target rolypoly)
  cmake --build build -j"$jobs" ${targets[@]+"${targets[@]}"}
fi

case "$mode" in
  demo)
    echo "setup.sh: rendering the demo (the first run compiles the OpenCL kernels, about half a" \
         "minute on 2 cores; later runs reuse them)"
    build/rolypoly render --size 720 --frames 1 --out out/
    ;;
  test)
    ctest --test-dir build --output-on-failure -j2
    ;;
  test-sanitize)
    # oclgrind is skipped (a simulator under ASan is slow and adds nothing: the kernels are
    # checked by the oclgrind label), so is the long soak. Leaks inside the OpenCL ICD loader
    # and PoCL (third-party, freed at exit or never) are suppressed by tests/lsan.supp.
    # The window tests under Xvfb run without leak checking: the GL driver that GLFW
    # dlopen()s leaks 240 bytes that LSan can only attribute to "<unknown module>".
    export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
    export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
    window_tests='WindowUnderXvfb|RecordedWindowSession|WindowClose|RunRecordEnd|ShadowKey|OutputIntegrityCli.RunRecord'
    ASAN_OPTIONS="detect_leaks=1" \
      ctest --test-dir build-asan --output-on-failure -j2 -LE 'oclgrind|soak|rusticl' -E "$window_tests"
    ASAN_OPTIONS="detect_leaks=0" \
      ctest --test-dir build-asan --output-on-failure -j2 -LE 'oclgrind|soak|rusticl' -R "$window_tests"
    ;;
esac
