#!/usr/bin/env bash
# Compares two renders of the same scene (Cycles against Vesper) as
# bench/cycles/README.md reports them: the ratio of image means and the range
# of 16x16-pixel block mean ratios, on Rec.709 luminance.
#   bench/cycles/compare_images.sh CYCLES.exr VESPER.exr [BLOCK]
# Prints: mean_ratio=… block_ratio_min=… block_ratio_max=… blocks=N
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 CYCLES.exr VESPER.exr [BLOCK]" >&2; exit 2; }
block=${3:-16}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
read -r w h < <(oiiotool --info "$1" | sed -E 's/.*: *([0-9]+) x +([0-9]+).*/\1 \2/')
bw=$((w / block)) bh=$((h / block))
[ "$bw" -ge 1 ] && [ "$bh" -ge 1 ] || { echo "$1: smaller than one ${block}px block" >&2; exit 2; }
for i in 1 2; do
  f=${!i}
  # Luminance, cropped to whole blocks, then block means (box filter, integer factor).
  oiiotool "$f" --ch R,G,B --chsum:weight=0.2126,0.7152,0.0722 \
    --cut "$((bw * block))x$((bh * block))+0+0" -o "$tmp/y$i.exr"
  oiiotool "$tmp/y$i.exr" --resize:filter=box "${bw}x${bh}" -o "$tmp/b$i.exr"
done
avg() { oiiotool --stats "$1" | awk '/Stats Avg/ {print $3}'; }
m1=$(avg "$tmp/y1.exr") m2=$(avg "$tmp/y2.exr")
oiiotool "$tmp/b1.exr" "$tmp/b2.exr" --div -o "$tmp/ratio.exr"
read -r lo hi < <(oiiotool --stats "$tmp/ratio.exr" | awk '/Stats Min/ {lo=$3} /Stats Max/ {hi=$3} END {print lo, hi}')
awk -v a="$m1" -v b="$m2" -v lo="$lo" -v hi="$hi" -v n=$((bw * bh)) \
  'BEGIN {printf "mean_ratio=%.4f block_ratio_min=%.4f block_ratio_max=%.4f blocks=%d\n", a / b, lo, hi, n}'
