#!/usr/bin/env bash
# The farm's overhead: the same frame rendered directly (`vesper render`) and
# through a local farm (`vesper up`: server, workers, blob upload, task
# directory, child render, upload, fetch; no composite), interleaved in one
# run so machine load hits both alike. Prints the median wall times and the
# ratios farm / direct.
#   bench/farm_overhead.sh [SCENE] [ROUNDS] [SPLIT]
#   (default: the night-room demo, 3 rounds, the 2-worker run split into
#   tasks of 32 samples = the demo's 64 spp in two)
set -euo pipefail
cd "$(dirname "$0")/.."
vesper=./build/cli/vesper
scene=${1:-scenes/night-room/scene.json}
rounds=${2:-3}
split=${3:-32}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

now() { date +%s.%N; }
declare -a direct up1 up2
for ((i = 0; i < rounds; i++)); do
  t0=$(now)
  $vesper render "$scene" --frame 1 -o "$work/direct.exr" -q >/dev/null
  t1=$(now)
  $vesper up --scene "$scene" --workers 1 --no-comp --data-dir "$work/farm1-$i" -o "$work/out1-$i" \
    >/dev/null 2>"$work/up1.log"
  t2=$(now)
  $vesper up --scene "$scene" --workers 2 --split "$split" --no-comp --data-dir "$work/farm2-$i" -o "$work/out2-$i" \
    >/dev/null 2>"$work/up2.log"
  t3=$(now)
  direct+=("$(awk "BEGIN {print $t1 - $t0}")")
  up1+=("$(awk "BEGIN {print $t2 - $t1}")")
  up2+=("$(awk "BEGIN {print $t3 - $t2}")")
  echo "round $((i + 1)): direct ${direct[-1]} s, farm 1 worker ${up1[-1]} s, farm 2 workers (frame split in 2) ${up2[-1]} s" >&2
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
d=$(median "${direct[@]}")
u1=$(median "${up1[@]}")
u2=$(median "${up2[@]}")
printf 'scene %s, %d rounds, %d cores\n' "$scene" "$rounds" "$(nproc)"
printf 'median  direct %.2f s | farm, 1 worker %.2f s (x%.3f) | farm, 2 workers %.2f s (x%.3f)\n' \
  "$d" "$u1" "$(awk "BEGIN {print $u1 / $d}")" "$u2" "$(awk "BEGIN {print $u2 / $d}")"
