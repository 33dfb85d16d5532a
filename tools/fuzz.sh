#!/usr/bin/env bash
# libFuzzer runs: builds fuzz/ with clang into build-fuzz/ and runs every target
# for SECONDS (default 30) from its seed corpus fuzz/corpus/<target>/.
#
#   bash tools/fuzz.sh [SECONDS] [TARGET...]     targets: input_log cli_devices cli gltf_loader
#                                                (default: all)
#
# New inputs go to build-fuzz/corpus/<target>/ (the seeds in fuzz/ are only read), crash
# reproducers to build-fuzz/artifacts/<target>/; a reproducer re-runs with
#   build-fuzz/fuzz_<target> build-fuzz/artifacts/<target>/crash-...
# Exits non-zero when a target finds a crash, sanitizer report, leak or hang, or fails to build.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds="${1:-30}"
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -gt 0 ]] ||
  { echo "fuzz.sh: SECONDS must be a positive integer, got '$seconds'" >&2; exit 2; }
shift || true
targets=("$@")
((${#targets[@]})) || targets=(input_log cli_devices cli gltf_loader)

command -v clang++ >/dev/null ||
  { echo "fuzz.sh: clang++ not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }

build=build-fuzz
CC=clang CXX=clang++ cmake -S fuzz -B "$build" >/dev/null
cmake --build "$build" -j"$(nproc 2>/dev/null || echo 2)" --target "${targets[@]/#/fuzz_}"

failed=()
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t"
  echo "== fuzz_$t: ${seconds}s"
  log="$build/fuzz_$t.log"
  # A target's dictionary (fuzz/<target>.dict: its option names and tricky values), if any.
  dict=()
  [[ -f "fuzz/$t.dict" ]] && dict=(-dict="fuzz/$t.dict")
  # -timeout: one input running longer than 10 s is a hang; -rss_limit_mb: a runaway allocation.
  if "$build/fuzz_$t" "$build/corpus/$t" "fuzz/corpus/$t" -max_total_time="$seconds" \
      -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/artifacts/$t/" "${dict[@]}" >"$log" 2>&1; then
    # Summary: the last status line (executions, cov, ft, corpus) and the run's totals.
    grep -E '^#[0-9]+' "$log" | tail -n 1
    grep -E '^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)' "$log"
  else
    echo "fuzz_$t: FOUND A PROBLEM (log: $log, reproducer in $build/artifacts/$t/)" >&2
    grep -E '^(fuzz_[a-z_]+: |==[0-9]+== ?ERROR|SUMMARY|artifact_prefix)' "$log" | head -n 20 >&2
    failed+=("$t")
  fi
done

if ((${#failed[@]})); then
  echo "fuzz.sh: failed: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz.sh: no findings in ${targets[*]} (${seconds}s each)"
