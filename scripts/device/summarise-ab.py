#!/usr/bin/env python3
"""Medians and ratios of a device-ab.sh run (docs/performance.md, "Interleaved A/B runs").

usage: scripts/device/summarise-ab.py OUTDIR [--dump FILE]

OUTDIR holds round-R/LABEL/SCENE/bench.json (device-ab.sh writes them) and labels.txt, the SPECs'
labels in the order given; the first is the baseline. Per scene, size and accelerator: each label's
camera-ray time (primary_only_ms: GPU timestamps, the median of a run's repeats) as the median over
the rounds, with its rate in Mrays/s, and each later label's time over the baseline's in the same
round, then the median of those ratios (below 1: faster than the baseline). Embree's rate, measured
in the same repeats on the host's cores, is printed per label as a check on the machine's load.
--dump FILE writes every time read as one JSON list, a compact record of the run.
"""
import collections
import glob
import json
import os
import statistics
import sys


def load(outdir):
    runs = []
    for f in sorted(glob.glob(os.path.join(outdir, "round-*", "*", "*", "bench.json"))):
        scene_dir = os.path.dirname(f)
        label = os.path.basename(os.path.dirname(scene_dir))
        rnd = int(os.path.basename(os.path.dirname(os.path.dirname(scene_dir)))[len("round-"):])
        for scene in json.load(open(f))["scenes"]:
            size = f'{scene["width"]}x{scene["height"]}'
            embree = (scene.get("embree") or {}).get("intersect1_mrays_per_s")
            for a in scene["accelerators"]:
                runs.append({"label": label, "round": rnd, "scene": scene["name"], "size": size,
                             "accel": a["accel"], "ms": a["primary_only_ms"]["median"],
                             "pixels": scene["width"] * scene["height"], "embree_mrays": embree})
    return runs


def main():
    if len(sys.argv) < 2 or sys.argv[1].startswith("-"):
        sys.exit(__doc__)
    outdir = sys.argv[1]
    runs = load(outdir)
    if not runs:
        sys.exit(f"summarise-ab: no round-*/*/*/bench.json under {outdir}")
    if "--dump" in sys.argv:
        json.dump(runs, open(sys.argv[sys.argv.index("--dump") + 1], "w"), indent=1)
    labels_file = os.path.join(outdir, "labels.txt")
    labels = [l.strip() for l in open(labels_file)] if os.path.exists(labels_file) else []
    labels += sorted({r["label"] for r in runs} - set(labels))
    base = labels[0]

    times = collections.defaultdict(dict)  # (scene, size, accel) -> {(label, round): ms}
    pixels, embree = {}, collections.defaultdict(list)
    for r in runs:
        key = (r["scene"], r["size"], r["accel"])
        times[key][(r["label"], r["round"])] = r["ms"]
        pixels[key] = r["pixels"]
        if r["embree_mrays"]:
            embree[(r["scene"], r["label"])].append(r["embree_mrays"])

    print(f"camera-ray time, median over rounds; ratios to {base} round by round, then their median")
    print("| scene | accel | " + " | ".join(f"{l} ms (Mrays/s)" for l in labels) + " | "
          + " | ".join(f"{l} / {base}" for l in labels[1:]) + " |")
    print("| :--- | :--- |" + " ---: |" * len(labels) + " :--- |" * (len(labels) - 1))
    for (scene, size, accel), d in times.items():
        cells = []
        for l in labels:
            v = [ms for (lab, _), ms in d.items() if lab == l]
            m = statistics.median(v) if v else None
            cells.append(f"{m:.3f} ({pixels[(scene, size, accel)] / m / 1e3:.3g})" if m else "")
        for l in labels[1:]:
            ratios = [d[(l, rnd)] / d[(base, rnd)] for (lab, rnd) in d if lab == l and (base, rnd) in d]
            cells.append(f"{statistics.median(ratios):.3f} ({' '.join(f'{x:.3f}' for x in ratios)})" if ratios else "")
        print(f"| {scene} {size} | {accel} | " + " | ".join(cells) + " |")
    print()
    for (scene, label), v in sorted(embree.items()):
        print(f"Embree rtcIntersect1, {scene}, during {label}'s runs: {statistics.median(v):.1f} Mrays/s "
              f"({min(v):.1f}-{max(v):.1f})")


main()
