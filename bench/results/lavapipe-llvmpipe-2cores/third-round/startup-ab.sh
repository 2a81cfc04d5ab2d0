#!/usr/bin/env bash
# usage: startup-ab.sh ROUNDS SCENE BIN...: the whole `vkray render SCENE` command's wall clock for
# each binary, interleaved round by round; median and minimum in ms.
N=$1; SCENE=$2; shift 2
declare -A t
for ((r = 0; r < N; r++)); do
  for b in "$@"; do
    t0=$(date +%s%N); "$b" render "$SCENE" -o /tmp/startup-ab.png >/dev/null 2>&1; t1=$(date +%s%N)
    t[$b]="${t[$b]} $(( (t1 - t0) / 1000 ))"
  done
done
for b in "$@"; do
  python3 - "$b" "${t[$b]}" <<'PY'
import sys, statistics as st
v = [int(x) / 1000 for x in sys.argv[2].split()]
print(f"{sys.argv[1][-28:]:28s} median {st.median(v):6.1f} ms  min {min(v):6.1f} ms")
PY
done
