# One golden-image test (run by CTest through `cmake -P`; golden_tests.cmake passes the variables):
# renders SCENE with the GPU path at the golden size into OUT_DIR, compares it with GOLDEN using
# `vkray compare` and the thresholds given, and on failure names the new image and the difference
# image it leaves beside the test output. It never touches GOLDEN: regenerating is deliberate
# (scripts/update-golden.sh).
#   VKRAY SCENE GOLDEN OUT_DIR NAME SIZE DEVICE MAX_RMSE MAX_BAD_FRACTION THRESHOLD
set(new "${OUT_DIR}/${NAME}.png")
set(diff "${OUT_DIR}/${NAME}-diff.png")
file(MAKE_DIRECTORY "${OUT_DIR}")
file(REMOVE "${new}" "${diff}")  # nothing stale from an earlier run may be mistaken for this one's

if(NOT EXISTS "${GOLDEN}")
  message(FATAL_ERROR "no golden image ${GOLDEN} for ${SCENE}: make it deliberately with "
                      "scripts/update-golden.sh, look at it, and commit it")
endif()

execute_process(
  COMMAND "${VKRAY}" render "${SCENE}" --size ${SIZE} --device ${DEVICE} -o "${new}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "rendering ${SCENE} failed (exit ${rc}):\n${out}${err}")
endif()

execute_process(
  COMMAND "${VKRAY}" compare "${GOLDEN}" "${new}" --threshold ${THRESHOLD} --max-rmse ${MAX_RMSE}
          --max-bad-fraction ${MAX_BAD_FRACTION} --diff "${diff}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR
    "${NAME}: the fresh render differs from its golden image beyond the thresholds.\n"
    "  golden:     ${GOLDEN}\n"
    "  new image:  ${new}\n"
    "  difference: ${diff}\n"
    "Look at them. If the change is intended, regenerate the goldens deliberately with "
    "scripts/update-golden.sh and commit them with the change that explains it.")
endif()
