#!/usr/bin/env python3
"""Interleaved A/B runs of `vkray render`: two or more vkray binaries, or one binary with several
kernel folders, alternated render by render (ABAB...), with medians and ratios to the first.

usage: scripts/ab.py [--rounds N] [--warmup N] [--metric M] [--rotate] [--dump FILE]
                     SPEC SPEC [SPEC...] -- SCENE [vkray render options...]

SPEC      a vkray binary, or BINARY:KERNEL_DIR: that binary reading its kernels from KERNEL_DIR
          (VKRAY_KERNEL_DIR, one render_<kernel>[_resumable][_split].spv each; docs/architecture.md).
          Any executable that runs vkray will do: a wrapper that sets VK_ICD_FILENAMES compares two
          Vulkan drivers (docs/drivers.md). The first SPEC is the baseline.
--rounds  timed rounds (default 7); each runs every SPEC once, in order.
--warmup  untimed rounds first (default 1): Mesa's disk cache then holds every kernel's machine code.
--metric  what is compared: a field of `vkray render --json`'s report, dotted (default gpu.gpu_ms,
          the kernels' time by timestamp queries; device_ms, gpu.pipeline_ms, render_ms, total_ms,
          ...), or "wall": the whole process's wall clock. Several, comma-separated, are taken from
          the same renders and printed one table each.
--rotate  rotate the order every round (ABC, BCA, CAB, ...), so no SPEC always runs after another.
--dump    write every measurement as JSON.

Prints, per SPEC, the median and the minimum over the rounds, and against the baseline: the ratio
of the medians, of the minima, and the median (range) of the ratios within each round. A ratio
below 1 is faster. On a shared machine trust the minimum and the within-round ratios most; with
lavapipe, LP_NUM_THREADS=1 in the environment leaves the second core to the neighbours.
The options after `--` go to `vkray render` as they are, but -o and --json, which this script adds.

example: LP_NUM_THREADS=1 scripts/ab.py /tmp/old/vkray build/vkray -- scenes/cornell.scene --size 320x240
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


def parse():
    if "--" not in sys.argv:
        sys.exit(__doc__)
    cut = sys.argv.index("--")
    p = argparse.ArgumentParser(usage="scripts/ab.py [options] SPEC SPEC [SPEC...] -- SCENE [vkray render options...]",
                                description="Interleaved A/B runs of vkray render (see the head of this file).")
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--warmup", type=int, default=1)
    p.add_argument("--metric", default="gpu.gpu_ms")
    p.add_argument("--rotate", action="store_true")
    p.add_argument("--dump")
    p.add_argument("specs", nargs="+")
    args = p.parse_args(sys.argv[1:cut])
    args.render = sys.argv[cut + 1:]
    if len(args.specs) < 2 or not args.render or args.rounds < 1:
        p.error("two SPECs or more, a scene after --, and at least one round")
    for spec in args.specs:
        binary, _, kernels = spec.partition(":")
        if not os.access(binary, os.X_OK):
            p.error(f"{binary}: not an executable")
        if kernels and not os.path.isdir(kernels):
            p.error(f"{kernels}: not a folder")
    return args


def run(spec, render_args, metrics, image):
    binary, _, kernels = spec.partition(":")
    env = dict(os.environ)
    env.pop("VKRAY_KERNEL_DIR", None)
    if kernels:
        env["VKRAY_KERNEL_DIR"] = os.path.abspath(kernels)
    cmd = [binary, "render", *render_args, "--json", "-o", image]
    t0 = time.perf_counter()
    done = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall_ms = (time.perf_counter() - t0) * 1e3
    if done.returncode != 0:
        last = (done.stderr.strip().splitlines() or ["(no message)"])[-1]
        sys.exit(f"ab: {spec}: exit {done.returncode}: {last}")
    report = json.loads(done.stdout)
    out = []
    for metric in metrics:
        if metric == "wall":
            out.append(wall_ms)
            continue
        value = report
        for key in metric.split("."):
            if not isinstance(value, dict) or key not in value:
                sys.exit(f"ab: the report has no {metric} (at '{key}')")
            value = value[key]
        out.append(float(value))
    return out


def main():
    args = parse()
    order = list(range(len(args.specs)))
    metrics = args.metric.split(",")
    times = {m: [[] for _ in args.specs] for m in metrics}  # by position: the same SPEC twice is an A/A check
    with tempfile.TemporaryDirectory() as tmp:
        image = os.path.join(tmp, "ab.png")
        for r in range(-args.warmup, args.rounds):
            shift = r % len(order) if args.rotate and r >= 0 else 0
            for i in order[shift:] + order[:shift]:
                values = run(args.specs[i], args.render, metrics, image)
                if r >= 0:
                    for m, v in zip(metrics, values):
                        times[m][i].append(v)
            print(f"round {r + 1}/{args.rounds}" if r >= 0 else "warm-up", file=sys.stderr, flush=True)
    if args.dump:
        json.dump({"metrics": metrics, "render": args.render, "specs": args.specs, "times": times},
                  open(args.dump, "w"), indent=1)
    for m in metrics:
        report(m, times[m], args)


def report(metric, times, args):
    base = times[0]
    width = max(len(s) for s in args.specs)
    print(f"{metric}, {args.rounds} rounds: {' '.join(args.render)}")
    for i, spec in enumerate(args.specs):
        t = times[i]
        line = f"{spec:<{width}}  median {statistics.median(t):9.2f}  min {min(t):9.2f}"
        if i > 0:
            within = [a / b for a, b in zip(t, base)]
            line += (f"  / baseline: median {statistics.median(t) / statistics.median(base):.3f}"
                     f"  min {min(t) / min(base):.3f}"
                     f"  per round {statistics.median(within):.3f} ({min(within):.3f}-{max(within):.3f})")
        print(line)


main()
