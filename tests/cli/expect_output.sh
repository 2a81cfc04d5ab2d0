#!/usr/bin/env bash
# Runs a vkray command that must succeed: exit code 0 (not a crash, not an error) and output
# (stdout and stderr together) with a line matching the expected extended regular expression.
# CTest's PASS_REGULAR_EXPRESSION would check the output alone and ignore the exit code.
# usage: expect_output.sh PATTERN COMMAND [ARGS...]
set -u
pattern=$1; shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$@" >"$out" 2>&1
rc=$?
cat "$out"
[[ $rc -eq 0 ]] || { echo "FAIL: exit code $rc, expected 0 (command: $*)"; exit 1; }
grep -E -q -- "$pattern" "$out" || { echo "FAIL: no line matches '$pattern' (command: $*)"; exit 1; }
echo "ok: a line matches '$pattern'"
