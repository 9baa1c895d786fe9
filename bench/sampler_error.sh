#!/usr/bin/env bash
# Error per sample of two or more samplers, side by side in one run: each is
# a `vesper` binary (e.g. one built before the sampler changed). Every example
# scene is rendered on a reduced film at each spp with several seeds, the
# binaries interleaved, and compared with one high-spp reference (made by the
# last binary, another seed). Prints per scene and spp the mean relMSE
# (DESIGN.md's definition, bench/vesper_relmse) of each binary, its ratio to
# the first binary's, and the equal-error time ratio against the first:
#   (t_first * relMSE_first / relMSE_this) / t_this
# i.e. the time the first binary needs to reach this binary's error (its
# relMSE ~ 1/spp: the first binary must be the independent-random sampler)
# over the time this one took. Times are process CPU seconds (user + sys),
# less sensitive to other load than wall time, less the CPU seconds of the
# same binary rendering the scene on a 1x1 film at 1 spp (start-up and scene
# loading: about 0.5 s even for `vesper --version`).
#
#   bench/sampler_error.sh LABEL=BINARY LABEL=BINARY... 
# Environment: SCENES (default: every example scene), SPPS ("16 64 256"),
#   SEEDS (repeats, 4), REF_SPP (4096), SCALE (film scale, 0.5),
#   OUT (work directory, kept: references are reused; default /tmp/vesper-sampler-error)
set -euo pipefail
cd "$(dirname "$0")/.."
relmse=./build/bench/vesper_relmse
scenes=${SCENES:-"cornell fog-shafts cloud smoke night-room"}
spps=${SPPS:-"16 64 256"}
seeds=${SEEDS:-4}
ref_spp=${REF_SPP:-4096}
scale=${SCALE:-0.5}
out=${OUT:-/tmp/vesper-sampler-error}
labels=() bins=()
for a in "$@"; do labels+=("${a%%=*}") bins+=("${a#*=}"); done
((${#bins[@]} >= 1)) || { echo "usage: $0 LABEL=BINARY..." >&2; exit 2; }
mkdir -p "$out"

# A copy of the scene with a scaled film and absolute file paths.
scene_copy() {  # scene-dir copy.json [film scale]
  python3 - "$1" "$2" "${3:-$scale}" <<'PY'
import json, os, sys
src, dst, scale = sys.argv[1], sys.argv[2], float(sys.argv[3])
d = json.load(open(os.path.join(src, "scene.json")))
d["film"]["width"] = max(1, round(d["film"]["width"] * scale))
d["film"]["height"] = max(1, round(d["film"]["height"] * scale))
def fix(n):
    if isinstance(n, dict):
        for k, v in n.items():
            if k == "file" and isinstance(v, str):
                n[k] = os.path.abspath(os.path.join(src, v))
            else:
                fix(v)
    elif isinstance(n, list):
        for v in n: fix(v)
fix(d)
json.dump(d, open(dst, "w"))
PY
}

cpu_render() {  # binary scene spp seed out.exr -> CPU seconds on stdout
  local TIMEFORMAT='%U %S'
  { time "$1" render "$2" --spp "$3" --seed "$4" -o "$5" -q >/dev/null; } 2>&1 | awk '{print $1 + $2}'
}

for s in $scenes; do
  scene=$out/$s.json
  if [[ $s == cloud && ! -f scenes/cloud/cloud.vdb && ! -f $out/cloud.vdb ]]; then
    "${bins[-1]}" vdb cloud -o "$out/cloud.vdb" -q >/dev/null
  fi
  if [[ $s == smoke && ! -f ../shared/data/smoke.vdb ]]; then
    echo "$s: skipped (../shared/data/smoke.vdb absent)"; continue
  fi
  scene_copy "scenes/$s" "$scene"
  scene_copy "scenes/$s" "$out/$s-1px.json" 0
  [[ $s == cloud && ! -f scenes/cloud/cloud.vdb ]] &&
    sed -i "s|\"[^\"]*cloud.vdb\"|\"$out/cloud.vdb\"|" "$scene" "$out/$s-1px.json"
  declare -A base=()
  for i in "${!bins[@]}"; do
    base[$i]=$(for r in 1 2 3; do cpu_render "${bins[$i]}" "$out/$s-1px.json" 1 1 "$out/1px.exr"; done |
      sort -g | sed -n 2p)
  done
  ref=$out/$s-ref$ref_spp.exr
  [[ -f $ref ]] || "${bins[-1]}" render "$scene" --spp "$ref_spp" --seed 987654 -o "$ref" -q >/dev/null
  echo "$s (film x$scale, reference $ref_spp spp by ${labels[-1]}, $seeds seeds)"
  printf '  %5s %-10s %12s %8s %9s %11s\n' spp sampler relMSE ratio "cpu [s]" "equal-err t"
  for spp in $spps; do
    declare -A err=() cpu=()
    for ((r = 1; r <= seeds; r++)); do
      for i in "${!bins[@]}"; do
        img=$out/$s-$i-$spp-$r.exr
        c=$(awk "BEGIN {print $(cpu_render "${bins[$i]}" "$scene" "$spp" "$r" "$img") - ${base[$i]}}")
        e=$($relmse "$ref" "$img" | awk '{print $1}')
        err[$i]=$(awk "BEGIN {print ${err[$i]:-0} + $e / $seeds}")
        cpu[$i]=$(awk "BEGIN {print ${cpu[$i]:-0} + $c / $seeds}")
        rm -f "$img"
      done
    done
    for i in "${!bins[@]}"; do
      awk -v spp="$spp" -v l="${labels[$i]}" -v e="${err[$i]}" -v t="${cpu[$i]}" \
        -v e0="${err[0]}" -v t0="${cpu[0]}" 'BEGIN {
          printf "  %5d %-10s %12.5g %7.2fx %9.2f %10.2fx\n", spp, l, e, e0 / e, t, (t0 * e0 / e) / t }'
    done
    unset err cpu
  done
  unset base
done
