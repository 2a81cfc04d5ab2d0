#!/usr/bin/env python3
"""Camera-ray table of primary-embree-old-new.sh's runs: per mesh and run, Embree's rtcIntersect1 and
rtcIntersect16 Mrays/s, each accelerator's camera-ray Mrays/s with its ratio to the rtcIntersect1
times measured in its own repeats, and each kd traversal's rate over bvh's.
usage: summarise.py OUTDIR (holding old-1, new-1, ... from primary-embree-old-new.sh)"""
import json, pathlib, sys

out = pathlib.Path(sys.argv[1])
runs = sorted(p for p in out.iterdir() if (p / "bench.json").exists())
rows = {}
for run in runs:
    for s in json.load(open(run / "bench.json"))["scenes"]:
        acc = {a["accel"]: a for a in s["accelerators"]}
        rate = {k: next(r["mrays_per_s"] for r in a["ray_kinds"] if r["kind"] == "primary") for k, a in acc.items()}
        ratio = {k: a["embree_interleaved"]["primary_vs_intersect1"] for k, a in acc.items()}
        e = s["embree"]
        cells = [f"{e['intersect1_mrays_per_s']:.1f} / {e['intersect16_mrays_per_s']:.1f}"]
        cells += [f"{rate[k]:.2f} ({ratio[k]:.3f}x)" for k in acc]
        kd = [k for k in acc if k.startswith("kd-")]
        cells.append(" / ".join(f"{rate[k] / rate['bvh']:.2f}" for k in kd))
        rows.setdefault(s["name"], []).append((run.name, list(acc), kd, cells))
for name, entries in rows.items():
    accs, kd = entries[0][1], entries[0][2]
    print(f"\n{name}\n| run | Embree 1 / 16 | " + " | ".join(accs) + " | " + " / ".join(kd) + " over bvh |")
    print("| --- " * (len(accs) + 3) + "|")
    for run, _, _, cells in entries:
        print(f"| {run} | " + " | ".join(cells) + " |")
