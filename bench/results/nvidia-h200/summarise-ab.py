#!/usr/bin/env python3
"""Medians of device-ab.txt: camera-ray Mrays/s per binary, scene and accelerator, and Embree's.
   python3 bench/results/nvidia-h200/summarise-ab.py bench/results/nvidia-h200/device-ab.txt"""
import re, statistics, sys
from collections import defaultdict

runs = defaultdict(list)  # (binary, scene, accel) -> [Mrays/s]
binary, scene_of_embree = None, 0
for line in open(sys.argv[1]):
    m = re.match(r"=== round \d+: (\S+)", line)
    if m:
        binary, scene_of_embree = m.group(1), 0
        continue
    if binary is None or line.startswith("==="):
        binary = None if line.startswith("===") else binary
        continue
    m = re.match(r"\s+Embree\s+camera rays\s+([\d.]+) Mrays/s", line)
    if m:
        scene_of_embree += 1
        runs[(binary, scene_of_embree, "Embree rtcIntersect1")].append(float(m.group(1)))
        continue
    m = re.match(r"\s+(\S+)\s+build.*camera rays\s+([\d.]+) Mrays/s", line)
    if m:
        runs[(binary, scene_of_embree, m.group(1))].append(float(m.group(2)))

scenes = {1: "bunny close-up 1024x768", 2: "1M sphere grid close-up 1920x1080"}
binaries = list(dict.fromkeys(k[0] for k in runs))
accels = list(dict.fromkeys(k[2] for k in runs))
for s, name in scenes.items():
    print(f"{name}: camera-ray Mrays/s, median (min-max) of {len(runs[(binaries[0], s, accels[0])])} rounds")
    print("| | " + " | ".join(binaries) + " |")
    print("| --- |" + " ---: |" * len(binaries))
    for a in accels:
        cells = []
        for b in binaries:
            v = runs[(b, s, a)]
            cells.append(f"{statistics.median(v):.0f} ({min(v):.0f}-{max(v):.0f})" if v else "")
        print(f"| {a} | " + " | ".join(cells) + " |")
    print()
