#!/usr/bin/env python3
"""Medians of kernel-ab.sh's or minmax-ab.sh's rounds: camera-ray time (primary_only_ms, GPU
timestamps; median of each run's repeats) per scene and accelerator, each variant's time over the
old kernels' in the same round, and the median of those ratios.
    python3 summarise-ab.py OUTDIR [--dump FILE]
OUTDIR holds VARIANT-ROUND[-...]/bench.json; --dump writes the times it read as one JSON file (how
the runs are kept in this folder: times.json of each script)."""
import collections, glob, json, os, statistics, sys

def load(outdir):
    runs = []
    for f in sorted(glob.glob(os.path.join(outdir, "*-*", "bench.json"))):
        variant, rnd = os.path.basename(os.path.dirname(f)).split("-")[:2]
        for scene in json.load(open(f))["scenes"]:
            for a in scene["accelerators"]:
                runs.append({"variant": variant, "round": int(rnd), "scene": scene["name"], "accel": a["accel"],
                             "size": f'{scene["width"]}x{scene["height"]}', "primary_only_ms": a["primary_only_ms"]})
    return runs

def main():
    source = sys.argv[1]
    runs = json.load(open(source)) if source.endswith(".json") else load(source)
    if "--dump" in sys.argv:
        json.dump(runs, open(sys.argv[sys.argv.index("--dump") + 1], "w"), indent=1)
    t = collections.defaultdict(dict)
    for r in runs:
        t[(r["scene"], r["size"], r["accel"])][(r["variant"], r["round"])] = r["primary_only_ms"]["median"]
    variants = sorted({v for d in t.values() for v, _ in d if v != "old"})
    print("| scene | accel | old ms | " + " | ".join(f"{v} ms | {v} / old per round | median" for v in variants) + " |")
    print("| :--- | :--- | ---: |" + " ---: | :--- | ---: |" * len(variants))
    for (scene, size, accel), d in t.items():
        rounds = sorted({r for _, r in d})
        cells = [f"{statistics.median(d[('old', r)] for r in rounds if ('old', r) in d):.3f}"]
        for v in variants:
            ratios = [d[(v, r)] / d[("old", r)] for r in rounds if (v, r) in d and ("old", r) in d]
            cells += [f"{statistics.median(d[(v, r)] for r in rounds if (v, r) in d):.3f}",
                      " ".join(f"{x:.3f}" for x in ratios), f"{statistics.median(ratios):.3f}"]
        print(f"| {scene} {size} | {accel} | " + " | ".join(cells) + " |")

main()
