#!/usr/bin/env bash
# Set up, build and (optionally) run rolypoly on Debian/Ubuntu.
#
#   bash tools/setup.sh            check/install packages, build Release into build/
#   bash tools/setup.sh demo       ... then render the demo headless: out/frame_0000.png
#   bash tools/setup.sh test       ... then run the whole test suite (ctest, all labels)
#   bash tools/setup.sh --werror   any mode, with compiler warnings as errors (also when CI=true)
#
# Missing Debian packages are installed with apt-get when run as root; otherwise the exact
# apt-get command is printed and the script stops.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

# Build tools, OpenCL (PoCL CPU driver, headers, ICD loader, oclgrind for the kernel checks),
# libraries, and a virtual X server with software OpenGL for the window test.
PACKAGES=(
  cmake make g++ pkg-config
  pocl-opencl-icd ocl-icd-opencl-dev opencl-c-headers opencl-clhpp-headers clinfo oclgrind
  libglm-dev libglfw3-dev libgl-dev libstb-dev libembree-dev
  libgtest-dev libcli11-dev nlohmann-json3-dev
  xvfb xauth libgl1-mesa-dri
)

mode=build
werror=OFF
[[ "${CI:-}" == "true" ]] && werror=ON
for arg in "$@"; do
  case "$arg" in
    build|demo|test) mode="$arg" ;;
    --werror) werror=ON ;;
    -h|--help) sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "setup.sh: unknown argument '$arg' (expected build, demo, test or --werror)" >&2; exit 2 ;;
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
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DROLYPOLY_WERROR="$werror"
cmake --build build -j"$jobs"

case "$mode" in
  demo)
    build/rolypoly render --size 720 --frames 1 --out out/
    ;;
  test)
    ctest --test-dir build --output-on-failure -j2
    ;;
esac
