#!/usr/bin/env bash
# `vkray bench` stopped by SIGTERM once its first scene is saved, then `--resume`: the interrupted
# run exits non-zero and leaves the finished scenes marked incomplete in all three files; the
# resumed run measures only the missing scenes, keeps the saved ones' figures and completes the
# report; a third --resume finds nothing to measure; --resume with other settings is refused.
# usage: bench_interrupt_resume.sh VKRAY OUT SCENE...  (three or more)
set -euo pipefail
. "$(dirname "$0")/wait_first_scene.sh"
vkray=$1 out=$2
shift 2
scenes=("$@")
fail() { echo "FAIL: $*"; for f in "$out".err*; do echo "--- $f:"; cat "$f"; done; exit 1; }
rm -rf "$out" "$out".err*
opts=(--size 32x24 --repeat 1 --threads 1 --accel bvh,kd-stack --deltas 8 --maxdepths none --out "$out")

"$vkray" bench "${scenes[@]}" "${opts[@]}" 2>"$out.err1" >/dev/null &
pid=$!
wait_first_scene "$pid" "$out"
kill -TERM "$pid" 2>/dev/null || true
rc=0
wait "$pid" || rc=$?
[[ $rc -ne 0 ]] || fail "the interrupted run exited 0 (did it finish before SIGTERM?)"
grep -q '^error: interrupted by SIGTERM' "$out.err1" || fail "no 'interrupted by SIGTERM' error"
grep -q "marked incomplete; --resume measures the rest" "$out.err1" || fail "no line about the saved scenes"
done=$(jq '.scenes | length' "$out/bench.json")
[[ $done -ge 1 && $done -lt ${#scenes[@]} ]] || fail "$done scenes saved"
jq -e --argjson done "$done" --args '.complete == false and .failure == "interrupted by SIGTERM"
    and .missing_scenes == $ARGS.positional[$done:]' "${scenes[@]}" <"$out/bench.json" >/dev/null ||
  fail "bench.json is not marked incomplete with the missing scenes"
grep -q '^> \*\*Incomplete:\*\* .*interrupted by SIGTERM' "$out/bench.md" || fail "bench.md is not marked incomplete"
grep -q '<p class="incomplete">' "$out/report.html" || fail "report.html is not marked incomplete"
first=$(jq -c '.scenes[0].reference.render_ms, .scenes[0].accelerators[0].trace_ms' "$out/bench.json")

"$vkray" bench "${scenes[@]}" "${opts[@]}" --resume 2>"$out.err2" >/dev/null || fail "--resume failed"
for ((i = 1; i <= done; ++i)); do
  ! grep -q "^bench: scene $i/" "$out.err2" || fail "--resume measured scene $i again"
done
grep -q "^bench: scene ${#scenes[@]}/${#scenes[@]}" "$out.err2" || fail "--resume did not measure the last scene"
jq -e --argjson n "${#scenes[@]}" '.complete == true and .failure == null and .missing_scenes == []
    and (.scenes | length) == $n and ([.scenes[].index] == [range($n)])' "$out/bench.json" >/dev/null ||
  fail "the resumed report is not complete"
[[ $(jq -c '.scenes[0].reference.render_ms, .scenes[0].accelerators[0].trace_ms' "$out/bench.json") == "$first" ]] ||
  fail "scene 1's figures changed"
! grep -q Incomplete "$out/bench.md" || fail "bench.md still says incomplete"
! ls "$out"/images/*.pfm >/dev/null 2>&1 || fail "the complete report kept the pixels of the incomplete one"

report=$(md5sum "$out"/bench.json "$out"/bench.md "$out"/report.html "$out"/images/*)
"$vkray" bench "${scenes[@]}" "${opts[@]}" --resume >"$out.err3" 2>&1 || fail "--resume of a complete run failed"
grep -q "the run is complete: nothing left to measure" "$out.err3" || fail "no 'nothing left to measure'"
! grep -q "^bench: scene" "$out.err3" || fail "--resume of a complete run measured"
[[ $(md5sum "$out"/bench.json "$out"/bench.md "$out"/report.html "$out"/images/*) == "$report" ]] ||
  fail "--resume of a complete run changed its report"

opts[3]=2  # --repeat 2
if "$vkray" bench "${scenes[@]}" "${opts[@]}" --resume 2>"$out.err4" >/dev/null; then fail "resumed another run"; fi
grep -q "^error: .*bench.json: --resume: other settings: repeat is 1 here, 2 in this run" "$out.err4" ||
  fail "no error naming the other setting"
rm -f "$out".err*
echo "ok: interrupted after $done of ${#scenes[@]} scenes, resumed"
