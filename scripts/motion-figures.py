#!/usr/bin/env python3
"""The flicker tables of docs/techniques/motion.md and docs/results.md: each row one
`compare --motion PATH --frames 8 --supersample 1` at the scene's own size (or the frames
its group names), its figures read from metrics.json.

motion-figures.py BIN [OUT.md]: prints the Markdown (or writes it to OUT.md, as
scripts/results.sh's `motion` job does). About ten minutes on two cores of llvmpipe."""
import json, subprocess, sys, tempfile

B = sys.argv[1]
FRAMES = 8

# (heading, the rows' shared arguments, each row's own flags, against the area truth); a
# group's arguments may name its own --frames.
groups = [
    ("dummy, light-sweep 0.5° a frame",
     ["--scene", "dummy", "--motion", "light-sweep"],
     [["--filter", f] for f in ["single", "hw2x2", "pcf3x3", "pcf5x5", "hw3x3", "pcf4x4-weighted", "soft-pcf"]]
     + [["--bias", "0.005", "--filter", f] for f in ["single", "pcf3x3"]],
     False),
    ("large, strafe 0.05 a frame",
     ["--scene", "large", "--cascades", "4", "--motion", "strafe"],
     [["--snap", "on"], ["--snap", "off"]],
     False),
    ("large, dolly 0.05 a frame",
     ["--scene", "large", "--fit", "scene", "--motion", "dolly"],
     [["--snap", "on"], ["--snap", "off"]],
     False),
    ("learnopengl, orbit 0.5° a frame",
     ["--scene", "learnopengl", "--fit", "scene", "--motion", "orbit"],
     [["--snap", "on"], ["--snap", "off"]],
     False),
    ("learnopengl from the code's camera, orbit 3° a frame over 12 frames",
     ["--scene", "learnopengl", "--view", "code", "--fit", "scene", "--motion", "orbit", "--motion-step", "3", "--frames", "12"],
     [["--snap", "on"], ["--snap", "off"]],
     False),
    ("penumbra, light-sweep 0.5° a frame (the spot rises about its target), against the area light",
     ["--scene", "penumbra", "--motion", "light-sweep"],
     [["--filter", f] for f in ["single", "pcf3x3", "soft-pcf", "pcss", "vsm", "vssm", "msm-soft"]],
     True),
]


def measure(args):
    with tempfile.TemporaryDirectory() as d:
        frames = [] if "--frames" in args else ["--frames", str(FRAMES)]
        cmd = [B, "compare", *args, *frames, "--supersample", "1", "--out-dir", f"{d}/c"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed: {r.stderr.strip()}")
        return json.load(open(f"{d}/c/metrics.json"))["motion"]


def pct(x):
    return f"{100 * x:.3f}%"


lines = []
for title, base, rows, area in groups:
    frames = "" if "--frames" in base else f" --frames {FRAMES}"
    lines += [f"\n{title}: `shadowmap compare {' '.join(base)} FLAGS{frames} --supersample 1`\n"]
    still = "MAE vs area (frame 0)" if area else "misclassified (frame 0)"
    lines += [f"| FLAGS | flicker energy | beyond the truth's steps | the truth's own | false flicker | truth's change | {still} |",
              "|---|---|---|---|---|---|---|"]
    for flags in rows:
        m = measure(base + flags)
        f0 = m["frames"][0]
        error = f"{f0['mae']:.4f}" if area else pct(f0["misclassified"])
        lines.append(f"| `{' '.join(flags)}` | {m['energy']:.4f} | {m['excess_energy']:.4f} | {m['truth_energy']:.4f} "
                     f"| {pct(m['false_flicker'])} | {pct(m['truth_change'])} | {error} |")
        print(lines[-1], file=sys.stderr, flush=True)
text = "\n".join(lines).lstrip("\n") + "\n"
if len(sys.argv) > 2:
    with open(sys.argv[2], "w") as out:
        out.write(f"Written by `scripts/motion-figures.py BIN` (`scripts/results.sh BIN motion`).\n\n{text}")
else:
    print(text, end="")
