#!/usr/bin/env python3
"""Box against sphere containers, as Mahmuda 2017's Tables 5.3 and 5.4 measure them.

usage: box-sphere.py VKRAY ROUNDS SIZE THREADS SCENE...   (SIZE as WIDTHxHEIGHT)
Per scene, interleaved in every round: bvh-hq and bvh-sphere (the same AAC-HQ, boxes or spheres),
each rendered on the GPU (the report's accel.build_ms and gpu.gpu_ms, the kernels' time of the
whole Whitted render) and with --cpu (the double-precision reference's render_ms, its trace; the
build is timed apart). Medians, and the box : sphere ratios of Table 5.4 (below 1: boxes faster).
"""
import json, statistics as st, subprocess, sys

vkray, rounds, size, threads, scenes = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5:]


def run(scene, accel, cpu):
    cmd = [vkray, "render", scene, "--accel", accel, "--size", size, "--threads", threads, "--json", "-o",
           "/tmp/box-sphere.png"] + (["--cpu"] if cpu else [])
    d = json.loads(subprocess.run(cmd, capture_output=True, text=True, check=True).stdout)
    return d["accel"]["build_ms"], d["render_ms"] if cpu else d["gpu"]["gpu_ms"]


print("| scene | triangles | box build ms | box GPU trace ms | box CPU trace ms | sphere build ms | sphere GPU trace ms | "
      "sphere CPU trace ms | build box:sphere | GPU trace box:sphere | CPU trace box:sphere |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for scene in scenes:
    f = {}
    for _ in range(rounds):
        for accel in ("bvh-hq", "bvh-sphere"):
            for cpu in (False, True):
                build, trace = run(scene, accel, cpu)
                if not cpu:  # the CPU run's build also makes its tracer
                    f.setdefault((accel, "build"), []).append(build)
                f.setdefault((accel, "cpu" if cpu else "gpu"), []).append(trace)
    m = {k: st.median(v) for k, v in f.items()}
    tris = json.loads(subprocess.run([vkray, "render", scene, "--size", "8x6", "--cpu", "--json", "-o", "/tmp/box-sphere.png"],
                                     capture_output=True, text=True, check=True).stdout)["triangles"]
    b, s = "bvh-hq", "bvh-sphere"
    print(f"| {scene} | {tris} | {m[(b, 'build')]:.1f} | {m[(b, 'gpu')]:.1f} | {m[(b, 'cpu')]:.1f} | {m[(s, 'build')]:.1f} | "
          f"{m[(s, 'gpu')]:.1f} | {m[(s, 'cpu')]:.1f} | {m[(b, 'build')] / m[(s, 'build')]:.2f} | "
          f"{m[(b, 'gpu')] / m[(s, 'gpu')]:.2f} | {m[(b, 'cpu')] / m[(s, 'cpu')]:.2f} |", flush=True)
