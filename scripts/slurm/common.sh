# shellcheck shell=bash
# Sourced by submit-bench.sh and submit-render.sh: the vkray binary, sbatch, and waiting for jobs.
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)

# The script's "# usage:" comment, without the "# ", on stderr.
usage() { sed -n '/^# usage:/,/^[^#]/s/^# \{0,1\}//p' "$0" >&2; }

# The options both submit scripts take before their arguments: --wait and --tasks LIST. Sets `wait`
# and `tasks`, and `options_used` to the number of words they took (the caller shifts them away).
parse_submit_options() {
  wait=0 tasks="" options_used=0
  while [[ $# -gt 0 && $1 == --* ]]; do
    case $1 in
      --wait) wait=1; shift; options_used=$((options_used + 1)) ;;
      --tasks) tasks=${2:?--tasks needs a list}; shift 2; options_used=$((options_used + 2)) ;;
      *) echo "$(basename "$0" .sh): unknown option $1" >&2; exit 2 ;;
    esac
  done
}

# Refuses a task count N that is not a positive number.
check_count() {
  [[ $1 =~ ^[1-9][0-9]*$ ]] || { echo "$(basename "$0" .sh): N must be a positive number, not '$1'" >&2; exit 2; }
}

# VKRAY, else vkray on PATH, else this checkout's build/vkray; as an absolute path, for the jobs.
vkray_binary() {
  local v=${VKRAY:-}
  [[ -n "$v" ]] || v=$(command -v vkray || true)
  [[ -n "$v" ]] || v=$repo/build/vkray
  [[ -x "$v" ]] || { echo "$(basename "$0"): no vkray binary at '$v' (set VKRAY)" >&2; exit 1; }
  realpath "$v"
}

# sbatch with SBATCH_OPTIONS (e.g. "--partition=gpu --gres=gpu:1") before the given options; prints
# the job id.
submit() {
  local out
  # shellcheck disable=SC2086  # SBATCH_OPTIONS is a list of options
  out=$(sbatch --parsable ${SBATCH_OPTIONS:-} "$@") || exit 1
  echo "${out%%;*}"
}

# Waits until none of the jobs is queued or running (polling squeue every POLL seconds, default 2),
# then prints each one's final state from scontrol and fails unless the last one COMPLETED.
wait_jobs() {
  local ids
  ids=$(IFS=,; echo "$*")
  while [[ -n "$(squeue -h -j "$ids" -o %i 2>/dev/null)" ]]; do sleep "${POLL:-2}"; done
  local id state=""
  for id in "$@"; do
    state=$(scontrol show job "$id" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort | uniq -c |
            awk '{ printf "%s%s x%d", sep, $2, $1; sep = ", " }')
    echo "job $id: ${state:-gone from the controller}"
  done
  scontrol show job "${!#}" 2>/dev/null | grep -q 'JobState=COMPLETED'
}
