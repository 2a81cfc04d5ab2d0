# Runs `vkray bench` at a tiny size and checks the exit code, the summary and the files written.
# -DVKRAY=... -DSCENE=... -DOUT=...
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${VKRAY} bench ${SCENE} --size 32x24 --repeat 1 --threads 1 --deltas 8
                        --maxdepths none --accel bvh,kd-backtrack --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 240)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "vkray bench failed (${rc}):\n${out}\n${err}")
endif()
foreach(f bench.json bench.md report.html)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "vkray bench wrote no ${f}:\n${out}")
  endif()
endforeach()
file(GLOB pngs ${OUT}/images/*.png)
list(LENGTH pngs n)
if(n LESS 7)  # reference + 2 accelerators x (image, difference, heatmap)
  message(FATAL_ERROR "vkray bench wrote ${n} images, expected at least 7")
endif()
foreach(accel bvh kd-backtrack)
  if(NOT out MATCHES "\n  ${accel} +build")
    message(FATAL_ERROR "summary has no line for ${accel}:\n${out}")
  endif()
endforeach()
# A log (not a terminal) gets one progress line per step.
if(NOT err MATCHES "bench: scene 1/1 objects \\| trace kd-backtrack")
  message(FATAL_ERROR "no progress lines on stderr:\n${err}")
endif()
message(STATUS "${out}")
