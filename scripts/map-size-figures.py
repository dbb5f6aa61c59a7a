#!/usr/bin/env python3
"""The fitted box's error on learnopengl by the map's size, as docs/results.md quotes it: one
`compare` each, from the code's camera (the figures' own view; the scene opens from above),
its misclassified share read from metrics.json.

map-size-figures.py BIN [OUT.md]: prints the Markdown table (or writes it to OUT.md, the
interface of scripts/results.sh's script jobs). About half a minute on two cores of
llvmpipe. tests/measure/results_figures.rs holds docs/results.md to the table and re-runs two of
its rows."""
import json, subprocess, sys, tempfile

B = sys.argv[1]
# The command docs/results.md cites, less `--map-size N`.
ARGS = ["--scene", "learnopengl", "--view", "code", "--fit", "scene", "--filter", "hw2x2"]
SIZES = [1024, 1152, 1280, 1448, 1600, 2048, 4096]


def measure(size):
    with tempfile.TemporaryDirectory() as d:
        cmd = [B, "compare", *ARGS, "--map-size", str(size), "--out-dir", f"{d}/c"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed: {r.stderr.strip()}")
        with open(f"{d}/c/metrics.json") as f:
            return json.load(f)["metrics"]


def percent(share):
    return f"{share * 100:.3f}%"


lines = [
    f"`shadowmap compare {' '.join(ARGS)} --map-size N` "
    "(written by `scripts/map-size-figures.py`)",
    "",
    "| map size | misclassified | false shadow | false light | outside a 1-px edge band |",
    "|---|---|---|---|---|",
]
for size in SIZES:
    m = measure(size)
    lines.append(
        f"| {size} | {percent(m['misclassified_rate'])} | {percent(m['false_shadow_rate'])} "
        f"| {percent(m['false_light_rate'])} | {percent(m['misclassified_outside_band_rate'])} |"
    )
text = "\n".join(lines) + "\n"
if len(sys.argv) > 2:
    with open(sys.argv[2], "w") as f:
        f.write(text)
else:
    sys.stdout.write(text)
