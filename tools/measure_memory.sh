#!/usr/bin/env bash
# Resident memory of a long headless render: runs
#   rolypoly render --size 32 --frames N --marbles --fireball --out DIR [EXTRA ARGS...]
# and samples VmRSS from /proc/PID/status every INTERVAL seconds together with the newest frame
# written so far. DIR is a fresh folder on tmpfs (/dev/shm when it exists); every frame but the
# newest is deleted as the run goes, so 2000 frames cost no disk. Reports the RSS at the first
# sample at or after frame WARMUP (after warm-up: kernels built, buffers allocated), at the last
# sample taken while frames were still being rendered (not during the teardown after the last
# frame, when RSS drops), the peak, and the growth between the two (kB and kB per 1000 frames).
# A flat run shows a growth of a few hundred kB at most (glibc's heap and page cache noise);
# per-frame allocations that are never freed show as a steady climb.
#
# Usage: tools/measure_memory.sh [ROLYPOLY_BINARY] [-- EXTRA RENDER ARGS]
#   env: FRAMES (2000), WARMUP (100), INTERVAL (1, seconds), SAMPLES (file for the
#        "seconds frame rss_kB" table; default: a temp file, printed path), MAX_GROWTH_KB (if set,
#        exit 1 when the growth exceeds it).
# Exit status: the render's own status if it failed, 1 if MAX_GROWTH_KB is exceeded, else 0.
set -euo pipefail

bin=${1:-build/rolypoly}
shift || true
[ "${1:-}" = "--" ] && shift
frames=${FRAMES:-2000}
warmup=${WARMUP:-100}
interval=${INTERVAL:-1}
if [ ! -x "$bin" ]; then
  echo "measure_memory: $bin is not an executable (build rolypoly first or pass its path)" >&2
  exit 2
fi

base=/tmp
[ -d /dev/shm ] && [ -w /dev/shm ] && base=/dev/shm
out=$(mktemp -d "$base/rolypoly-mem.XXXXXX")
samples=${SAMPLES:-$(mktemp /tmp/rolypoly-mem-samples.XXXXXX)}
log=$(mktemp /tmp/rolypoly-mem-log.XXXXXX)
pid=
cleanup() {
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then kill "$pid" 2>/dev/null || true; fi
  rm -rf "$out"
}
trap cleanup EXIT

"$bin" render --size 32 --frames "$frames" --marbles --fireball --out "$out" "$@" >"$log" 2>&1 &
pid=$!
start=$(date +%s.%N)
echo "# seconds frame rss_kB" >"$samples"
while kill -0 "$pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ {print $2}' "/proc/$pid/status" 2>/dev/null || true)
  [ -z "$rss" ] && break
  # Newest complete frame; older ones go (frame_NNNN.png names sort by number).
  newest=$(cd "$out" && ls -1 2>/dev/null | grep -E '^frame_[0-9]+\.png$' | sort | tail -n 1 || true)
  frame=-1
  if [ -n "$newest" ]; then
    frame=$((10#$(echo "$newest" | tr -dc '0-9')))
    find "$out" -maxdepth 1 -name 'frame_*.png' ! -name "$newest" -delete
  fi
  now=$(date +%s.%N)
  printf '%.1f %d %d\n' "$(awk -v a="$now" -v b="$start" 'BEGIN { print a - b }')" "$frame" "$rss" >>"$samples"
  sleep "$interval"
done
set +e
wait "$pid"
status=$?
set -e
pid=
if [ $status -ne 0 ]; then
  echo "measure_memory: the render failed (exit status $status):" >&2
  cat "$log" >&2
  exit $status
fi

awk -v warmup="$warmup" -v frames="$frames" '
  /^#/ { next }
  { t = $1; f = $2; r = $3; if (r > peak) peak = r; n++
    if (!have_warm && f >= warmup) { have_warm = 1; warm_f = f; warm_r = r; warm_t = t }
    # The end: the last sample while frames were still being rendered. Once the last frame is
    # written the process tears down (buffers, kernels freed) and its RSS drops.
    if (f < frames - 1 || n == 1) { last_f = f; last_r = r; last_t = t }
    all_t = t }
  END {
    if (!have_warm) { print "measure_memory: no sample at or after frame " warmup " (run too short?)"; exit 3 }
    growth = last_r - warm_r
    per_k = (last_f > warm_f) ? growth * 1000.0 / (last_f - warm_f) : 0
    printf "frames rendered: %d (%d samples, %.1f s)\n", frames, n, all_t
    printf "RSS after warm-up (frame %d, %.1f s): %d kB\n", warm_f, warm_t, warm_r
    printf "RSS at the end   (frame %d, %.1f s): %d kB\n", last_f, last_t, last_r
    printf "RSS peak: %d kB\n", peak
    printf "growth: %+d kB (%+.1f kB per 1000 frames)\n", growth, per_k
    print growth > "/dev/stderr"
  }' "$samples" 2>"$out.growth"
growth=$(cat "$out.growth")
rm -f "$out.growth" "$log"
echo "samples: $samples"
if [ -n "${MAX_GROWTH_KB:-}" ] && [ "$growth" -gt "$MAX_GROWTH_KB" ]; then
  echo "measure_memory: RSS grew by $growth kB after warm-up (limit $MAX_GROWTH_KB kB)" >&2
  exit 1
fi
