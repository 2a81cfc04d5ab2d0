#!/usr/bin/env bash
# `vkray bench` given SIGTERM again and again once its first scene is saved: the first asks the run
# to stop and save, the next one that lands before it has ends the process with the signal's status
# (143). Signals sent while one is pending merge into one, so they go 5 ms apart; on a busy machine
# the run may still finish its save first (status 1). Either way what --out holds is whole: no
# temporary file of an output being written, and a bench.json with the finished scene.
# usage: bench_second_signal.sh VKRAY OUT SCENE...  (three or more)
set -euo pipefail
. "$(dirname "$0")/wait_first_scene.sh"
vkray=$1 out=$2
shift 2
fail() { echo "FAIL: $*"; cat "$out.err" 2>/dev/null; exit 1; }
rm -rf "$out" "$out.err"
"$vkray" bench "$@" --size 32x24 --repeat 1 --threads 1 --accel bvh,kd-stack --deltas 8 --maxdepths none \
  --out "$out" 2>"$out.err" >/dev/null &
pid=$!
wait_first_scene "$pid" "$out"
kill -TERM "$pid" 2>/dev/null || fail "the run ended before the signals"
for _ in $(seq 2000); do kill -TERM "$pid" 2>/dev/null || break; sleep 0.005; done
rc=0
wait "$pid" || rc=$?
[[ $rc -eq 143 || $rc -eq 1 ]] || fail "exit status $rc, expected 143 (ended by a later SIGTERM) or 1 (saved first)"
left=$(find "$out" -name '.*vkray-*')
[[ -z $left ]] || fail "temporary files left: $left"
jq -e '.scenes | length >= 1' "$out/bench.json" >/dev/null || fail "bench.json lost its finished scene"
rm -f "$out.err"
echo "ok: exit status $rc, --out whole"
