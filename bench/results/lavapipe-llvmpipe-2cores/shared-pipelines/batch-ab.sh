#!/usr/bin/env bash
# usage: batch-ab.sh OLD_BIN NEW_BIN ROUNDS SCENES...
# Every scene in one `vkray render` call (--out-dir), the whole command's wall clock: OLD_BIN and
# NEW_BIN on the GPU (the default device and accelerator) and NEW_BIN --cpu, interleaved in every
# round; medians, and the GPU's over the CPU's. Then each new GPU image against the old one.
set -euo pipefail
OLD=$1; NEW=$2; N=$3; shift 3
tmp=$(mktemp -d); mkdir -p "$tmp/old" "$tmp/new" "$tmp/cpu"
for ((r = 0; r < N; r++)); do
  for mode in old new cpu; do
    bin=$NEW; extra=()
    [[ $mode == old ]] && bin=$OLD
    [[ $mode == cpu ]] && extra=(--cpu)
    t0=$(date +%s%N)
    "$bin" render "$@" "${extra[@]}" --quiet --out-dir "$tmp/$mode"
    t1=$(date +%s%N)
    echo "$mode $(((t1 - t0) / 1000000))"
  done
done | python3 -c '
import collections, statistics as st, sys
d = collections.defaultdict(list)
for line in sys.stdin:
    k, v = line.split(); d[k].append(float(v))
m = {k: st.median(v) for k, v in d.items()}
for k in ("old", "new", "cpu"): print(f"{k:4s} median {m[k]:7.0f} ms   rounds {d[k]}")
print("new / old %.3f   old GPU / CPU %.3f   new GPU / CPU %.3f" % (m["new"] / m["old"], m["old"] / m["cpu"], m["new"] / m["cpu"]))'
for f in "$tmp"/new/*; do
  "$NEW" compare "$f" "$tmp/old/$(basename "$f")" --threshold 0 --max-rmse 0 --max-bad-fraction 0 --quiet \
    && echo "identical: $(basename "$f")" || echo "DIFFERENT: $(basename "$f")"
done
rm -rf "$tmp"
