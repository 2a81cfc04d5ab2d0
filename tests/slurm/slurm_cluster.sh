# shellcheck shell=bash
# A throwaway single-node Slurm for the tests of tests/slurm/, sourced: munged, slurmctld and slurmd
# on localhost, every file (keys, state, spool, logs) in one temporary folder, every daemon started
# in the foreground in the background and stopped by its PID (never by name: other things run on the
# machine). Jobs run as the user running the test.
#   slurm_start       starts it in a new temporary folder, exports SLURM_CONF; fails, saying why, if
#                     it cannot
#   slurm_stop        cancels its jobs, waits for them, stops the daemons, removes the folder
#                     (installed as an EXIT trap)
#   slurm_wait ID...  waits until none of the jobs is queued or running (0.25 s polls)
#   slurm_state ID    the job's JobState (of every task, for an array), from scontrol

slurm_pids=()
slurm_dir=""

slurm_fail() {
  echo "FAIL: Slurm cannot start: $*" >&2
  local log
  for log in "$slurm_dir"/*.log; do
    [[ -s "$log" ]] && { echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; }
  done
  exit 1
}

# Two ports nothing listens on, from a base that differs per test run (CTest may run tests in
# parallel, and each Slurm needs its own).
slurm_ports() {
  local p=$((20000 + ($$ % 2000) * 2))
  while (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || (exec 3<>"/dev/tcp/127.0.0.1/$((p + 1))") 2>/dev/null; do
    p=$((p + 2))
  done
  echo "$p $((p + 1))"
}

slurm_start() {
  local tool
  for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
    command -v "$tool" >/dev/null || slurm_fail "$tool is not installed (scripts/install-deps.sh installs slurmctld slurmd slurm-client munge)"
  done
  slurm_dir=$(mktemp -d) || slurm_fail "no temporary folder"
  trap slurm_stop EXIT
  mkdir -p "$slurm_dir"/{munge,state,spool}
  chmod 755 "$slurm_dir" "$slurm_dir/munge"  # munged wants o+x on its socket's folders
  mungekey -c -k "$slurm_dir/munge/munge.key" || slurm_fail "mungekey could not create a key"
  munged -F --key-file="$slurm_dir/munge/munge.key" --socket="$slurm_dir/munge/munge.sock" \
         --pid-file="$slurm_dir/munge/munged.pid" --log-file="$slurm_dir/munged.log" \
         --seed-file="$slurm_dir/munge/munged.seed" 2>>"$slurm_dir/munged.log" &
  slurm_pids+=($!)
  local i
  for ((i = 0; i < 40; i++)); do
    [[ -S "$slurm_dir/munge/munge.sock" ]] && break
    sleep 0.25
  done
  [[ -S "$slurm_dir/munge/munge.sock" ]] || slurm_fail "munged made no socket in 10 s"

  local node ports
  node=$(slurmd -C | head -1 | sed -E 's/^NodeName=[^ ]+ //') || slurm_fail "slurmd -C failed"
  read -r -a ports <<<"$(slurm_ports)"
  cat >"$slurm_dir/slurm.conf" <<CONF
ClusterName=vkraytest
SlurmctldHost=localhost
SlurmUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$slurm_dir/munge/munge.sock
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
StateSaveLocation=$slurm_dir/state
SlurmdSpoolDir=$slurm_dir/spool
SlurmctldPidFile=$slurm_dir/slurmctld.pid
SlurmdPidFile=$slurm_dir/slurmd.pid
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MailProg=/bin/true
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 $node State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$slurm_dir/slurm.conf
  slurmctld -D -i 2>"$slurm_dir/slurmctld.log" &
  slurm_pids+=($!)
  slurmd -D -N localhost 2>"$slurm_dir/slurmd.log" &
  slurm_pids+=($!)
  local start=$SECONDS
  until [[ "$(sinfo -h -o %T 2>/dev/null)" == idle ]]; do
    ((SECONDS - start < 30)) || slurm_fail "the node is not idle after 30 s (sinfo: $(sinfo -h -o %T 2>&1 | head -1))"
    local pid
    for pid in "${slurm_pids[@]}"; do kill -0 "$pid" 2>/dev/null || slurm_fail "a daemon (PID $pid) exited"; done
    sleep 0.25
  done
  echo "slurm: up in $((SECONDS - start)) s or less on ports ${ports[*]}, node: $node"
}

slurm_stop() {
  [[ ${#slurm_pids[@]} -gt 0 ]] || return 0
  # Jobs' processes belong to PID 1, not to slurmd: cancel them while slurmd is up.
  local jobs
  jobs=$(squeue -h -o %A 2>/dev/null | sort -u | tr '\n' ' ')
  if [[ -n "${jobs// /}" ]]; then
    # shellcheck disable=SC2086
    scancel $jobs 2>/dev/null || true
    local i
    for ((i = 0; i < 80; i++)); do
      [[ -z "$(squeue -h 2>/dev/null)" ]] && break
      sleep 0.25
    done
  fi
  local k pid
  for ((k = ${#slurm_pids[@]} - 1; k >= 0; k--)); do
    pid=${slurm_pids[k]}
    kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  done
  slurm_pids=()
  [[ -n "$slurm_dir" ]] && rm -rf "$slurm_dir"
}

slurm_wait() {
  local ids
  ids=$(IFS=,; echo "$*")
  while [[ -n "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ]]; do sleep 0.25; done
}

slurm_state() {
  scontrol show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort | uniq -c | tr -s ' ' | xargs
}
