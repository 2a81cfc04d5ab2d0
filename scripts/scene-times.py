#!/usr/bin/env python3
"""Render times of every scene at 640x480, GPU path and CPU reference: the table of docs/scenes.md
("Render times at 640x480 on lavapipe").

usage: scripts/scene-times.py VKRAY ROUNDS SCENE...
example: scripts/scene-times.py build/vkray 5 scenes/*.scene

After one untimed GPU render a scene (Mesa's disk cache then holds the kernel's machine code, as
it does for a user's second render), each round renders every scene on the GPU path and with
--cpu, alternated; prints a Markdown row a scene with the medians of the JSON report's timings
(the whole command's total_ms, not the process's wall clock, so the process start and exit are
left out on both paths)."""
import json, statistics, subprocess, sys

if len(sys.argv) < 4:
    sys.exit(__doc__)
vkray, rounds, scenes = sys.argv[1], int(sys.argv[2]), sys.argv[3:]


def render(scene, cpu):
    cmd = [vkray, "render", scene, "--size", "640x480", "--json", "-o", "/tmp/scene-times.png"]
    out = subprocess.run(cmd + (["--cpu"] if cpu else []), check=True, capture_output=True, text=True).stdout
    return json.loads(out)


runs = {s: {"gpu": [], "cpu": []} for s in scenes}
for s in scenes:  # warm-up: a kernel's first render with new features compiles its machine code
    render(s, False)
for r in range(rounds):
    for s in scenes:
        runs[s]["gpu"].append(render(s, False))
        runs[s]["cpu"].append(render(s, True))


def med(reports, f):
    return statistics.median(f(d) for d in reports)


print("| scene | triangles | load ms | BVH build ms | device start ms | render ms | of which kernels ms | write ms "
      "| total ms | `--cpu` total ms | GPU / CPU | camera + secondary rays | shadow rays |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
for s in scenes:
    g, c = runs[s]["gpu"], runs[s]["cpu"]
    total, cpu = med(g, lambda d: d["total_ms"]), med(c, lambda d: d["total_ms"])
    name = s.split("scenes/", 1)[-1]
    print(f"| `{name}` | {g[0]['triangles']} | {med(g, lambda d: d['load_ms']):.0f} "
          f"| {med(g, lambda d: d['accel']['build_ms']):.0f} | {med(g, lambda d: d['device_ms']):.0f} "
          f"| {med(g, lambda d: d['render_ms']):.0f} | {med(g, lambda d: d['gpu']['gpu_ms']):.0f} "
          f"| {med(g, lambda d: d['write_ms']):.0f} | {total:.0f} | {cpu:.0f} | {total / cpu:.2f} "
          f"| {g[0]['gpu']['rays']} | {g[0]['gpu']['shadow_rays']} |", flush=True)
