#!/usr/bin/env bash
# The cones' indirect light split into its parts (bench/results/zen5-2core-pocl-cone-thin-surfaces.md):
# the yard (gen_load_scene --yard) under a constant sky (the sky alone), the upper half of it
# (a sky over a ground: what the ground hides), and one sun taken out as a directional light
# (a sun-lit surface's bounce), plus the demo (a closed box), each with bench --accuracy at
# 128x128 against a 256-spp truth; then one Markdown table of indirect L1 and bias.
#   bash tools/cone_light_split.sh [BUILD_DIR] [OUT_DIR] [OPTIONS]
# (defaults: build, out/cone-split; OPTIONS are added to every run, e.g. "--gi-volume svo".
# To try kernel changes, export ROLYPOLY_KERNEL_DIR=DIR first.) About 15 s a row on 2 cores
# once the truths are cached (the first run path traces them: a few minutes).
set -euo pipefail
build="${1:-build}"
out="${2:-out/cone-split}"
extra="${3:-}"
for tool in "$build/rolypoly" "$build/tools/gen_load_scene" "$build/tools/gen_env_map"; do
  [[ -x "$tool" ]] || { echo "cone_light_split: $tool missing (cmake --build $build" \
                          "--target rolypoly gen_load_scene gen_env_map)" >&2; exit 1; }
done
mkdir -p "$out"
"$build/tools/gen_load_scene" "$out/yard.glb" --yard > /dev/null
for kind in const upper sun; do "$build/tools/gen_env_map" "$out/$kind.hdr" "$kind" > /dev/null; done
rows=("const:--scene $out/yard.glb --env $out/const.hdr"
      "upper:--scene $out/yard.glb --env $out/upper.hdr"
      "sun:--scene $out/yard.glb --env $out/sun.hdr"
      "demo:--scene default")
for row in "${rows[@]}"; do
  name="${row%%:*}"
  # shellcheck disable=SC2086  # the option strings are word lists
  "$build/rolypoly" bench --accuracy ${row#*:} $extra --size 128 --spp 256 \
    --json "$out/$name.json" > "$out/$name.log" 2>&1 ||
    { echo "failed: $name (see $out/$name.log)" >&2; exit 1; }
done
python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
labels = {"const": "yard, constant sky", "upper": "yard, upper half of it",
          "sun": "yard, one sun", "demo": "demo (closed box)"}
print("| scene | fast/N L1 | fast/N bias | fast/1 bias | regions, fast/N bias |")
print("|---|---|---|---|---|")
for name, label in labels.items():
    j = json.load(open(f"{out}/{name}.json"))
    many = j["configurations"]["fast_many"]["indirect"]
    one = j["configurations"]["fast_one"]["indirect"]
    regions = ", ".join(f"{k} {100 * v['bias']:+.1f}" for k, v in many.items() if k != "image")
    print(f"| {label} | {100 * many['image']['rel_l1']:.1f} | {100 * many['image']['bias']:+.1f} "
          f"| {100 * one['image']['bias']:+.1f} | {regions} |")
PY
