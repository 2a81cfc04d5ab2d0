#!/usr/bin/env python3
"""Instructions a render kernel executes on lavapipe, counted by callgrind: the same figure on every
run, where kernel times on a shared machine drift by 15-30% (docs/performance.md, "Counting a
kernel's instructions").

usage: scripts/kernel-profile.py [--vkray BIN] [--kernels DIR] [--top N] [--asm N] -- SCENE [render options]

Runs `vkray render` under valgrind's callgrind with one lavapipe thread, Mesa's shader cache off
(so llvmpipe compiles the kernel in this process) and GALLIVM_DEBUG=asm (so it prints the machine
code it made), then matches the two: every function llvmpipe compiled at run time gets its
instruction count, and the largest, the kernel's body, its blocks: runs of instructions executed
the same number of times, the most expensive first, each with its length, executions and share.

--vkray    the vkray binary (default build/vkray)
--kernels  a folder of kernel SPIR-V for VKRAY_KERNEL_DIR (scripts/ab.py's kernel folders)
--top      blocks to list (default 12)
--asm      machine instructions printed of each listed block (default 0)

Needs valgrind (Debian's `valgrind`; scripts/install-deps.sh does not install it). Keep renders small (256x192 takes about a minute and a half): callgrind runs some 50 times slower.
Instruction counts are not time: a cache miss or a long division costs more than a move. Compare
two kernels by their counts and by scripts/ab.py's times together.

example: scripts/kernel-profile.py -- scenes/primary/bunny.scene --view close --size 256x192
"""
import argparse
import collections
import os
import re
import shutil
import subprocess
import sys
import tempfile


def parse():
    if "--" not in sys.argv:
        sys.exit(__doc__)
    cut = sys.argv.index("--")
    p = argparse.ArgumentParser(usage="scripts/kernel-profile.py [options] -- SCENE [render options]")
    p.add_argument("--vkray", default="build/vkray")
    p.add_argument("--kernels")
    p.add_argument("--top", type=int, default=12)
    p.add_argument("--asm", type=int, default=0)
    args = p.parse_args(sys.argv[1:cut])
    args.render = sys.argv[cut + 1:]
    if not args.render:
        p.error("a scene after --")
    if not os.access(args.vkray, os.X_OK):
        p.error(f"{args.vkray}: not an executable")
    if args.kernels and not os.path.isdir(args.kernels):
        p.error(f"{args.kernels}: not a folder")
    if not shutil.which("valgrind"):
        p.error("needs valgrind's callgrind: apt-get install valgrind")
    return args


def run(args, tmp):
    env = dict(os.environ, LP_NUM_THREADS="1", MESA_SHADER_CACHE_DISABLE="true", GALLIVM_DEBUG="asm")
    if args.kernels:
        env["VKRAY_KERNEL_DIR"] = args.kernels
    out = os.path.join(tmp, "callgrind.out")
    cmd = ["valgrind", "--tool=callgrind", "--smc-check=all", "--dump-instr=yes", f"--callgrind-out-file={out}",
           args.vkray, "render", *args.render, "-o", os.path.join(tmp, "image.png"), "--quiet"]
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, errors="replace")
    if r.returncode != 0:  # vkray's own lines, without the listing and valgrind's
        said = [l for l in r.stdout.splitlines() if l.strip() and not re.match(r"^(\s+[0-9a-f]+:\t|[\w.]+:$|==\d+==)", l)]
        sys.exit(f"kernel-profile: the render failed (exit {r.returncode}):\n" + "\n".join(said[-20:]))
    return out, r.stdout


def machine_code(log):
    """GALLIVM_DEBUG=asm's listing: {function index: (name, {offset: instruction text})}."""
    functions, current = [], None
    for line in log.splitlines():
        head = re.match(r"^([A-Za-z_][\w.]*):$", line)
        if head:
            current = (head.group(1), {})
            functions.append(current)
            continue
        ins = re.match(r"^\s+([0-9a-f]+):\t(.*)$", line)
        if ins and current:
            current[1][int(ins.group(1), 16)] = ins.group(2)
    return functions


def jit_costs(path):
    """Per function of code without an object file (llvmpipe's), instructions executed at each address."""
    objects, functions = {}, {}
    costs = collections.defaultdict(collections.Counter)
    jit, fn, addr, skip = False, None, 0, False

    def named(table, value):  # "(id) name" defines id, "(id)" refers to it
        ident, _, name = value.partition(")")
        if name.strip():
            table[ident] = name.strip()
        return table.get(ident, ident)

    for line in open(path, errors="replace"):
        line = line.rstrip("\n")
        key, eq, value = line.partition("=")
        if eq and key in ("ob", "cob"):
            name = named(objects, value)
            if key == "ob":
                jit = name == "???"
            continue
        if eq and key in ("fn", "cfn"):
            name = named(functions, value)
            if key == "fn":
                fn = name
            continue
        if eq and key == "calls":
            skip = True  # the next line is the call's inclusive cost
            continue
        if not line or line[0] not in "0123456789+-*":
            continue
        parts = line.split()
        pos = parts[0]
        if pos.startswith("0x"):
            addr = int(pos, 16)
        elif pos[0] in "+-":
            addr += int(pos[1:], 0) if pos[0] == "+" else -int(pos[1:], 0)
        if skip:
            skip = False
            continue
        if jit and len(parts) >= 3:
            costs[fn][addr] += int(parts[2])
    return costs


def match(start, counts, functions):
    """The listed function whose offsets hold every executed address of the profile's function."""
    best, best_share = None, 0.0
    for name, listing in functions:
        inside = sum(1 for a in counts if (a - start) in listing)
        share = inside / max(len(counts), 1)
        if share > best_share:
            best, best_share = (name, listing), share
    return best if best_share >= 0.99 else None


def blocks(listing, start, counts):
    """Runs of consecutive instructions executed equally often: (their offsets, executions)."""
    runs = []
    for off in sorted(listing):
        n = counts.get(start + off, 0)
        if runs and runs[-1][1] == n:
            runs[-1][0].append(off)
        else:
            runs.append(([off], n))
    return [r for r in runs if r[1] > 0]


def main():
    args = parse()
    with tempfile.TemporaryDirectory() as tmp:
        out, log = run(args, tmp)
        costs = jit_costs(out)
    functions = machine_code(log)
    total = sum(sum(c.values()) for c in costs.values())
    print(f"instructions executed in llvmpipe's code: {total:,}")
    ranked = sorted(costs.items(), key=lambda kv: -sum(kv[1].values()))
    listed = [match(int(fn, 16) if fn.startswith("0x") else 0, counts, functions) for fn, counts in ranked[:6]]
    for (fn, counts), m in zip(ranked, listed):
        n = sum(counts.values())
        print(f"  {n:>14,}  {100.0 * n / max(total, 1):5.1f}%  {m[0] if m else '(not in the listing)'} at {fn}")
    if not ranked:
        sys.exit("kernel-profile: callgrind saw no code of llvmpipe's")
    fn, counts = ranked[0]
    start, m = int(fn, 16), listed[0]
    if not m:
        sys.exit("kernel-profile: the largest function is not in GALLIVM_DEBUG's listing")
    body = sum(counts.values())
    print(f"\n{m[0]}: its blocks, the most instructions first (offset, instructions, executions, share)")
    for offsets, n in sorted(blocks(m[1], start, counts), key=lambda r: -len(r[0]) * r[1])[:args.top]:
        moves = sum(1 for o in offsets if m[1][o].split()[0].startswith(("vmov", "mov")))
        print(f"  {offsets[0]:6x}  {len(offsets):5d} x {n:>10,}  {100.0 * len(offsets) * n / body:5.1f}%"
              f"  ({moves} register or stack moves)")
        for o in offsets[:args.asm]:
            print(f"          {o:6x}: {m[1][o]}")


if __name__ == "__main__":
    main()
