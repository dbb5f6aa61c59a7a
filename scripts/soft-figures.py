#!/usr/bin/env python3
"""Per filter on dummy, playground, large and penumbra: frame time (render --frames, median) and the
figures against the area-light truth (compare --supersample 1). Prints Markdown rows.

soft-figures.py BIN [SCENES [FILTERS [SCALES [FLAGS]]]]: comma-separated lists; SCALES multiply
each scene's light size (default 1), each scale's filters measured one after the other; FLAGS
(one string, e.g. "--soft-search-cells 2 --soft-filter-cells 2") are added to every render and
compare.
On the playground each filter that has a step of its own is measured at it (its settings: vssm
and msm-soft test the receiver's plane and take no epsilon), every other at the `pcss` step."""
import json, subprocess, sys, tempfile, re, os
B = sys.argv[1]
# Each scene's arguments and its light's size (the scene's own).
scenes = {
    "dummy": (["--scene", "dummy", "--bias", "0.005"], 5.0),
    "playground": (["--scene", "playground", "--step", "pcss"], 1.0),
    "large": (["--scene", "large", "--map-size", "2048"], 2.0),
    "penumbra": (["--scene", "penumbra"], 1.5),
}
filters = ["single", "pcf3x3", "pcf5x5", "pcf4x4-weighted", "soft-pcf", "pcss", "vsm", "evsm2", "evsm4", "msm", "vssm", "msm-soft"]
# Filters measured at their own step of a scene's list, by scene.
own_step = {"playground": {"vssm": "vssm", "msm-soft": "msm-soft"}}
only = sys.argv[2].split(",") if len(sys.argv) > 2 else list(scenes)
filters = sys.argv[3].split(",") if len(sys.argv) > 3 else filters
scales = [float(s) for s in sys.argv[4].split(",")] if len(sys.argv) > 4 else [1.0]
flags = sys.argv[5].split() if len(sys.argv) > 5 else []
for name in only:
    base, size = scenes[name]
    for scale in scales:
        light = ["--light-size", f"{size * scale:g}"]
        print(f"\n{name}: {' '.join(base + light)}", flush=True)
        print("| filter | frame ms | MAE vs area | bleed | penumbra error px (width) |")
        print("|---|---|---|---|---|", flush=True)
        for f in filters:
            args = base + light + flags
            if f in own_step.get(name, {}):
                args[args.index("--step") + 1] = own_step[name][f]
            with tempfile.TemporaryDirectory() as d:
                r = subprocess.run([B, "render", *args, "--filter", f, "--frames", "40", "--out", f"{d}/f.png"], capture_output=True, text=True)
                m = re.search(r"median ([0-9.]+) ms", r.stdout + r.stderr)
                if r.returncode != 0:
                    print(f"| {f} | refused: {(r.stderr.strip().splitlines() or ['?'])[-1][:120]} |||", flush=True)
                    continue
                c = subprocess.run([B, "compare", *args, "--filter", f, "--supersample", "1", "--out-dir", f"{d}/c"], capture_output=True, text=True)
                if c.returncode != 0:
                    print(f"| {f} | compare failed: {c.stderr.strip()[-120:]} |||", flush=True)
                    continue
                j = json.load(open(f"{d}/c/metrics.json"))
                a = j.get("area_light") or {}
                print(f"| {f} | {m.group(1) if m else '?'} | {a.get('mae', float('nan')):.5f} | {100*a.get('light_bleed_rate', float('nan')):.3f}% | {a.get('penumbra_width_error_px', float('nan')):.2f} ({a.get('penumbra_width_px', float('nan')):.2f}, truth {a.get('penumbra_width_truth_px', float('nan')):.2f}) |", flush=True)
