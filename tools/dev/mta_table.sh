#!/usr/bin/env bash
# mta_table.sh TESSERA MODEL OUT [BUILD OPTION...]: one row of the atlas tree's data-set table.
#
# Builds MODEL's atlas tree with the given `mta build` options into OUT/tree.mta, then takes every column
# of the closing tables of issue 14 from the commands' own JSON, never from timing this script:
#   build seconds and peak RSS    mta build's info JSON (build.seconds, build.peak_resident_bytes)
#   file size, nodes, depth       the same JSON (file_bytes, trees[].nodes / depth)
#   binds per frame, residency    mta render --frames FRAMES (texture_binds, bytes_resident vs capacity)
#   violations                    texel --budget unlimited (isotropic and per axis, every block resident)
#   PSNR                          mta runs (the atlas tree's frames against original textures)
# Prints OUT/row.json and one Markdown table row. FRAMES (default 300), SIZE (default 1024x768) and
# TEXEL_FRAMES (default 60) come from the environment, and MEMORY_BUDGET (default 4GiB), the oracle's
# --memory-budget: run 1 of `mta runs` uploads every visible original (6.1 GiB a frame on berlin 10,000).
# REUSE=1 skips each step whose output is already in OUT (tree.mta with build.json, the build's printed
# JSON; render/frames.json; texel/texel.json), e.g. a build too long to repeat. A failing command stops
# the script (set -e) with its own message; its outputs stay in OUT for a look.
#
#   tools/dev/mta_table.sh build/tessera data/railway.glb /tmp/t/railway --d-min 5
#   tools/dev/mta_table.sh build/tessera data/railway.glb /tmp/t/railway-raw --d-min 5 --raw
set -euo pipefail
usage() { sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; }
if [ "${1:-}" = "-h" ] || [ "${1:-}" = "--help" ]; then usage; exit 0; fi
if [ $# -lt 3 ]; then usage >&2; echo "mta_table: expected at least 3 arguments, got $#" >&2; exit 2; fi
T=$(realpath "$1") MODEL=$2 OUT=$3
shift 3
FRAMES=${FRAMES:-300} SIZE=${SIZE:-1024x768} TEXEL_FRAMES=${TEXEL_FRAMES:-60} MEMORY_BUDGET=${MEMORY_BUDGET:-4GiB}
have() { [ "${REUSE:-0}" = 1 ] && [ -s "$OUT/$1" ] && echo "mta_table: reusing $OUT/$1" >&2; }
mkdir -p "$OUT"
have tree.mta && have build.json || "$T" mta build "$MODEL" -o "$OUT/tree.mta" --quiet "$@" > "$OUT/build.json"
have render/frames.json || "$T" mta render "$OUT/tree.mta" --frames "$FRAMES" --size "$SIZE" --save-every 0 \
  --memory-budget "$MEMORY_BUDGET" -o "$OUT/render" --quiet > /dev/null
have texel/texel.json || "$T" texel "$OUT/tree.mta" --budget unlimited --frames "$TEXEL_FRAMES" --size "$SIZE" \
  --memory-budget "$MEMORY_BUDGET" -o "$OUT/texel" --quiet > /dev/null
"$T" mta runs "$OUT/tree.mta" --frames "$TEXEL_FRAMES" --size "$SIZE" --save-every 0 --memory-budget "$MEMORY_BUDGET" \
  -o "$OUT/runs" --quiet > "$OUT/runs.json"
python3 - "$OUT" "$MODEL" "$*" <<'EOF'
import json, sys, os
out, model, options = sys.argv[1:4]
load = lambda p: json.load(open(os.path.join(out, p)))
b, r, runs = load('build.json'), load('render/frames.json'), load('runs.json')
t = load('texel/texel.json')['summary']
frames = r['frames']
resident_over_capacity = max(f['bytes_resident'] / f['capacity_bytes'] for f in frames)
row = {
    'model': model, 'options': options,
    'build_seconds': b['build']['seconds'], 'peak_rss_bytes': b['build']['peak_resident_bytes'],
    'file_bytes': b['file_bytes'], 'nodes': sum(x['nodes'] for x in b['trees']),
    'depth': max(x['depth'] for x in b['trees']),
    'binds_max': r['summary']['texture_binds_max'], 'binds_mean': r['summary']['texture_binds_mean'],
    'peak_bytes_resident': r['summary']['peak_bytes_resident'], 'capacity_bytes': r['summary']['capacity_bytes'],
    'decoded_bytes_resident_max': max((f.get('decoded_bytes_resident', 0) for f in frames), default=0),
    'max_resident_over_capacity': resident_over_capacity,
    'frames_with_needed_blocks_missing': r['summary']['frames_with_needed_blocks_missing'],
    'violations_isotropic': t['magnification_violations_when_every_needed_block_resident'],
    'violations_per_axis': t['per_axis_magnification_violations_when_every_needed_block_resident'],
    'psnr_db_mean': runs['atlas_tree']['psnr_db_mean_finite'], 'psnr_db_min': runs['atlas_tree']['psnr_db_min'],
}
json.dump(row, open(os.path.join(out, 'row.json'), 'w'), indent=2)
gib = lambda x: x / 2**30
print(f"| {os.path.basename(model)} {options} | {row['build_seconds']:.0f} s | {gib(row['peak_rss_bytes']):.2f} GiB | "
      f"{row['file_bytes']:,} B | {row['nodes']:,} (depth {row['depth']}) | {row['binds_max']:.0f} / {row['binds_mean']:.1f} | "
      f"{row['peak_bytes_resident']/1e6:.1f} / {row['capacity_bytes']/1e6:.1f} MB (decoded {row['decoded_bytes_resident_max']/1e6:.1f} MB) | "
      f"{row['violations_isotropic']} / {row['violations_per_axis']} | {row['psnr_db_mean']:.2f} (min {row['psnr_db_min']:.2f}) dB |")
EOF
