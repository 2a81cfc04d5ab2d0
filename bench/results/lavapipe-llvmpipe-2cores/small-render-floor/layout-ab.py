#!/usr/bin/env python3
"""The whole render command (total_ms of its JSON report), two binaries alternated every round.
usage: layout-ab.py OLD NEW ROUNDS SCENE [render args...]"""
import json, statistics, subprocess, sys

old, new, rounds, scene, extra = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5:]
times = {old: [], new: []}
for r in range(rounds):
    for b in (old, new):
        out = subprocess.run([b, "render", scene, "--json", "-o", "/tmp/layout-ab.png", *extra], check=True,
                             capture_output=True, text=True).stdout
        times[b].append(json.loads(out)["total_ms"])
ratios = [n / o for o, n in zip(times[old], times[new])]
print(f"{scene} {' '.join(extra)}: old {statistics.median(times[old]):.0f} ms, new {statistics.median(times[new]):.0f} ms, "
      f"new / old {statistics.median(ratios):.3f} ({min(ratios):.3f}-{max(ratios):.3f}), {rounds} rounds")
