#!/usr/bin/env bash
# A `vkray bench` run refused before it measures anything: the one clean error line that
# tests/cli/expect_error.sh checks, and no results in --out.
# usage: expect_refused.sh OUT PATTERN VKRAY bench ... --out OUT
set -u
out=$1; shift
rm -rf "$out"
"$(dirname "$0")/../cli/expect_error.sh" "$@" || exit 1
for f in bench.json bench.md report.html; do
  [[ ! -e $out/$f ]] || { echo "FAIL: a refused run left $out/$f"; exit 1; }
done
echo "ok: nothing in $out"
