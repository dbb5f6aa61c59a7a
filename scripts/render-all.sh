#!/usr/bin/env bash
# render-all.sh BIN OUTDIR: every built-in scene x (scene's own + every step), plus extras.
set -u
bin=$1; out=$2; mkdir -p "$out"
scenes="dummy learnopengl slides playground point-shadows large three-lights"
steps=$($bin render --help | sed -n '/--step/,/--map-size/p' | tr '\n' ' ' | grep -o 'possible values: [^]]*' | head -1 | sed 's/possible values: //; s/[],[]//g')
# The smoke scene's steps (volumetric-*) belong to its own list alone.
steps=$(echo $steps | tr ' ' '\n' | grep -v '^volumetric-' | tr '\n' ' ')
[ -z "$steps" ] && steps="depth-map no-bias bias slope-bias cull-front over-sampling-repeat over-sampling-book over-sampling pcf hi-res perspective perspective-depth-map"
for s in $scenes; do
  $bin render --scene $s --size 640x360 --out $out/$s.png --shadow-out $out/$s-vis.png >/dev/null 2>>$out/errors.txt || echo "FAIL $s" >>$out/errors.txt
  for st in $steps; do
    $bin render --scene $s --size 640x360 --step $st --out $out/$s-$st.png >/dev/null 2>>$out/errors.txt || echo "FAIL $s $st" >>$out/errors.txt
  done
done
# extras: cascades, fitted box, filters, point passes, depth views
x() { name=$1; shift; $bin render --size 640x360 --out $out/x-$name.png "$@" >/dev/null 2>>$out/errors.txt || echo "FAIL x $name" >>$out/errors.txt; }
x large-c4 --scene large --cascades 4 --map-size 1024
x large-c4-show --scene large --cascades 4 --map-size 1024 --show-cascades
x large-c2-dm --scene large --cascades 2 --show-depth-map
x three-c4 --scene three-lights --cascades 4 --map-size 512
x three-dm --scene three-lights --show-depth-map
x dummy-fit --scene dummy --fit scene --light-view look-at
x dummy-hw2 --scene dummy --filter hw2x2 --normal-offset 1
x dummy-hw3 --scene dummy --filter hw3x3 --bias-mode slope
x dummy-5x5 --scene dummy --filter pcf5x5 --polygon-offset 1.1,4 --cull back
x point-six --scene point-shadows --point-pass six-passes
x point-soft --scene point-shadows --filter pcf3x3 --frames 5
x point-single --scene point-shadows --filter single --frames 5
x point-dm --scene point-shadows --show-depth-map
x learn-fit --scene learnopengl --fit scene
x learn-persp --scene learnopengl --light-projection perspective --filter hw2x2
x dummy-16 --scene dummy --depth-format 16 --wrap clamp-to-border --beyond-far lit
x dummy-32 --scene dummy --depth-format 32f --wrap repeat
x dummy-frames --scene dummy --frames 30 --light-angle 70
x slides-c3 --scene slides --cascades 3
x play-no --scene playground --normal-offset 2 --filter hw2x2
# moment filters, the soft filters, volumes, caster groups, the depth map read back
x dummy-vsm --scene dummy --filter vsm
x dummy-evsm2 --scene dummy --filter evsm2
x dummy-evsm4 --scene dummy --filter evsm4 --show-depth-map
x dummy-msm --scene dummy --filter msm
x play-msm --scene playground --filter msm --light-size 1
x play-pcss --scene playground --filter pcss --light-size 1
x play-soft --scene playground --filter soft-pcf
x play-w4 --scene playground --filter pcf4x4-weighted
x large-pcss --scene large --filter pcss
x slides-vol --scene slides --technique volumes
x dummy-vol --scene dummy --technique volumes --show-volumes
x three-vol --scene three-lights --technique volumes
x learn-g2 --scene learnopengl --caster-groups 2 --fit scene --filter hw2x2
x large-g4 --scene large --caster-groups 4
x large-g4-dm --scene large --caster-groups 4 --show-depth-map
x dummy-depth-out --scene dummy --depth-out $out/x-dummy-depth.png
x learn-depth-out --scene learnopengl --depth-out $out/x-learn-depth.png --shadow-out $out/x-learn-vis.png
echo done
