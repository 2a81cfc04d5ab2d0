#!/usr/bin/env bash
# Runs each fuzz target of tests/fuzz for SECONDS on its corpus (make_corpus.sh), PARALLEL targets at a
# time, each its own process with its own log (BUILD/fuzz-NAME.log). A crash, a sanitizer report, a
# leak, an input that takes 10 s or an allocation past 2 GiB fails the target: its log is printed and
# its input left in BUILD/artifacts/ (named NAME-crash-..., NAME-oom-..., NAME-timeout-...). Replay
# one with BUILD/tests/fuzz/vkray_fuzz_NAME FILE.
# usage: tests/fuzz/run_fuzz.sh BUILD SECONDS PARALLEL [NAME...]   (default: every target)
set -uo pipefail
build=$1 seconds=$2 parallel=$3
shift 3
targets=("$@")
(( ${#targets[@]} )) || targets=(scene obj off ply gltf image)
mkdir -p "$build/artifacts"
echo "fuzz: ${seconds} s each of ${targets[*]}, $parallel at a time (logs: $build/fuzz-NAME.log)"

run_one() {  # NAME: exit status of the fuzzer
  "$build/tests/fuzz/vkray_fuzz_$1" -max_total_time="$seconds" -dict="$build/corpus/$1.dict" -max_len=32768 \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$build/artifacts/$1-" \
    "$build/corpus/$1" >"$build/fuzz-$1.log" 2>&1
}
export -f run_one
export build seconds
printf '%s\n' "${targets[@]}" | xargs -P "$parallel" -I{} bash -c 'run_one {}; echo "{} $?" >"$build/fuzz-{}.rc"'

failed=0
for t in "${targets[@]}"; do
  rc=$(cut -d' ' -f2 "$build/fuzz-$t.rc" 2>/dev/null || echo 1)
  if [[ $rc == 0 ]]; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build/fuzz-$t.log")
    cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' "$build/fuzz-$t.log" | tail -1)
    echo "fuzz: $t: ${runs:-?} runs, $cov"
  else
    cat "$build/fuzz-$t.log"
    echo "fuzz: $t FAILED (exit $rc), input in $build/artifacts/"
    failed=1
  fi
done
exit $failed
