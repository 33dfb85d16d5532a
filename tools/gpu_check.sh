#!/usr/bin/env bash
# Runs rolypoly on a GPU: the kernel tests and the bench on the machine's NVIDIA GPU,
# from binaries built elsewhere. Two steps:
#
#   bash tools/gpu_check.sh bundle [BUILD_DIR] [BUNDLE.tar.gz]
#       on the build machine: packs BUILD_DIR's rolypoly, the OpenCL test binaries, the assets
#       and every shared library they need except the C runtime, the GPU driver and the
#       OpenCL ICD loader's vendor files into BUNDLE (default build, out/gpu-bundle.tar.gz).
#   bash tools/gpu_check.sh run [BUNDLE_DIR_OR_TAR] [OUT_DIR] [--device SPEC]
#       on the GPU machine (no package access needed): unpacks the bundle, registers NVIDIA's
#       OpenCL ICD when no ICD file names it (in /etc/OpenCL/vendors when writable, else in a
#       private vendors folder passed to the loader with OCL_ICD_VENDORS), lists the devices,
#       runs `rolypoly bench --scene busy --sizes 720,1080` on the GPU in both real-time modes
#       (fast, reference) at render scales 1 and 0.5, the atrium at the same sizes, the octree
#       (busy and atrium at 720, 256^3 and 512^3), then the kernel tests (test_cl,
#       test_passes, test_render; each at most 180 s), writing into OUT_DIR (default
#       gpu-check-<host>): devices.txt, bench-<mode>-s<scale>.json/.md/.svg/.log,
#       tests-<binary>.log and summary.txt. --device picks the device (index or part of its
#       name; default: the first GPU that `rolypoly devices` lists). --quick: a dry run of the
#       script itself (one test suite per binary, a 64x64 bench of 2 frames), e.g. on a CPU
#       device. Exit 0 when everything passed, 1 otherwise (the
#       summary says which step failed); 2 for bad usage or no GPU.
#
# The bundle carries libOpenCL.so.1 (the ICD loader) in case the GPU machine has none; the
# NVIDIA driver provides libnvidia-opencl.so.1 (and libcuda) itself.
set -euo pipefail

usage() { sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; }

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

bundle() {
  local build="${1:-build}" tarball="${2:-out/gpu-bundle.tar.gz}"
  local bins=("$build/rolypoly" "$build/tests/test_cl" "$build/tests/test_passes"
              "$build/tests/test_render")
  for b in "${bins[@]}"; do
    [[ -x "$b" ]] || { echo "gpu_check: $b not built (cmake --build $build)" >&2; exit 2; }
  done
  local stage
  stage="$(mktemp -d)"
  mkdir -p "$stage/gpu-bundle/bin" "$stage/gpu-bundle/lib"
  cp "${bins[@]}" "$stage/gpu-bundle/bin/"
  # Assets (textures; ROLYPOLY_ASSET_DIR) and the test data the kernel tests read (their path
  # is compiled in: SOURCE_DIR records it so `run` can link it there).
  mkdir -p "$stage/gpu-bundle/scene" "$stage/gpu-bundle/tests"
  cp -r "$here/scene/assets" "$stage/gpu-bundle/scene/"
  cp -r "$here/tests/data" "$stage/gpu-bundle/tests/"
  echo "$here" > "$stage/gpu-bundle/SOURCE_DIR"
  # Shared libraries: everything ldd resolves except the C runtime and the GPU driver's own.
  ldd "${bins[@]}" 2>/dev/null | awk '/=> \// { print $3 }' | sort -u | while read -r lib; do
    case "$(basename "$lib")" in
      libc.so*|libm.so*|libdl.so*|librt.so*|libpthread.so*|ld-linux*|libcuda*|libnvidia*) ;;
      *) cp -L "$lib" "$stage/gpu-bundle/lib/" ;;
    esac
  done
  git -C "$here" rev-parse HEAD > "$stage/gpu-bundle/COMMIT" 2>/dev/null || true
  mkdir -p "$(dirname "$tarball")"
  tar -C "$stage" -czf "$tarball" gpu-bundle
  rm -rf "$stage"
  echo "gpu_check: wrote $tarball ($(du -h "$tarball" | cut -f1)); on the GPU machine:"
  echo "  bash gpu_check.sh run $(basename "$tarball")"
}

# Registers NVIDIA's OpenCL ICD when no vendor file names it; prints what it did.
register_nvidia_icd() {
  local vendors=/etc/OpenCL/vendors
  if [[ -n "${OCL_ICD_VENDORS:-}" ]]; then vendors="$OCL_ICD_VENDORS"; fi
  if grep -qsl nvidia "$vendors"/*.icd 2>/dev/null; then
    echo "ICD: NVIDIA already registered in $vendors"
    return
  fi
  local lib
  lib="$( (ldconfig -p 2>/dev/null | awk '/libnvidia-opencl\.so\.1/ { print $NF; exit }') || true)"
  if [[ -z "$lib" ]]; then
    lib="$(find /usr/lib /usr/lib64 /usr/local/nvidia /usr/lib/x86_64-linux-gnu \
             -name 'libnvidia-opencl.so.1' 2>/dev/null | head -n1 || true)"
  fi
  if [[ -z "$lib" ]]; then
    echo "ICD: no libnvidia-opencl.so.1 found (is the NVIDIA driver installed?)"
    return
  fi
  if mkdir -p /etc/OpenCL/vendors 2>/dev/null && [[ -w /etc/OpenCL/vendors ]]; then
    echo "$lib" > /etc/OpenCL/vendors/nvidia.icd
    echo "ICD: registered $lib in /etc/OpenCL/vendors/nvidia.icd"
  else
    local private="$out/vendors"
    mkdir -p "$private"
    # Keep what the system registers (PoCL, ...) beside NVIDIA's.
    cp /etc/OpenCL/vendors/*.icd "$private/" 2>/dev/null || true
    echo "$lib" > "$private/nvidia.icd"
    export OCL_ICD_VENDORS="$private"
    echo "ICD: registered $lib in $private (OCL_ICD_VENDORS)"
  fi
}

run() {
  local src="${1:-gpu-bundle}" device="" quick=0
  out="${2:-gpu-check-$(hostname -s 2>/dev/null || echo host)}"
  shift $(( $# >= 2 ? 2 : $# ))
  while (( $# )); do
    case "$1" in
      --device) device="$2"; shift 2 ;;
      --quick) quick=1; shift ;;
      *) echo "gpu_check: unknown argument '$1'" >&2; usage >&2; exit 2 ;;
    esac
  done
  mkdir -p "$out"
  out="$(cd "$out" && pwd)"
  local root
  if [[ -f "$src" ]]; then
    tar -C "$out" -xzf "$src"
    root="$out/gpu-bundle"
  else
    root="$(cd "$src" && pwd)"
  fi
  export LD_LIBRARY_PATH="$root/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
  export ROLYPOLY_ASSET_DIR="$root/scene/assets"
  # The tests read <source>/tests/data (compiled in): link the bundle's copy there if missing.
  local srcdir
  srcdir="$(cat "$root/SOURCE_DIR" 2>/dev/null || true)"
  if [[ -n "$srcdir" && ! -d "$srcdir/tests/data" ]]; then
    if mkdir -p "$srcdir/tests" 2>/dev/null && ln -sfn "$root/tests/data" "$srcdir/tests/data"; then
      echo "test data linked at $srcdir/tests/data"
    else
      echo "gpu_check: cannot create $srcdir/tests/data: tests reading golden images will fail"
    fi
  fi
  export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$out/pocl-cache}"
  local summary="$out/summary.txt"
  : > "$summary"
  {
    echo "gpu_check on $(hostname) at $(date -u +%Y-%m-%dT%H:%M:%SZ)"
    echo "bundle commit: $(cat "$root/COMMIT" 2>/dev/null || echo unknown)"
    command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total \
      --format=csv,noheader 2>/dev/null | sed 's/^/GPU: /' || echo "nvidia-smi: not found"
  } | tee -a "$summary"
  register_nvidia_icd | tee -a "$summary"

  local rp="$root/bin/rolypoly"
  "$rp" devices > "$out/devices.txt" 2>&1 || true
  cat "$out/devices.txt"
  if [[ -z "$device" ]]; then
    # The first device whose "type" line says GPU: its index is on the line before.
    device="$(awk '/^  \[[0-9]+\]/ { idx = substr($1, 2, length($1) - 2) }
                   /type GPU/ { print idx; exit }' "$out/devices.txt")"
  fi
  if [[ -z "$device" ]]; then
    echo "gpu_check: no GPU among the OpenCL devices (see $out/devices.txt)" | tee -a "$summary" >&2
    exit 2
  fi
  echo "device: $device" | tee -a "$summary"

  local failed=0
  local sizes="720,1080" frames=(--frames 30 --warmup 5) test_limit=180 svo_voxels="256,512"
  # every test, but the voxelizer's CPU layouts at 8 and 16 lanes (GPUs never build them, and
  # NVIDIA's compiler takes 10-25 s for each)
  local filter="*-*VoxelizeSpans*span8_*:*VoxelizeSpans*span16_*"
  if (( quick )); then
    sizes=64; frames=(--frames 2 --warmup 1); filter="Profiler.*:ToneMap.*:Golden*"
    svo_voxels=256
  fi
  # bench_step TAG ARGS...: one bench into bench-TAG.{json,md,svg,log}, recorded in the summary
  bench_step() {
    local tag="$1"
    shift
    if "$rp" bench --devices "$device" "$@" --json "$out/bench-$tag.json" \
        --markdown "$out/bench-$tag.md" --chart "$out/bench-$tag.svg" \
        > "$out/bench-$tag.log" 2>&1; then
      echo "bench $tag: written (bench-$tag.json, .md, .svg)" | tee -a "$summary"
    else
      echo "bench $tag: FAILED (see bench-$tag.log)" | tee -a "$summary"
      tail -n 20 "$out/bench-$tag.log" >> "$summary"
      failed=1
    fi
  }
  # The benches first (the figures this run exists for), then the kernel tests, each under a
  # time limit so that one slow binary cannot eat a short lease.
  local quality scale
  for quality in fast reference; do
    for scale in 1 0.5; do
      bench_step "$quality-s$scale" --scene busy --sizes "$sizes" "${frames[@]}" \
        --quality "$quality" --render-scale "$scale"
    done
  done
  bench_step atrium --scene atrium --sizes "$sizes" "${frames[@]}"
  # the octree: what the voxelizer's GPU layout must keep fast (spheres, large triangles)
  bench_step svo-busy --scene busy --gi-volume svo --voxels "$svo_voxels" \
    --size "${sizes%%,*}" "${frames[@]}"
  bench_step svo-atrium --scene atrium --gi-volume svo --voxels "$svo_voxels" \
    --size "${sizes%%,*}" "${frames[@]}"
  for t in test_cl test_passes test_render; do
    if ROLYPOLY_TEST_DEVICE="$device" ROLYPOLY_TEST_BINARY="$rp" timeout "$test_limit" "$root/bin/$t" \
        --gtest_filter="$filter" > "$out/tests-$t.log" 2>&1; then
      echo "$t: passed" | tee -a "$summary"
    else
      echo "$t: FAILED or over ${test_limit} s (see tests-$t.log)" | tee -a "$summary"
      grep -E '^\[  FAILED  \]' "$out/tests-$t.log" | sort -u | head -40 >> "$summary" || true
      failed=1
    fi
  done
  tail -n 30 "$out/bench-fast-s1.log" || true
  echo "results in $out; copy bench-*.json / .md to bench/results/<machine>-<device>-*"
  exit "$failed"
}

case "${1:-}" in
  bundle) shift; bundle "$@" ;;
  run) shift; run "$@" ;;
  -h|--help|"") usage; [[ -n "${1:-}" ]] || exit 2 ;;
  *) echo "gpu_check: unknown step '$1'" >&2; usage >&2; exit 2 ;;
esac
