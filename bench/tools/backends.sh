#!/usr/bin/env bash
# Fragment against compute on this machine (bench/reports/THROUGHPUT.md, "Fragment against compute on
# llvmpipe"): `glint render --backend ...` at 256x256, variants interleaved, ROUNDS rounds; prints
# one line per run (variant, spp/s) and the medians. Usage: bench/tools/backends.sh GLINT PROJECT [SPP] [ROUNDS]
set -euo pipefail
glint=$1 project=$2 spp=${3:-32} rounds=${4:-5}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
export XDG_CACHE_HOME=$out/cache  # forced backends write no cache; keep the user's alone anyway
variants=("fragment" "compute 8x8" "compute 16x16" "compute 8x4" "compute 32x1")
for round in $(seq "$rounds"); do
  for v in "${variants[@]}"; do
    set -- $v
    args=(--backend "$1")
    [ $# -gt 1 ] && args+=(--work-group "$2")
    rate=$("$glint" render "$project" -o "$out/x.exr" --width 256 --height 256 --spp "$spp" "${args[@]}" 2>&1 |
           sed -n 's/.* s, \([0-9.]*\) spp\/s.*/\1/p')
    echo "$round,$v,$rate" | tee -a "$out/runs.csv"
  done
done
echo "medians (spp/s):"
for v in "${variants[@]}"; do
  grep ",$v," "$out/runs.csv" | cut -d, -f3 | sort -g | awk -v v="$v" '{a[NR]=$1} END {printf "  %-14s %s\n", v, (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'
done
