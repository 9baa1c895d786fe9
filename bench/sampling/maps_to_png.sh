#!/bin/sh
# Turns the per-pixel maps of `vesper_adaptive_bench --maps DIR` into PNGs
# (one strip per scene: reference, adaptive spp, adaptive error, uniform error).
#   bench/sampling/maps_to_png.sh DIR
# spp: sqrt(spp / 1024), errors: sqrt(20 x the pixel's relMSE term), both clamped
# to [0, 1] and shown with the inferno colour map; the reference as sqrt(luma).
set -eu
dir=$1
for maps in "$dir"/*-maps.exr; do
  out=${maps%-maps.exr}
  oiiotool "$maps" --ch ref_luma --clamp:min=0:max=1 --powc 0.5 --ch 0,0,0 -o "$out-ref.png"
  oiiotool "$maps" --ch spp --divc 1024 --clamp:min=0:max=1 --powc 0.5 --colormap inferno \
    -o "$out-spp.png"
  for err in err_adaptive err_uniform; do
    oiiotool "$maps" --ch $err --mulc 20 --clamp:min=0:max=1 --powc 0.5 --colormap inferno \
      -o "$out-$err.png"
  done
  oiiotool "$out-ref.png" "$out-spp.png" "$out-err_adaptive.png" "$out-err_uniform.png" \
    --mosaic:pad=4 4x1 -o "$out-strip.png"
done
