#!/usr/bin/env bash
# usage: profile-kernel.sh OUTDIR VKRAY [render args...]
# Where a kernel's time goes on lavapipe, instruction by instruction. llvmpipe JIT-compiles the
# kernel, and Mesa's shader cache keeps the machine code as an ELF object (zstd-compressed after a
# small header): the render runs with a fresh MESA_SHADER_CACHE_DIR under perf (one lavapipe
# thread), the object is unpacked and disassembled, and perf's samples in the JIT mapping are laid
# on the disassembly by their offset from the mapping's page. Writes OUTDIR/annotated.s (samples per
# instruction) and prints the samples per function (cs_co_variant is the kernel, texfunc_* the
# texel-fetch functions, one per texel view).
# Example: profile-kernel.sh /tmp/prof build/vkray render scenes/primary/bunny.scene --view close --size 2048x1536 -o /tmp/p.png
set -euo pipefail
out=$1; shift
rm -rf "$out"; mkdir -p "$out/cache"
LP_NUM_THREADS=1 MESA_SHADER_CACHE_DIR="$out/cache" perf record -q -e cpu-clock -F 5000 -o "$out/perf.data" "$@" >/dev/null 2>&1
blob=$(ls -S $(find "$out/cache" -type f ! -name index) | head -1)  # the kernel is the largest entry
python3 - "$blob" "$out/kernel.o" <<'PY'
import subprocess, sys
data = open(sys.argv[1], "rb").read()
start = data.index(b"\x28\xb5\x2f\xfd")  # zstd frame magic
open(sys.argv[2], "wb").write(subprocess.run(["zstd", "-dc"], input=data[start:], capture_output=True, check=True).stdout)
PY
objdump -d --no-show-raw-insn "$out/kernel.o" > "$out/kernel.s"
perf script -i "$out/perf.data" -F ip,dso 2>/dev/null | awk '/perf-/ {print $1}' > "$out/ips.txt"
python3 - "$out" <<'PY'
import collections, re, sys
out = sys.argv[1]
ips = [int(x, 16) for x in open(f"{out}/ips.txt")]
base = min(ips) & ~0xFFF  # the JIT mapping's first page holds the object's .text from offset 0
samples = collections.Counter(ip - base for ip in ips)
per_function, lines, current = collections.Counter(), [], None
for line in open(f"{out}/kernel.s").read().splitlines():
    m = re.match(r"^([0-9a-f]+) <(.*)>:", line)
    if m:
        current = m.group(2)
        lines.append(line)
        continue
    m = re.match(r"^\s+([0-9a-f]+):", line)
    if m:
        n = samples.get(int(m.group(1), 16), 0)
        per_function[current] += n
        lines.append(f"{n:6d} {line}")
open(f"{out}/annotated.s", "w").write("\n".join(lines) + "\n")
print(f"{len(ips)} samples in the JIT code")
for name, n in per_function.most_common(8):
    print(f"  {name:28s} {n:6d} {100 * n / max(len(ips), 1):5.1f}%")
PY
