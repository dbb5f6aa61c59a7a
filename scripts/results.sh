#!/usr/bin/env bash
# Makes the tables, plots and step pages that docs/results.md and the technique pages show,
# into assets/readme/, and writes assets/readme/COMMANDS.md naming the command behind each file.
#
#   scripts/results.sh BIN [JOB...]      run the jobs (all of them by default)
#   scripts/results.sh --list            print the jobs and their commands, run nothing
#
# BIN is a built shadowmap (cargo build --release; target/release/shadowmap). The jobs:
# dummy (the full sweep, about 12 minutes), learnopengl, large, volumes, scale, volumetric
# (a few minutes each), motion (the flicker tables, scripts/motion-figures.py, about 10
# minutes) and steps (seconds). OUT=DIR writes elsewhere than assets/readme.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${OUT:-assets/readme}"

# name | arguments | files the command writes -> names kept in $out
# (arguments "script X" run scripts/X BIN DIR/X.md instead of shadowmap)
jobs=(
  "dummy|bench --scene dummy|bench.csv->bench-dummy.csv bench.md->bench-dummy.md pareto.png->pareto-dummy.png"
  "learnopengl|bench --scene learnopengl --view code --quick --fit scene|bench.md->bench-learnopengl.md pareto.png->pareto-learnopengl.png"
  "large|bench --scene large --quick --size 640x360 --frames 40|bench.md->bench-large.md pareto.png->pareto-large.png"
  "volumes|bench --scene dummy --quick --size 640x360|bench.csv->bench-volumes-dummy.csv pareto.png->pareto-volumes-dummy.png"
  "scale|bench --scale|scale.csv->scale.csv scale-fit.csv->scale-fit.csv scale.png->scale.png"
  "volumetric|bench --scene smoke --quick --size 640x360 --frames 10 --warmup 3|bench.md->bench-smoke.md"
  "motion|script motion-figures.py|motion-figures.py.md->motion.md"
  "steps-dummy|steps --scene dummy --size 640x360|*->steps-dummy/"
  "steps-learnopengl|steps --scene learnopengl --size 800x600|*->steps-learnopengl/"
  "steps-playground|steps --scene playground|*->steps-playground/"
  "steps-smoke|steps --scene smoke --size 640x360|*->steps-smoke/"
)

commands_md() {
  echo "# The commands behind the files in this folder"
  echo
  echo "Written by \`scripts/results.sh\`; each command ran with \`--out-dir\` a scratch folder."
  echo
  echo "| file | command |"
  echo "|---|---|"
  for job in "${jobs[@]}"; do
    IFS='|' read -r _ args files <<<"$job"
    for f in $files; do
      case "$args" in
        script\ *) echo "| \`${f#*->}\` | \`scripts/${args#script } BIN\` (its tables) |" ;;
        *) echo "| \`${f#*->}\` | \`shadowmap $args --out-dir DIR\` (its \`${f%%->*}\`) |" ;;
      esac
    done
  done
}

if [ "${1:-}" = "--list" ]; then
  for job in "${jobs[@]}"; do
    IFS='|' read -r name args _ <<<"$job"
    case "$args" in
      script\ *) printf '%-18s scripts/%s BIN\n' "$name" "${args#script }" ;;
      *) printf '%-18s shadowmap %s --out-dir DIR\n' "$name" "$args" ;;
    esac
  done
  exit 0
fi

bin="${1:?usage: scripts/results.sh BIN [JOB...] | --list}"
shift
[ -x "$bin" ] || { echo "not an executable: $bin" >&2; exit 1; }
wanted=("$@")
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
ran=0
for job in "${jobs[@]}"; do
  IFS='|' read -r name args files <<<"$job"
  if [ ${#wanted[@]} -gt 0 ]; then
    match=0
    for w in "${wanted[@]}"; do
      # "steps" picks every steps-* job.
      [ "$w" = "$name" ] || [ "$name" = "${w}-${name#*-}" ] && match=1
    done
    [ $match = 1 ] || continue
  fi
  dir="$scratch/$name"
  case "$args" in
    script\ *)
      script="${args#script }"
      echo "== $name: scripts/$script BIN"
      mkdir -p "$dir"
      python3 "scripts/$script" "$bin" "$dir/$script.md"
      ;;
    *)
      echo "== $name: shadowmap $args --out-dir DIR"
      # shellcheck disable=SC2086 # the arguments are words
      "$bin" $args --out-dir "$dir"
      ;;
  esac
  for f in $files; do
    from="${f%%->*}" to="${f#*->}"
    if [ "$from" = "*" ]; then
      mkdir -p "$out/$to"
      cp "$dir"/* "$out/$to"
    else
      cp "$dir/$from" "$out/$to"
    fi
    echo "   -> $out/$to"
  done
  ran=$((ran + 1))
done
[ $ran -gt 0 ] || { echo "no such job: ${wanted[*]} (scripts/results.sh --list)" >&2; exit 1; }
commands_md >"$out/COMMANDS.md"
echo "wrote $out/COMMANDS.md"
