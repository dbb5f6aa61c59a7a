#!/usr/bin/env bash
# playground-originals.sh CHECKOUT [OUTDIR] [BIN]: renders each of the shadow-playground's demo
# pages (basic, PCF, soft PCF, variance, moment) from the playground's own code in headless
# Chromium at 400 x 300, renders the same step here (`render --scene playground --size 400x300
# --step S --shadow-out ...`), and scores each pair with `examples/playground_score.rs`.
#
# CHECKOUT is a checkout of github.com/misaka-10032/shadow-playground (its js/ folder is read;
# nothing is copied out of it). The pages load require.js and glm-js from the network; this
# script needs neither: a small page of its own defines `define` (modules by file name) and the
# few glm calls the demos make (vec2, vec3, mat4, translate, rotate, lookAt, perspective, '*'),
# loads the checkout's js/ files, calls the demo's onStart on a 400 x 300 canvas and reads the
# canvas back with toDataURL (Chromium's --dump-dom prints it). WebGL 2 runs on SwiftShader.
#
# What is scored (see examples/playground_score.rs): a demo draws red = 0.5 + 0.5 visibility on
# its geometry (green 0) over a (0.8, 0.9, 0.8) clear; here --shadow-out gives visibility as
# grey. Pixels that are geometry in both are compared (the demo's canvas is antialiased: its
# pixels blended with the clear colour, green above 0, are left out).
#   shadow mask: visibility < 0.49 (below one half by more than 8-bit rounding: a PCF edge pixel
#   at exactly one half must not count as shadow in one picture and lit in the other).
#   IoU = |both| / |either| of the two masks.
#   penumbra band: pixels where either picture's visibility is in (0.02, 0.98), or that have a
#   neighbour (8-connected) on the other side of its own picture's mask; band = mean |difference
#   of visibility| over it.
set -eu
checkout=${1:?usage: playground-originals.sh CHECKOUT [OUTDIR] [BIN]}
out=${2:-/tmp/playground-originals}
bin=${3:-target/release/shadowmap}
checkout=$(cd "$checkout" && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
[ -n "${3:-}" ] && bin=$(realpath "$bin")
cd "$(dirname "$0")/.."
chromium=${CHROMIUM:-chromium}

cargo build --release --quiet --example playground_score
score=target/release/examples/playground_score

# The page's own loader and glm: column-major 4 x 4 matrices as glm's, `.elements` a
# Float32Array, `m['*'](n)` the product m n.
cat >"$out/harness.js" <<'EOF'
(function () {
  const pending = [];
  const modules = {};
  window.define = function (deps, factory) {
    const src = document.currentScript.src;
    pending.push({ name: src.substring(src.lastIndexOf('/') + 1).replace(/\.js$/, ''), deps, factory });
  };
  function mat(e) {
    const m = { elements: Float32Array.from(e) };
    m['*'] = function (n) {
      const r = new Array(16).fill(0);
      for (let c = 0; c < 4; c++)
        for (let row = 0; row < 4; row++)
          for (let k = 0; k < 4; k++) r[c * 4 + row] += e[k * 4 + row] * n.raw[c * 4 + k];
      return mat(r);
    };
    m.raw = e;
    return m;
  }
  const identity = () => [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const vec = (...v) => ({ v, elements: Float32Array.from(v) });
  const sub = (a, b) => a.map((x, i) => x - b[i]);
  const dot = (a, b) => a.reduce((s, x, i) => s + x * b[i], 0);
  const norm = (a) => a.map((x) => x / Math.sqrt(dot(a, a)));
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  modules.glm = {
    vec2: (x, y) => vec(x, y),
    vec3: (x, y, z) => vec(x, y, z),
    mat4: () => mat(identity()),
    radians: (d) => (d * Math.PI) / 180,
    translate: (m, t) => {
      const e = identity();
      [e[12], e[13], e[14]] = t.v;
      return m['*'](mat(e));
    },
    rotate: (m, a, axis) => {
      const [x, y, z] = norm(axis.v), c = Math.cos(a), s = Math.sin(a), t = 1 - c;
      return m['*'](mat([
        t * x * x + c, t * x * y + s * z, t * x * z - s * y, 0,
        t * x * y - s * z, t * y * y + c, t * y * z + s * x, 0,
        t * x * z + s * y, t * y * z - s * x, t * z * z + c, 0,
        0, 0, 0, 1]));
    },
    lookAt: (eye, centre, up) => {
      const f = norm(sub(centre.v, eye.v)), s = norm(cross(f, up.v)), u = cross(s, f);
      return mat([s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
        -dot(s, eye.v), -dot(u, eye.v), dot(f, eye.v), 1]);
    },
    perspective: (fovy, aspect, near, far) => {
      const t = Math.tan(fovy / 2);
      return mat([1 / (aspect * t), 0, 0, 0, 0, 1 / t, 0, 0,
        0, 0, -(far + near) / (far - near), -1, 0, 0, (-2 * far * near) / (far - near), 0]);
    },
  };
  window.runDemo = function (name) {
    function get(n) {
      if (!(n in modules)) {
        const p = pending.find((m) => m.name === n);
        if (!p) throw new Error('module ' + n + ' was not loaded');
        modules[n] = p.factory(...p.deps.map(get));
      }
      return modules[n];
    }
    const out = document.getElementById('out');
    try {
      get(name).onStart({ canvasId: 'canvas' });
      out.textContent = document.getElementById('canvas').toDataURL('image/png');
    } catch (e) {
      out.textContent = 'error: ' + e;
    }
  };
})();
EOF

# demo file (js/NAME.js) and the step it is set beside
demos="basic-shadow-demo:basic pcf-shadow-demo:pcf soft-pcf-shadow-demo:soft-pcf variance-shadow-demo:variance moment-shadow-demo:moment"
printf '%-9s %8s %8s %8s\n' step IoU band pixels
for pair in $demos; do
  demo=${pair%%:*}; step=${pair##*:}
  page="$out/$demo.html"
  {
    echo '<html><body style="margin:0"><canvas id="canvas" width="400" height="300"></canvas>'
    echo '<pre id="out"></pre>'
    echo "<script src=\"file://$out/harness.js\"></script>"
    for m in glh cube-scene paper-scene "$demo"; do
      [ -f "$checkout/js/$m.js" ] && echo "<script src=\"file://$checkout/js/$m.js\"></script>"
    done
    echo "<script>runDemo('$demo');</script></body></html>"
  } >"$page"
  "$chromium" --headless=new --no-sandbox --use-gl=angle --use-angle=swiftshader \
    --enable-unsafe-swiftshader --allow-file-access-from-files --dump-dom "file://$page" \
    2>/dev/null | sed -n 's/.*<pre id="out">\(.*\)<\/pre>.*/\1/p' >"$out/$demo.txt"
  if ! grep -q '^data:image/png;base64,' "$out/$demo.txt"; then
    echo "$step: the page drew nothing: $(head -c 300 "$out/$demo.txt")" >&2
    continue
  fi
  sed 's/^data:image\/png;base64,//' "$out/$demo.txt" | base64 -d >"$out/original-$step.png"
  "$bin" render --scene playground --size 400x300 --step "$step" --out "$out/port-$step.png" \
    --shadow-out "$out/port-$step-vis.png" >/dev/null
  printf '%-9s ' "$step"
  "$score" "$out/original-$step.png" "$out/port-$step-vis.png"
done
