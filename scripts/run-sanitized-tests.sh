#!/usr/bin/env bash
# Runs the tests of a sanitizer build (`make sanitize`): the GoogleTest binaries NAME..., two at a
# time, each with its output in BUILD/NAME.log, then CTest's runs of the sanitized vkray binary
# (tests/cli: bad input through the command line; tests/bench, tests/golden). A sanitizer finding
# aborts its process with a report (abort_on_error), which fails the run and prints the log.
# usage: scripts/run-sanitized-tests.sh BUILD NAME...
set -uo pipefail
build=$1; shift
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:abort_on_error=1
export VKRAY_VALIDATION=1  # as under CTest: a Vulkan validation error fails a GPU test

# Lavapipe stays loaded until exit. The Vulkan loader unmaps the driver when the last instance is
# destroyed; with Debian's Mesa 22.3.6-1+deb12u2 some of the driver's allocations are then referenced
# only from its unmapped globals, and LeakSanitizer reports them as a leak in an unknown module
# (2 x 128 bytes after every process that used the GPU). Preloaded, the driver is never unmapped and
# they stay reachable; vkray's own leaks are still found. verify_asan_link_order=0 lets the
# sanitized binaries start with a library ahead of the ASan runtime; the tools around them (bash,
# xargs, ctest) are not sanitized and only load the driver. Mesa 25's manifest names the driver by
# its file name alone: nothing is preloaded there, and LeakSanitizer finds no such leak.
lvp=$(sed -n 's/.*"library_path": *"\([^"]*libvulkan_lvp[^"]*\)".*/\1/p' /usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -n 1)
if [[ -n "$lvp" && -e "$lvp" ]]; then
  export LD_PRELOAD="$lvp"
  export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"
fi

run_one() {
  local build=$1 name=$2 start=$SECONDS rc=0
  # A build without the sanitizers would pass and prove nothing (say, CMakeLists.txt lost the option).
  if ! grep -q -a __asan_init "$build/tests/$name" || ! grep -q -a __ubsan_handle "$build/tests/$name"; then
    echo "sanitize: $build/tests/$name is not built with ASan + UBSan (-DVKRAY_SANITIZE=ON ignored?)"
    return 1
  fi
  timeout 1800 "$build/tests/$name" --gtest_brief=1 >"$build/$name.log" 2>&1 || rc=$?
  if [[ $rc -eq 0 ]]; then
    echo "sanitize: $name passed in $((SECONDS - start)) s"
  else
    cat "$build/$name.log"
    echo "sanitize: $name FAILED (exit $rc) after $((SECONDS - start)) s; log: $build/$name.log"
    return 1
  fi
}
export -f run_one
printf '%s\n' "$@" | xargs -P 2 -I{} bash -c 'run_one "$0" "$1"' "$build" {} || exit 1

# The vkray binary as users run it. tests/cli/expect_error.sh also fails on a sanitizer report in
# stderr, so a finding after the expected error line is not missed either.
start=$SECONDS
if ! (cd "$build" && ctest -R '^(cli|bench|golden)\.' -j 2 --timeout 900 --output-on-failure >ctest.log 2>&1); then
  cat "$build/ctest.log"
  echo "sanitize: CTest's runs of vkray FAILED after $((SECONDS - start)) s; log: $build/ctest.log"
  exit 1
fi
echo "sanitize: $(grep -E '^[0-9]+% tests passed' "$build/ctest.log") (CTest's runs of vkray) in $((SECONDS - start)) s"
