#!/usr/bin/env bash
# Fails unless every __kernel in KERNEL_DIR/*.cl appears in one of the launch logs the
# oclgrind runs wrote (LOG_DIR/*.kernels: ROLYPOLY_KERNEL_LOG, one kernel name per line, set by
# check_oclgrind.sh), so a new kernel cannot go unchecked by oclgrind.
# Usage: check_kernel_coverage.sh KERNEL_DIR LOG_DIR
set -euo pipefail
kernel_dir=$1
log_dir=$2
# `__kernel [__attribute__((...))] void NAME(`, across lines.
declared=$(cat "$kernel_dir"/*.cl | perl -0ne 'while (/__kernel\b.*?\bvoid\s+(\w+)\s*\(/gs) { print "$1\n" }' | sort -u)
shopt -s nullglob
logs=("$log_dir"/*.kernels)
if ((${#logs[@]} == 0)); then
  echo "no launch logs (*.kernels) in $log_dir: did the oclgrind runs run?" >&2
  exit 1
fi
launched=$(cat "${logs[@]}" | sort -u)
missing=$(comm -23 <(echo "$declared") <(echo "$launched"))
echo "$(echo "$declared" | wc -l) kernels declared, $(echo "$launched" | wc -l) launched under oclgrind"
if [ -n "$missing" ]; then
  echo "never launched under oclgrind (add a run that reaches them to tests/oclgrind/CMakeLists.txt):" >&2
  echo "$missing" >&2
  exit 1
fi
echo "every kernel ran under oclgrind"
