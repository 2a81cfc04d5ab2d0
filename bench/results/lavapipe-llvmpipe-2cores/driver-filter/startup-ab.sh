#!/usr/bin/env bash
# usage: startup-ab.sh OLD_BIN NEW_BIN ROUNDS SCENE [render args...]
# The whole `vkray render` command's wall clock with OLD_BIN and NEW_BIN, alternated every round;
# medians, and the median and range of the per-round ratios new / old.
OLD=$1; NEW=$2; N=$3; SCENE=$4; shift 4
for ((r=0; r<N; r++)); do
  for b in old new; do
    bin=$OLD; [[ $b == new ]] && bin=$NEW
    t0=$(date +%s%N)
    $bin render "$SCENE" "$@" -o /tmp/startup-$b.png >/dev/null 2>&1 || echo "FAIL $b" >&2
    t1=$(date +%s%N)
    echo "$b $(( (t1 - t0) / 1000 ))"
  done
done | awk -v what="$SCENE $*" -v n="$N" '
  $1 == "old" { o[++no] = $2 } $1 == "new" { w[++nw] = $2; r[nw] = $2 / o[nw] }
  function med(a, k,   i, j, t) {  # insertion sort, then the middle
    for (i = 2; i <= k; i++) for (j = i; j > 1 && a[j-1] > a[j]; j--) { t = a[j]; a[j] = a[j-1]; a[j-1] = t }
    return a[int((k + 1) / 2)] }
  END { mo = med(o, no); mw = med(w, nw); mr = med(r, nw)
        printf "%s: old %.1f ms, new %.1f ms, new/old %.3f (rounds %.3f-%.3f), %d rounds\n", what, mo / 1000, mw / 1000, mr, r[1], r[nw], n }'
