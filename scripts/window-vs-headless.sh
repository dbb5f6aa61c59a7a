#!/usr/bin/env bash
# The window figure of docs/results.md: the demo's frame time in a window (through GLX and through EGL)
# against headless `render --frames`, alternated in one run (the machine is noisy; compare
# the ratios, not the milliseconds). Needs a display (e.g. `Xvfb :99 &` and DISPLAY=:99).
#
#   scripts/window-vs-headless.sh BIN [SCENE] [ROUNDS] [FRAMES] [-- extra flags]
# e.g. scripts/window-vs-headless.sh target/release/shadowmap dummy 3 400 -- --size 1280x720
set -euo pipefail
bin=${1:?usage: $0 BIN [SCENE] [ROUNDS] [FRAMES] [-- extra flags]}
scene=${2:-learnopengl}
rounds=${3:-3}
frames=${4:-400}
shift $(($# < 4 ? $# : 4))
[ "${1:-}" = "--" ] && shift
[ -n "${DISPLAY:-}" ] || { echo "error: DISPLAY is not set: start Xvfb and set DISPLAY" >&2; exit 2; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

median() { grep -o 'median [0-9.]* ms' | awk '{print $2}'; }
declare -A sum
for r in $(seq "$rounds"); do
  line="round $r:"
  for side in glx egl headless; do
    if [ "$side" = headless ]; then
      ms=$("$bin" render --scene "$scene" --frames "$frames" --out "$out/h.png" "$@" 2>&1 | median)
    else
      ms=$("$bin" demo --scene "$scene" --exit-after-frames "$frames" --no-hud --no-animation \
        --gl-api "$side" "$@" 2>&1 | median)
    fi
    [ -n "$ms" ] || { echo "error: no frame time from the $side run" >&2; exit 1; }
    sum[$side]=$(awk -v a="${sum[$side]:-0}" -v b="$ms" 'BEGIN{print a+b}')
    line="$line $side $ms ms"
  done
  echo "$line"
done
awk -v g="${sum[glx]}" -v e="${sum[egl]}" -v h="${sum[headless]}" -v n="$rounds" 'BEGIN{
  printf "mean of medians: glx %.2f ms, egl %.2f ms, headless %.2f ms\n", g/n, e/n, h/n;
  printf "window/headless: glx %.3f, egl %.3f\n", g/h, e/h }'
