#!/usr/bin/env bash
# Runs a command under oclgrind with data-race and API checks and fails when
# oclgrind's log reports anything (oclgrind itself always exits 0) or the command fails.
# (--uninitialized is not used: oclgrind 21.10 crashes with it on plain float4 arithmetic;
# re-checked with the current kernels: the 16x16 render and the debug-view gtests both die
# with SIGSEGV inside oclgrind before the first kernel finishes.)
# The kernels the command launches are listed in LOGFILE's name with .kernels for .log
# (ROLYPOLY_KERNEL_LOG, src/cl/launch_log.h), for check_kernel_coverage.sh.
# Usage: check_oclgrind.sh LOGFILE COMMAND [ARGS...]
set -u
log=$1
shift
rm -f "$log"
export ROLYPOLY_KERNEL_LOG="${log%.log}.kernels"
rm -f "$ROLYPOLY_KERNEL_LOG"
# Each test gets its own kernel cache: oclgrind's compiled programs are not PoCL's.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-/tmp/rolypoly-oclgrind-pocl}"
oclgrind --data-races --check-api --log "$log" "$@"
status=$?
if [ $status -ne 0 ]; then
  echo "command failed under oclgrind with exit status $status" >&2
  [ -s "$log" ] && cat "$log" >&2
  exit 1
fi
if [ -s "$log" ]; then
  echo "oclgrind reported problems ($log):" >&2
  head -n 200 "$log" >&2
  exit 1
fi
echo "oclgrind: clean"
