#!/usr/bin/env python3
"""Per filter on dummy, playground, large and penumbra: frame time (render --frames, median) and the
figures against the area-light truth (compare --supersample 1). Prints Markdown rows."""
import json, subprocess, sys, tempfile, re, os
B = sys.argv[1]
scenes = {
    "dummy": ["--scene", "dummy", "--light-size", "5", "--bias", "0.005"],
    "playground": ["--scene", "playground", "--step", "pcss", "--light-size", "1"],
    "large": ["--scene", "large", "--light-size", "2", "--map-size", "2048"],
    "penumbra": ["--scene", "penumbra"],
}
filters = ["single", "pcf3x3", "pcf5x5", "pcf4x4-weighted", "soft-pcf", "pcss", "vsm", "evsm2", "evsm4", "msm", "vssm", "msm-soft"]
only = sys.argv[2].split(",") if len(sys.argv) > 2 else list(scenes)
filters = sys.argv[3].split(",") if len(sys.argv) > 3 else filters
for name in only:
    args = scenes[name]
    print(f"\n{name}: {' '.join(args)}", flush=True)
    print("| filter | frame ms | MAE vs area | bleed | penumbra error px (width) |")
    print("|---|---|---|---|---|", flush=True)
    for f in filters:
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
            print(f"| {f} | {m.group(1) if m else '?'} | {a.get('mae', float('nan')):.4f} | {100*a.get('light_bleed_rate', float('nan')):.3f}% | {a.get('penumbra_width_error_px', float('nan')):.2f} ({a.get('penumbra_width_px', float('nan')):.2f}, truth {a.get('penumbra_width_truth_px', float('nan')):.2f}) |", flush=True)
