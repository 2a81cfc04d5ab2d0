#!/usr/bin/env bash
# Runs a vkray command that must fail cleanly: a non-zero exit that is not a crash (signal) or a
# time-out, and exactly one "error: " line on stderr that matches the expected pattern.
# usage: [EXPECT_RC=N] expect_error.sh PATTERN COMMAND [ARGS...]   (EXPECT_RC: the exit status it must be)
set -u
pattern=$1; shift
command="$*"
err=$(mktemp); out=$(mktemp)
trap 'rm -f "$err" "$out"' EXIT
timeout 120 "$@" >"$out" 2>"$err"
rc=$?
fail() { echo "FAIL: $*"; echo "--- command: $command"; echo "--- stderr:"; cat "$err"; exit 1; }
[[ $rc -eq 0 ]] && fail "exit code 0, expected an error"
[[ $rc -eq 124 ]] && fail "timed out (a hang)"
[[ $rc -ge 128 ]] && fail "killed by signal $((rc - 128)) (a crash)"
[[ -n "${EXPECT_RC:-}" && $rc -ne $EXPECT_RC ]] && fail "exit code $rc, expected $EXPECT_RC"
# A sanitizer build (`make sanitize`) reports there; such a report is a bug even after a clean error.
grep -q -E 'Sanitizer|runtime error:' "$err" && fail "a sanitizer report"
n=$(grep -c '^error: ' "$err")
[[ $n -eq 1 ]] || fail "expected exactly one 'error: ' line, got $n"
grep -E -q -- "^error: .*${pattern}" "$err" || fail "error line does not match '$pattern'"
echo "ok (exit $rc): $(grep '^error: ' "$err")"
