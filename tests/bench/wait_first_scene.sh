# Sourced by the bench CLI tests that interrupt a run: wait_first_scene PID OUT returns once the
# `vkray bench` run PID has saved its first scene in OUT/bench.json, or has ended, or after 240 s.
wait_first_scene() {
  local pid=$1 out=$2
  for _ in $(seq 2400); do
    jq -e '.scenes | length >= 1' "$out/bench.json" >/dev/null 2>&1 && return 0
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
}
