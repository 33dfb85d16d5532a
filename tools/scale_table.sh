#!/usr/bin/env bash
# How each pass's time grows with triangles and with the GI volume's resolution, at 720x720:
#   tools/scale_table.sh [BUILD] [OUT_PREFIX]
# (defaults: build, bench/results/zen3-2core-pocl-scale). Triangles: gen_load_scene's generated
# field of instanced tumbler meshes (tools/gen_load_scene.cpp: 50 textures, a sun and three point
# lights) at 25k, 100k, 250k and 1M triangles; voxels: the atrium (`--scene atrium`) with the
# dense volume at 32^3, 64^3, 128^3 and the octree at 256^3 and 512^3. Writes OUT_PREFIX.md (the
# tables, from tools/scale_chart), OUT_PREFIX-triangles.svg, OUT_PREFIX-voxels.svg and the
# benches' JSON in OUT_PREFIX/. About 10 minutes on the project's 2-core machine; run it on a
# quiet machine (the tables are single runs, not round-robin comparisons).
set -euo pipefail
build=${1:-build}
prefix=${2:-bench/results/zen3-2core-pocl-scale}
for tool in "$build/rolypoly" "$build/tools/gen_load_scene" "$build/tools/scale_chart"; do
  [[ -x $tool ]] || { echo "scale_table.sh: $tool is missing (cmake --build $build" \
                          "--target rolypoly gen_load_scene scale_chart)" >&2; exit 1; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$prefix"
bench=("$build/rolypoly" bench --size 720)

for n in 25000 100000 250000 1000000; do
  "$build/tools/gen_load_scene" "$tmp/field-$n.glb" "$n" 50 >/dev/null
  "${bench[@]}" --scene "$tmp/field-$n.glb" --frames 10 --warmup 3 \
    --json "$prefix/triangles-$n.json" >/dev/null
done
"${bench[@]}" --scene atrium --frames 10 --warmup 3 --voxels 32,64,128 \
  --json "$prefix/voxels-dense.json" >/dev/null
"${bench[@]}" --scene atrium --frames 5 --warmup 2 --gi-volume svo --voxels 256,512 \
  --json "$prefix/voxels-svo.json" >/dev/null

{
  echo "# Pass time against triangles and voxel resolution (720x720)"
  echo
  echo "Made by \`tools/scale_table.sh\` on $(uname -n), $(date -u +%Y-%m-%d), from $(git rev-parse --short HEAD 2>/dev/null || echo '?')."
  echo "Milliseconds, medians of the measured frames; the growth exponent is the slope of log ms"
  echo "on log x (1: linear)."
  echo
  echo "## Triangles (gen_load_scene's field of tumblers)"
  echo
  "$build/tools/scale_chart" triangles "$prefix-triangles.svg" "$prefix"/triangles-*.json
  echo
  echo "## Voxel resolution (the atrium)"
  echo
  "$build/tools/scale_chart" voxels "$prefix-voxels.svg" "$prefix"/voxels-*.json
} > "$tmp/table.md"
mv "$tmp/table.md" "$prefix.md"
echo "wrote $prefix.md, $prefix-triangles.svg, $prefix-voxels.svg"
