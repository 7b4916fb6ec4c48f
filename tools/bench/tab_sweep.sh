#!/usr/bin/env bash
# Sweeps Algorithm 1's limits (a_max, d_max, b_max) on a model with `tessera tab build` and prints a
# Markdown table of what each setting yields: output batches, geometry batches (= batched draw calls),
# arrays, the fullest array, b_average(B_O) and the texture bytes duplicated across output batches.
#   tools/bench/tab_sweep.sh [TESSERA] [MODEL]      (defaults: build/tessera, data/railway.glb)
set -euo pipefail
T=${1:-build/tessera}; M=${2:-data/railway.glb}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
row() {
  "$T" tab build "$M" -o "$tmp/s.tab" --quiet "$@" | python3 -c "
import json, sys
j = json.load(sys.stdin)
print('| %s | %d | %d | %d | %d | %.0f | %d |' % (' '.join(sys.argv[1:]), j['output_batches'], j['geometry_batches'],
      j['array_count'], max(a['layers'] for a in j['arrays']), j['b_average_output'], j['texture_bytes_duplicated']))" "$@"
}
echo "| setting | output batches | geometry batches (draws) | arrays | max layers | b_average(B_O) | bytes duplicated |"
echo "|---|---|---|---|---|---|---|"
for a in 1 2 4 8; do row --a-max "$a"; done
for d in 1 2 4 8 256; do row --d-max "$d"; done
for b in 4 3000 10000 40000 1048576; do row --b-max "$b"; done
