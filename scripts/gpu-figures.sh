#!/usr/bin/env bash
# The figures a software rasteriser cannot settle, measured on this machine's GPU in one run
# with its own timer queries, each a ratio of two sides drawn alternately in that run.
# Writes results-gpu.md, the bench's CSVs beside it and every render's numbers (runs.csv).
# Builds nothing: it takes a built shadowmap. docs/gpu.md says what each row means.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/gpu-figures.sh [BIN] --out DIR [--quick] [--rounds N] [--frames N]
                              [--size WxH] [--limit SECONDS]

Measures, on the GL driver the binary finds (its renderer is printed first):
  the bench's quick sweep on dummy and on learnopengl --view code (--fit scene), with the
  comparison against the tutorials and the presets' rule redone on the GPU's timer queries;
  osm, fom and avsm against the opaque map, with the maps kept and redrawn (smoke);
  vssm and msm-soft against pcf5x5 and pcss with the map redrawn (playground, 1024^2 map);
  large --cascades 4 instanced against one draw per item (SHADOWMAP_INSTANCING=off);
  the shadow cache's static frame against the frame drawn from scratch (learnopengl).
Each render row runs `shadowmap render --frames N` for its sides in turn, the order
reversed every other round, and reports the ratio of the sides' medians.

  BIN              a built shadowmap (default: $SHADOWMAP_BIN, else target/release/shadowmap
                   of this checkout)
  --out DIR        folder for results-gpu.md, bench-dummy.csv, bench-learnopengl.csv, their
                   bench.md and pareto.png, and runs.csv (created if missing; required)
  --quick          check the run's shape, not its figures: 320x180 frames, 4 frames a render,
                   3 rounds, the bench at 160x90 with 3 frames a block (under 2 minutes on
                   llvmpipe with 2 cores)
  --rounds N       rounds of alternation (default 5; --quick 3)
  --frames N       frames a render, the first not counted, at least 2 (default 60; --quick 4)
  --size WxH       frame size of every render row (default: each scene's own; --quick
                   320x180); the bench keeps the scenes' sizes (--quick 160x90)
  --limit SECONDS  stop with an error when the run takes longer (default 480)
  -h, --help       this text
EOF
}

die() {
  echo "gpu-figures: $*" >&2
  exit 1
}

repo=$(cd "$(dirname "$0")/.." && pwd)
bin="${SHADOWMAP_BIN:-$repo/target/release/shadowmap}"
out="" quick=0 rounds="" frames="" size="" limit=480 positional=0

need_value() {
  [ $# -ge 2 ] && [ -n "$2" ] || die "$1 needs a value (scripts/gpu-figures.sh --help)"
}
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --quick) quick=1 ;;
    --out) need_value "$@"; out=$2; shift ;;
    --out=*) out=${1#--out=} ;;
    --rounds) need_value "$@"; rounds=$2; shift ;;
    --rounds=*) rounds=${1#--rounds=} ;;
    --frames) need_value "$@"; frames=$2; shift ;;
    --frames=*) frames=${1#--frames=} ;;
    --size) need_value "$@"; size=$2; shift ;;
    --size=*) size=${1#--size=} ;;
    --limit) need_value "$@"; limit=$2; shift ;;
    --limit=*) limit=${1#--limit=} ;;
    -*) die "unknown flag $1 (scripts/gpu-figures.sh --help)" ;;
    *)
      [ $positional = 0 ] || die "one binary only, got a second: $1"
      bin=$1 positional=1
      ;;
  esac
  shift
done

# Everything is checked before anything is written.
whole() { case "$1" in '' | *[!0-9]*) return 1 ;; *) [ "$1" -ge "$2" ] ;; esac; }
[ -n "$out" ] || die "--out DIR is required: where results-gpu.md goes"
[ ! -e "$out" ] || [ -d "$out" ] || die "--out $out: exists and is not a folder"
if [ $quick = 1 ]; then
  : "${rounds:=3}" "${frames:=4}" "${size:=320x180}"
  bench_flags=(--size 160x90 --frames 3 --warmup 1 --supersample 1)
else
  : "${rounds:=5}" "${frames:=60}"
  bench_flags=()
fi
whole "$rounds" 1 || die "--rounds $rounds: expected a whole number, at least 1"
whole "$frames" 2 || die "--frames $frames: expected a whole number, at least 2 (the first frame is not counted)"
whole "$limit" 1 || die "--limit $limit: expected whole seconds, at least 1"
case "$size" in '' | [1-9]*x[1-9]*) ;; *) die "--size $size: expected WxH, e.g. 1280x720" ;; esac
case "${size#*x}" in *[!0-9]*) die "--size $size: expected WxH, e.g. 1280x720" ;; esac
case "${size%x*}" in *[!0-9]*) die "--size $size: expected WxH, e.g. 1280x720" ;; esac
[ -f "$bin" ] && [ -x "$bin" ] || die "not an executable file: $bin (build it with cargo build --release, or pass its path)"
if command -v timeout >/dev/null; then bound=timeout
elif command -v gtimeout >/dev/null; then bound=gtimeout
else die "needs timeout (GNU coreutils) to bound the run"; fi
for tool in awk sort sed; do command -v $tool >/dev/null || die "needs $tool"; done
version=$("$bound" 20 "$bin" --version 2>&1) || die "$bin --version failed: $version"

start=$SECONDS
deadline=$((SECONDS + limit))
mkdir -p "$out"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
log="$scratch/step.log"

# Runs a command under what is left of the limit; its output goes to $log.
step=0 steps=0
bounded() {
  local what=$1 left
  shift
  step=$((step + 1))
  left=$((deadline - SECONDS))
  [ $left -gt 0 ] || die "stopped before step $step/$steps ($what): the run took its --limit of $limit s"
  echo "[$step/$steps] $what" >&2
  local rc=0
  "$bound" -k 5 "$left" "$@" >"$log" 2>&1 || rc=$?
  if [ $rc = 124 ] || [ $rc = 137 ]; then
    die "stopped during step $step/$steps ($what): the run took its --limit of $limit s"
  elif [ $rc != 0 ]; then
    tail -n 20 "$log" >&2
    die "step $step/$steps ($what) failed (exit $rc): $*"
  fi
}

# The render sides: name | SHADOWMAP_INSTANCING | arguments. A group's sides are drawn in
# turn, one render each a round.
smoke=(
  "smoke/shadows-off|on|--scene smoke --shadows off"
  "smoke/off-kept|on|--scene smoke --volumetric off"
  "smoke/osm-kept|on|--scene smoke --volumetric osm"
  "smoke/fom-kept|on|--scene smoke --volumetric fom"
  "smoke/avsm-kept|on|--scene smoke --volumetric avsm"
  "smoke/off-redrawn|on|--scene smoke --volumetric off --shadow-cache off"
  "smoke/osm-redrawn|on|--scene smoke --volumetric osm --shadow-cache off"
  "smoke/fom-redrawn|on|--scene smoke --volumetric fom --shadow-cache off"
  "smoke/avsm-redrawn|on|--scene smoke --volumetric avsm --shadow-cache off"
)
soft=(
  "soft/shadows-off|on|--scene playground --shadows off"
  "soft/pcf5x5|on|--scene playground --map-size 1024 --filter pcf5x5 --shadow-cache off"
  "soft/pcss|on|--scene playground --map-size 1024 --filter pcss --shadow-cache off"
  "soft/vssm|on|--scene playground --map-size 1024 --filter vssm --shadow-cache off"
  "soft/msm-soft|on|--scene playground --map-size 1024 --filter msm-soft --shadow-cache off"
)
instancing=(
  "large/instanced|on|--scene large --cascades 4 --shadow-cache off"
  "large/one-draw-per-item|off|--scene large --cascades 4 --shadow-cache off"
)
cache=(
  "cache/shadows-off|on|--scene learnopengl --shadows off"
  "cache/on|on|--scene learnopengl"
  "cache/off|on|--scene learnopengl --shadow-cache off"
)
groups=(smoke soft instancing cache)
sides=$((${#smoke[@]} + ${#soft[@]} + ${#instancing[@]} + ${#cache[@]}))
steps=$((1 + 2 + rounds * sides))

size_flags=()
[ -z "$size" ] || size_flags=(--size "$size")

# 1. The driver, from a render's GPU line.
bounded "the GL renderer" env SHADOWMAP_INSTANCING=on "$bin" render --scene dummy --size 64x64 \
  --frames 2 --out "$scratch/probe.png"
renderer=$(sed -n 's/^GPU time over .*(timer queries; \(.*\))$/\1/p' "$log")
[ -n "$renderer" ] || die "the binary printed no GPU time line (a shadowmap older than its timer queries?)"
echo "GL renderer: $renderer" >&2

# 2. The bench's quick sweeps.
bench() {
  local name=$1
  shift
  bounded "bench $name: $* --quick --fit scene" env SHADOWMAP_INSTANCING=on "$bin" bench "$@" \
    --quick --fit scene ${bench_flags[@]+"${bench_flags[@]}"} --out-dir "$scratch/$name"
  cp "$scratch/$name/bench.csv" "$out/bench-$name.csv"
  cp "$scratch/$name/bench.md" "$out/bench-$name.md"
  cp "$scratch/$name/pareto.png" "$out/bench-$name-pareto.png"
  # The bench's own comparison with the tutorials and its presets' rule (wall time).
  sed -n '/^against /,$p' "$log" | grep -v '^wrote ' >"$scratch/$name.text" || true
}
bench dummy --scene dummy
bench learnopengl --scene learnopengl --view code

# 3. The render rows, the sides of each group in turn, reversed every other round.
runs="$out/runs.csv"
echo "side,round,wall_ms,gpu_frame_ms,gpu_depth_ms,gpu_scene_ms,maps_drawn,maps_kept,translucent_drawn,translucent_kept" >"$runs"
render_side() {
  local spec=$1 round=$2 name inst args
  IFS='|' read -r name inst args <<<"$spec"
  # shellcheck disable=SC2086 # the arguments are words
  bounded "render $name (round $round of $rounds): $args" env SHADOWMAP_INSTANCING="$inst" \
    "$bin" render $args ${size_flags[@]+"${size_flags[@]}"} --frames "$frames" --out "$scratch/frame.png"
  awk -v side="$name" -v round="$round" '
    # "frame time over N frames after the first: median W ms, ..."
    /^frame time over / { for (i = 1; i <= NF; i++) if ($i == "median" && wall == "") wall = $(i + 1) }
    # "GPU time over N frames after the first: median F ms a frame (depth passes D ms,
    # scene pass S ms), ..."
    /^GPU time over / {
      for (i = 1; i <= NF; i++) {
        if ($i == "median" && frame == "") frame = $(i + 1)
        if ($i == "passes" && depth == "") depth = $(i + 1)
        if ($i == "pass" && scene == "") scene = $(i + 1)
      }
    }
    # "D drawn whole, P patched where casters moved (...), K kept unchanged"
    /^shadow-map passes over / {
      for (i = 1; i < NF; i++) {
        if ($(i + 1) == "drawn" || $(i + 1) == "patched") drawn += $i
        if ($(i + 1) == "kept") kept = $i
      }
    }
    # "D drawn, K kept unchanged"
    /^translucent maps over / {
      for (i = 1; i < NF; i++) {
        if ($(i + 1) == "drawn,") tdrawn = $i
        if ($(i + 1) == "kept") tkept = $i
      }
    }
    END {
      if (wall == "" || frame == "") exit 1
      printf "%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", side, round, wall, frame, depth, scene,
        drawn + 0, kept + 0, tdrawn + 0, tkept + 0
    }' "$log" >>"$runs" || { tail -n 20 "$log" >&2; die "render $name printed no frame or GPU time (its output above)"; }
}
for round in $(seq 1 "$rounds"); do
  for group in "${groups[@]}"; do
    eval "specs=(\"\${$group[@]}\")"
    n=${#specs[@]}
    for k in $(seq 0 $((n - 1))); do
      # Odd rounds forward, even rounds backward: neither side always comes first.
      [ $((round % 2)) = 1 ] && i=$k || i=$((n - 1 - k))
      render_side "${specs[$i]}" "$round"
    done
  done
done

# 4. Each side's medians over its rounds: side,wall,frame,depth,scene,maps and translucent
#    maps drawn / kept (summed).
sides_csv="$scratch/sides.csv"
: >"$sides_csv"
median() {
  awk -F, -v s="$1" -v c="$2" '$1 == s { print $c }' "$runs" | sort -g | awk '
    { v[NR] = $1 }
    END { if (NR % 2) print v[(NR + 1) / 2]; else print (v[NR / 2] + v[NR / 2 + 1]) / 2 }'
}
for name in $(tail -n +2 "$runs" | cut -d, -f1 | awk '!seen[$0]++'); do
  sums=$(awk -F, -v s="$name" '$1 == s { a += $7; b += $8; c += $9; d += $10 }
    END { printf "%d,%d,%d,%d", a, b, c, d }' "$runs")
  echo "$name,$(median "$name" 3),$(median "$name" 4),$(median "$name" 5),$(median "$name" 6),$sums" >>"$sides_csv"
done

# A row: measurement | A | B | the frame without shadows both are measured against (or -).
render_rows=(
  "avsm, maps kept|smoke/avsm-kept|smoke/off-kept|smoke/shadows-off"
  "avsm, maps redrawn|smoke/avsm-redrawn|smoke/off-redrawn|smoke/shadows-off"
  "fom, maps kept|smoke/fom-kept|smoke/off-kept|smoke/shadows-off"
  "fom, maps redrawn|smoke/fom-redrawn|smoke/off-redrawn|smoke/shadows-off"
  "osm, maps kept|smoke/osm-kept|smoke/off-kept|smoke/shadows-off"
  "osm, maps redrawn|smoke/osm-redrawn|smoke/off-redrawn|smoke/shadows-off"
  "vssm vs pcf5x5, map redrawn|soft/vssm|soft/pcf5x5|soft/shadows-off"
  "msm-soft vs pcf5x5, map redrawn|soft/msm-soft|soft/pcf5x5|soft/shadows-off"
  "vssm vs pcss, map redrawn|soft/vssm|soft/pcss|soft/shadows-off"
  "msm-soft vs pcss, map redrawn|soft/msm-soft|soft/pcss|soft/shadows-off"
  "large --cascades 4, instanced vs one draw per item|large/instanced|large/one-draw-per-item|-"
  "shadow cache, static frame (on vs off)|cache/on|cache/off|cache/shadows-off"
)
render_table() {
  echo "| measurement | ratio (GPU frame, A / B) | A | B | GPU ms a frame, A: depth + scene | GPU ms a frame, B: depth + scene | depth passes' GPU ratio | shadow overhead's GPU ratio | wall ms A / B | wall ratio | maps drawn / kept over the rounds, A; B |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|"
  local row
  for row in "${render_rows[@]}"; do
    awk -F, -v row="$row" '
      { side[$1] = $0 }
      function ratio(a, b) { return (b > 0 && a >= 0) ? sprintf("%.3f", a / b) : "n/a" }
      function maps(s,   f) {
        split(side[s], f, ",")
        if (f[8] + f[9] > 0) return sprintf("%d / %d (translucent %d / %d)", f[6], f[7], f[8], f[9])
        return sprintf("%d / %d", f[6], f[7])
      }
      END {
        split(row, r, "|")
        for (k = 2; k <= 4; k++) if (r[k] != "-" && !(r[k] in side)) {
          print "gpu-figures: the row \"" r[1] "\" needs side " r[k] ", which was not measured" > "/dev/stderr"
          exit 1
        }
        split(side[r[2]], a, ","); split(side[r[3]], b, ",")
        over = "-"
        if (r[4] != "-") {
          split(side[r[4]], p, ",")
          over = ratio(a[3] - p[3], b[3] - p[3])
        }
        printf "| %s | %s | `%s` | `%s` | %.3f + %.3f = %.3f | %.3f + %.3f = %.3f | %s | %s | %.2f / %.2f | %s | %s; %s |\n",
          r[1], ratio(a[3], b[3]), r[2], r[3], a[4], a[5], a[3], b[4], b[5], b[3],
          ratio(a[4], b[4]), over, a[2], b[2], ratio(a[2], b[2]), maps(r[2]), maps(r[3])
      }' "$sides_csv" || exit 1
  done
}

# 5. The bench's rows, redone on the GPU's timer queries: the tutorials' comparisons and the
#    presets' rule (docs/results.md) with the GPU overhead in place of the wall overhead.
bench_table() {
  local name=$1 title=$2
  awk -F, -v scene="$title" '
    NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i; next }
    {
      n++
      tut[n] = $col["tutorial"]
      fam[n] = $col["family"]
      # The error the bench ranks by: the MAE against the area truth for a light with a
      # size, else the misclassified fraction.
      area[n] = $col["area_rays"] > 0
      err[n] = area[n] ? $col["area_mae"] : $col["misclassified_rate"]
      gpu[n] = $col["depth_gpu_ms_median"] + $col["scene_gpu_ms_median"]
      ogpu[n] = $col["overhead_gpu_ms"]
      owall[n] = $col["overhead_ms"]
      front[n] = $col["pareto"]
      size = $col["map_size"]
      if (fam[n] == "cascades") size = $col["cascades"] "x" size
      if (fam[n] == "groups") size = $col["caster_groups"] "x" size
      label[n] = size " " $col["filter"] " " $col["bias_preset"] " cull-" $col["cull"] " " $col["depth_format"]
      if (fam[n] != "onemap") label[n] = label[n] " " fam[n]
      if (fam[n] == "volumes") label[n] = "stencil shadow volumes"
    }
    function ratio(a, b) { return (b > 0 && a > 0) ? sprintf("%.3f", a / b) : "n/a" }
    function pct(i) { return area[i] ? sprintf("MAE %.4f", err[i]) : sprintf("%.3f%%", err[i] * 100) }
    function row(what, a, b, wallpick) {
      if (a == 0) {
        printf "| %s | n/a | none | %s | | | | |\n", what, label[b]
        return
      }
      printf "| %s | %s | %s | %s | %.3f / %.3f | %.3f / %.3f | %s / %s | %s |\n", what,
        ratio(gpu[a], gpu[b]), label[a], label[b], gpu[a], gpu[b], ogpu[a], ogpu[b],
        pct(a), pct(b), (wallpick == a) ? "the same" : (wallpick ? label[wallpick] : "none")
    }
    # The least GPU (or wall) overhead at the error of row t or better.
    function at_error(t, wall,   i, best, v, bv) {
      best = 0
      for (i = 1; i <= n; i++) if (tut[i] == "-" && err[i] <= err[t]) {
        v = wall ? owall[i] : ogpu[i]; bv = wall ? owall[best] : ogpu[best]
        if (!best || v < bv || (v == bv && err[i] < err[best])) best = i
      }
      return best
    }
    # The least error at an overhead of at most budget (one-map rows only with onemap).
    function within(budget, wall, onemap,   i, best, v, bv) {
      best = 0
      for (i = 1; i <= n; i++) if (tut[i] == "-" && (!onemap || fam[i] == "onemap")) {
        v = wall ? owall[i] : ogpu[i]
        if (v > budget) continue
        bv = wall ? owall[best] : ogpu[best]
        if (!best || err[i] < err[best] || (err[i] == err[best] && v < bv)) best = i
      }
      return best
    }
    function least(wall, onemap,   i, best, v, bv) {
      best = 0
      for (i = 1; i <= n; i++) if (tut[i] == "-" && (!onemap || fam[i] == "onemap")) {
        v = wall ? owall[i] : ogpu[i]; bv = wall ? owall[best] : ogpu[best]
        if (!best || v < bv) best = i
      }
      return best
    }
    END {
      print "| measurement | ratio (GPU frame, A / B) | A | B | GPU ms a frame, A / B | GPU shadow overhead ms, A / B | error, A / B | the bench'"'"'s pick by wall overhead |"
      print "|---|---|---|---|---|---|---|---|"
      for (t = 1; t <= n; t++) {
        if (tut[t] == "-") continue
        row(scene ": at " tut[t] "'"'"'s error or better, least GPU overhead", at_error(t, 0), t, at_error(t, 1))
        row(scene ": at " tut[t] "'"'"'s GPU overhead or less, least error", within(ogpu[t], 0, 0), t, within(owall[t], 1, 0))
        if (tut[t] == "learnopengl") lo = t
      }
      if (lo) {
        row(scene ": preset low", least(0, 1), lo, least(1, 1))
        row(scene ": preset medium", within(0.5 * ogpu[lo], 0, 1), lo, within(0.5 * owall[lo], 1, 1))
        row(scene ": preset high", within(ogpu[lo], 0, 1), lo, within(owall[lo], 1, 1))
      }
      # The Pareto front of GPU overhead and error, against the bench'"'"'s of wall overhead.
      for (i = 1; i <= n; i++) {
        on = 1
        for (j = 1; j <= n; j++)
          if (ogpu[j] <= ogpu[i] && err[j] <= err[i] && (ogpu[j] < ogpu[i] || err[j] < err[i])) { on = 0; break }
        if (on) {
          gfront++
          if (front[i] == "true") both++
          names = names sprintf("%s%s (%.3f ms, %s)", gfront > 1 ? "; " : "", label[i], ogpu[i], pct(i))
        }
        if (front[i] == "true") wfront++
      }
      printf "\nThe Pareto front of %s (the configurations no other beats on both shadow overhead and error): %d by GPU overhead, %d by wall overhead (the bench'"'"'s), %d on both. By GPU overhead: %s.\n", scene, gfront, wfront, both + 0, names
    }' "$out/bench-$name.csv"
}

elapsed=$((SECONDS - start))
shown_size=${size:-"each scene's own"}
run_kind=""
[ $quick = 0 ] || run_kind="--quick, "
{
  echo "# GPU figures"
  echo
  echo "GL renderer: $renderer"
  echo
  echo "Binary: $version ($bin). Run: $run_kind$rounds rounds, $frames frames a render (the first not counted), frame size $shown_size; $elapsed s in all, by \`scripts/gpu-figures.sh\`."
  case "$renderer" in
    *llvmpipe* | *softpipe* | *SwiftShader* | *swrast* | *"Software Rasterizer"*)
      echo
      echo "This renderer is a software rasteriser, not a GPU: the run shows the table's shape, not a GPU's figures. It also rasterises a pass only when something reads its result, so its timer queries charge the depth passes to the scene pass and miss what it leaves to \`glFinish\` (a frame without shadows, or one that reads the shadow mask, reads near 0 ms): the wall columns are its figures."
      ;;
  esac
  echo
  echo "Every ratio is A's median over B's, both from this run. A render row's sides are drawn in turn, one \`shadowmap render --frames $frames\` each a round, the order reversed every other round; each side's figure is the median of its rounds' medians. \"GPU\" figures are \`GL_TIME_ELAPSED\` timer queries around the depth passes (every map, translucent ones too) and the scene pass; wall times are to \`glFinish\`. The shadow overhead's ratio is (A - the frame without shadows) over (B - the same). Every run's figures are in \`runs.csv\`."
  echo
  echo "## Renders"
  echo
  render_table
  for name in dummy learnopengl; do
    title=$name
    [ $name = dummy ] || title="learnopengl --view code"
    echo
    echo "## The bench's quick sweep on $title (--fit scene)"
    echo
    echo "All rows in [\`bench-$name.csv\`](bench-$name.csv) (\`overhead_gpu_ms\`: the frame's GPU time less the frame without shadows'; the bench's wall figures in [\`bench-$name.md\`](bench-$name.md)). B is the tutorial's configuration; the presets' rule is docs/results.md's, on the GPU overhead."
    echo
    bench_table "$name" "$title"
    echo
    echo "The bench's own comparison and presets, by wall overhead:"
    echo
    echo '```text'
    cat "$scratch/$name.text"
    echo '```'
  done
} >"$scratch/results-gpu.md"
mv "$scratch/results-gpu.md" "$out/results-gpu.md"
echo "wrote $out/results-gpu.md, bench-dummy.csv, bench-learnopengl.csv and runs.csv in $elapsed s" >&2
