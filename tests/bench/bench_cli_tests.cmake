# `vkray bench` end to end, as a user runs it. Included from tests/CMakeLists.txt; the report's
# completeness is checked in depth by bench_smoke_test.cpp, this checks the command itself.
set(BENCH_OUT ${CMAKE_BINARY_DIR}/test-output/bench-cli)
set(BENCH_SCENE ${CMAKE_SOURCE_DIR}/scenes/objects.scene)

# Each test writes below a folder of its own: run_bench_cli.cmake empties its OUT first, and the
# tests run in parallel.
add_test(NAME bench.cli.writes_report
         COMMAND ${CMAKE_COMMAND} -DVKRAY=$<TARGET_FILE:vkray> -DSCENE=${BENCH_SCENE} -DOUT=${BENCH_OUT}/report
                 -P ${CMAKE_CURRENT_SOURCE_DIR}/bench/run_bench_cli.cmake)
set_tests_properties(bench.cli.writes_report PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")

# Bad options fail before any measuring, with one error line.
set(expect_error ${CMAKE_CURRENT_SOURCE_DIR}/cli/expect_error.sh)
function(vkray_bench_error name pattern)
  add_test(NAME bench.cli.error.${name} COMMAND ${expect_error} "${pattern}" $<TARGET_FILE:vkray> bench ${ARGN})
  set_tests_properties(bench.cli.error.${name} PROPERTIES TIMEOUT 120)
endfunction()
vkray_bench_error(missing_scene "nope\\.scene: no such scene file" ${BENCH_OUT}/nope.scene --out ${BENCH_OUT}/x)
vkray_bench_error(unknown_accel "octree" ${BENCH_SCENE} --accel bvh,octree --out ${BENCH_OUT}/x)
vkray_bench_error(bad_accel_tuning "--accel bvh:aac-delta=x: 'aac-delta=x': the value is not a number" ${BENCH_SCENE} --accel bvh,bvh:aac-delta=x --out ${BENCH_OUT}/x)
vkray_bench_error(empty_accel_item "--accel bvh,,kd-stack: empty item" ${BENCH_SCENE} --accel bvh,,kd-stack --out ${BENCH_OUT}/x)
vkray_bench_error(repeat_zero "--repeat 0" ${BENCH_SCENE} --repeat 0 --out ${BENCH_OUT}/x)
vkray_bench_error(bad_delta "--deltas 4,x" ${BENCH_SCENE} --deltas 4,x --out ${BENCH_OUT}/x)
vkray_bench_error(bad_threads "--threads -1" ${BENCH_SCENE} --threads -1 --out ${BENCH_OUT}/x)
vkray_bench_error(huge_threads "--threads 1,2000: '2000' is not an integer in 0\\.\\.1024" ${BENCH_SCENE} --threads 1,2000 --out ${BENCH_OUT}/x)
vkray_bench_error(bad_size "--size 10x" ${BENCH_SCENE} --size 10x --out ${BENCH_OUT}/x)
vkray_bench_error(out_not_a_folder "--out .*cannot create" ${BENCH_SCENE} --out ${BENCH_SCENE}/sub)
# --shard and --merge (docs/cluster.md); a merge that works is run by tests/slurm and bench_shard_test.
vkray_bench_error(bad_shard "--shard 4/4: expected I/N with 0 <= I < N" ${BENCH_SCENE} --shard 4/4 --out ${BENCH_OUT}/x)
vkray_bench_error(shard_not_a_fraction "--shard 1: expected I/N" ${BENCH_SCENE} --shard 1 --out ${BENCH_OUT}/x)
vkray_bench_error(merge_no_report "nope/bench.json: no such file" --merge ${BENCH_OUT}/nope --out ${BENCH_OUT}/x)
vkray_bench_error(merge_with_shard "--shard measures, --merge only merges" --merge ${BENCH_OUT}/nope --shard 0/2 --out ${BENCH_OUT}/x)
vkray_bench_error(merge_with_resume "--resume excludes --merge|--merge excludes --resume" --merge ${BENCH_OUT}/nope --resume --out ${BENCH_OUT}/x)
vkray_bench_error(merge_with_scenes "scenes excludes --merge|--merge excludes scenes" ${BENCH_SCENE} --merge ${BENCH_OUT}/nope --out ${BENCH_OUT}/x)
# Every scene is checked before the first is measured: a missing or unloadable second scene is
# refused at once, and --out gets no results.
set(expect_refused ${CMAKE_CURRENT_SOURCE_DIR}/bench/expect_refused.sh)
set(ONE_TRIANGLE ${CMAKE_SOURCE_DIR}/tests/cli/data/one_triangle.scene)
add_test(NAME bench.cli.refuses.missing_second_scene
         COMMAND ${expect_refused} ${BENCH_OUT}/refused-scene "nope\\.scene: no such scene file" $<TARGET_FILE:vkray>
                 bench ${ONE_TRIANGLE} ${BENCH_OUT}/nope.scene --size 16x12 --repeat 1 --out ${BENCH_OUT}/refused-scene)
add_test(NAME bench.cli.refuses.unreadable_mesh
         COMMAND ${expect_refused} ${BENCH_OUT}/refused-mesh "missing_mesh\\.scene:3: cannot open OBJ file" $<TARGET_FILE:vkray>
                 bench ${ONE_TRIANGLE} ${CMAKE_SOURCE_DIR}/tests/cli/data/missing_mesh.scene --size 16x12 --repeat 1
                 --out ${BENCH_OUT}/refused-mesh)
set_tests_properties(bench.cli.refuses.missing_second_scene bench.cli.refuses.unreadable_mesh PROPERTIES TIMEOUT 120)
# SIGTERM after the first scene is saved leaves it marked incomplete; --resume measures the rest.
# Four scenes after the first, so that on a busy machine the run cannot end before the signal lands.
add_test(NAME bench.cli.interrupt_resume
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench/bench_interrupt_resume.sh $<TARGET_FILE:vkray>
                 ${BENCH_OUT}/interrupted ${ONE_TRIANGLE} ${BENCH_SCENE} ${BENCH_SCENE} ${BENCH_SCENE} ${BENCH_SCENE})
set_tests_properties(bench.cli.interrupt_resume PROPERTIES TIMEOUT 600 ENVIRONMENT "VKRAY_VALIDATION=1")
# A second SIGTERM ends the run at once, and --out stays whole.
add_test(NAME bench.cli.second_signal
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/bench/bench_second_signal.sh $<TARGET_FILE:vkray>
                 ${BENCH_OUT}/second-signal ${ONE_TRIANGLE} ${BENCH_SCENE} ${BENCH_SCENE} ${BENCH_SCENE})
set_tests_properties(bench.cli.second_signal PROPERTIES TIMEOUT 600)
# --quiet as render's: the report is written and nothing is printed.
add_test(NAME bench.cli.quiet
         COMMAND bash -c "out=$(\"$0\" bench \"$1\" --size 16x12 --repeat 1 --threads 1 --accel bvh --deltas none --maxdepths none --quiet --out \"$2\") && test -z \"$out\" && test -s \"$2/bench.json\""
                 $<TARGET_FILE:vkray> ${CMAKE_SOURCE_DIR}/tests/cli/data/one_triangle.scene ${BENCH_OUT}/quiet)
set_tests_properties(bench.cli.quiet PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")
# Too few repeats for a spread: a warning on stderr, also with --quiet.
add_test(NAME bench.cli.warns_repeat_one
         COMMAND bash -c "err=$(\"$0\" bench \"$1\" --size 16x12 --repeat 1 --threads 1 --accel bvh --deltas none --maxdepths none --quiet --out \"$2\" 2>&1 >/dev/null) && grep -q '^warning: --repeat 1: spreads of fewer than 3 runs are noise' <<< \"$err\""
                 $<TARGET_FILE:vkray> ${CMAKE_SOURCE_DIR}/tests/cli/data/one_triangle.scene ${BENCH_OUT}/repeat-one)
set_tests_properties(bench.cli.warns_repeat_one PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")
# A preset and a tuned variant of it in one run: both measured, each under the name as written, the
# variant's build with its own options (its reinsertion phase in the report).
add_test(NAME bench.cli.tuned_variant
         COMMAND bash -c "\"$0\" bench \"$1\" --size 32x24 --repeat 1 --threads 1 --accel bvh,bvh:bvh-reinsert-iterations=2 --deltas none --maxdepths none --quiet --out \"$2\" && jq -e '.scenes[0].accelerators | (map(.accel) == [\"bvh\", \"bvh:bvh-reinsert-iterations=2\"]) and (.[1].build_stats | has(\"reinsert_ms\")) and (.[0].build_stats | has(\"reinsert_ms\") | not)' \"$2/bench.json\""
                 $<TARGET_FILE:vkray> ${BENCH_SCENE} ${BENCH_OUT}/tuned)
set_tests_properties(bench.cli.tuned_variant PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")
