#!/usr/bin/env bash
# The sky-light accuracy table (bench/results/zen3-2core-pocl-sky-prt.md): the yard
# (gen_load_scene --yard) under every map of Debian's blender-data and the clear sky, for the
# cones and for PRT (9 coefficients interreflected, 25 interreflected, 25 shadowed), each with
# bench --accuracy at 128x128 against a 256-spp truth; then one Markdown table of the JSONs.
#   bash tools/sky_accuracy_table.sh [BUILD_DIR] [OUT_DIR] [OPTIONS]
# (defaults: build, out/sky-table; OPTIONS are added to every run, e.g. "--env-suns 0" for the
# maps whole, their suns gathered by the cones or PRT with the rest, or "--truth-noise" for a
# column with the truth's own noise). Environment: SKY_SPP (the truths' samples per pixel,
# default 256; studio's indirect light needs 4096 to be measured within a few per cent) and
# SKY_MAPS (default: the eight maps and clear).
# About 30 s per map and configuration on 2 cores (the truths and transfers are cached); a
# 4096-spp truth takes about 70 s per map (140 s with --truth-noise).
set -euo pipefail
build="${1:-build}"
out="${2:-out/sky-table}"
extra="${3:-}"
spp="${SKY_SPP:-256}"
maps=/usr/share/blender/datafiles/studiolights/world
[[ -d "$maps" ]] || { echo "sky_accuracy_table: $maps missing (apt-get install blender-data)" >&2; exit 2; }
mkdir -p "$out"
"$build/tools/gen_load_scene" "$out/yard.glb" --yard > /dev/null
configs=("cones:" "prt9i:--sky-light prt" "prt25i:--sky-light prt --prt-bands 5"
         "prt25s:--sky-light prt --prt-bands 5 --prt-transfer shadowed")
skies=()
names="${SKY_MAPS:-studio interior courtyard forest city sunrise sunset night clear}"
for m in $names; do
  if [[ "$m" == clear ]]; then skies+=("clear:--sky clear")
  else skies+=("$m:--env $maps/$m.exr"); fi
done
for sky in "${skies[@]}"; do
  name="${sky%%:*}"
  for config in "${configs[@]}"; do
    tag="${config%%:*}"
    [[ -f "$out/$name-$tag.json" ]] && continue
    # shellcheck disable=SC2086  # the option strings are word lists
    "$build/rolypoly" bench --accuracy --scene "$out/yard.glb" ${sky#*:} ${config#*:} $extra \
      --size 128 --spp "$spp" --out "$out/$name-$tag" --json "$out/$name-$tag.json" \
      > "$out/$name-$tag.log" 2>&1 || { echo "failed: $name $tag (see $out/$name-$tag.log)" >&2; exit 1; }
    echo "done: $name $tag"
  done
done
# shellcheck disable=SC2086  # the map names are a word list
python3 - "$out" $names <<'PY'
import json, sys
out = sys.argv[1]
names = sys.argv[2:]
tags = [("cones", "cones"), ("prt9i", "PRT 9 interr."), ("prt25i", "PRT 25 interr."),
        ("prt25s", "PRT 25 shadowed")]
mats = ["ground", "wall", "red", "blue", "green"]
first = json.load(open(f"{out}/{names[0]}-cones.json"))
noise = "noise" in first["truth"]
print("| map | SH irr. error 9 / 25 | " + ("truth noise | " if noise else "") +
      "light | final TAA dB | fast/N L1 | fast/N bias | " + " | ".join(mats) + " |")
print("|---|---|" + ("---|" if noise else "") + "---|---|---|---|" + "---|" * len(mats))
for n in names:
    for tag, label in tags:
        j = json.load(open(f"{out}/{n}-{tag}.json"))
        ind = j["configurations"]["fast_many"]["indirect"]
        err = j.get("sky_sh_irradiance_error", {})
        e = f"{100 * err['9']:.1f} / {100 * err['25']:.1f}" if err and tag == "cones" else ""
        cells = [f"{100 * ind[m]['rel_l1']:.1f} ({100 * ind[m]['bias']:+.0f})" for m in mats]
        tn = ""
        if noise:
            tn = (f"{100 * j['truth']['noise']['indirect']['image']['rel_l1']:.1f} | "
                  if tag == "cones" else " | ")
        print(f"| {n if tag == 'cones' else ''} | {e} | {tn}{label} | "
              f"{j['configurations']['fast_many_taa']['final_psnr_db']:.1f} | "
              f"{100 * ind['image']['rel_l1']:.1f} | {100 * ind['image']['bias']:+.1f} | "
              + " | ".join(cells) + " |")
PY
