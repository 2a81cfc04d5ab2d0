#!/usr/bin/env python3
"""Pipeline creation of two vkray binaries, interleaved (A B A B ...).

usage: pipeline-ab.py OLD_VKRAY NEW_VKRAY ROUNDS ACCELS SCENE...   (ACCELS comma-separated)
Per scene and accelerator: the report's gpu.pipeline_ms (vkCreateComputePipelines of the render
kernel; on lavapipe the SPIR-V's translation and optimisation, LLVM's code coming from Mesa's shader
cache after the first run) and gpu.gpu_ms; medians, and new/old of the medians and of the minima.
"""
import json, statistics as st, subprocess, sys

old, new, rounds, accels = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4].split(",")
scenes = sys.argv[5:]
print("| scene | accel | old pipeline ms | new pipeline ms | new/old median | new/old min | old kernel ms | new kernel ms |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for scene in scenes:
    for accel in accels:
        pipe, gpu = {"old": [], "new": []}, {"old": [], "new": []}
        for _ in range(rounds):
            for name, binary in (("old", old), ("new", new)):
                out = subprocess.run([binary, "render", scene, "--accel", accel, "-o", "/tmp/pipeline-ab.png", "--json"],
                                     capture_output=True, text=True, check=True).stdout
                g = json.loads(out)["gpu"]
                pipe[name].append(g["pipeline_ms"])
                gpu[name].append(g["gpu_ms"])
        mo, mn = st.median(pipe["old"]), st.median(pipe["new"])
        print(f"| {scene} | {accel} | {mo:.1f} | {mn:.1f} | {mn / mo:.3f} | {min(pipe['new']) / min(pipe['old']):.3f} | "
              f"{st.median(gpu['old']):.1f} | {st.median(gpu['new']):.1f} |", flush=True)
