#!/usr/bin/env python3
"""Work per ray of box against sphere containers: nodes, leaves and triangle tests per ray.

usage: counters.py VKRAY SIZE SCENE...   (SIZE as WIDTHxHEIGHT)
Renders each scene (its own camera, lights and maxdepth: the whole Whitted render) with bvh-hq and
bvh-sphere and --counters, and prints per ray (camera, secondary and shadow rays together) the
4-wide node steps, leaves, triangle tests, and the container tests (4 per inner node step: the
kernel tests all four children of a node at once) plus triangle tests, the thesis's "average
ray-bin and ray-obj intersect function called per ray" (Mahmuda 2017, Table 5.3).
"""
import json, subprocess, sys

vkray, size, scenes = sys.argv[1], sys.argv[2], sys.argv[3:]
print("| scene | accel | rays | node steps / ray | leaves / ray | triangle tests / ray | container + triangle tests / ray |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
for scene in scenes:
    for accel in ("bvh-hq", "bvh-sphere"):
        out = subprocess.run([vkray, "render", scene, "--accel", accel, "--size", size, "--counters", "--json",
                              "-o", "/tmp/bvh-sphere-counters.png"], capture_output=True, text=True, check=True).stdout
        g = json.loads(out)["gpu"]
        rays = g["rays"] + g["shadow_rays"]
        t = g["traversal"]
        inner = t["nodes"] - t["leaves"]
        print(f"| {scene} | {accel} | {rays} | {t['nodes'] / rays:.2f} | {t['leaves'] / rays:.2f} | "
              f"{t['triangles'] / rays:.2f} | {(4 * inner + t['triangles']) / rays:.2f} |", flush=True)
