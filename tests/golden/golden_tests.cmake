# Golden images: every hand-made scene of scenes/ (those that need no fetched mesh) rendered by the
# GPU path on lavapipe at 160x120 and compared with tests/golden/NAME.png. Included from
# tests/CMakeLists.txt. A failure leaves NAME.png and NAME-diff.png in test-output/golden/ and
# prints their paths; goldens are only ever rewritten by scripts/update-golden.sh.
set(GOLDEN_DIR ${CMAKE_CURRENT_SOURCE_DIR}/golden)
set(GOLDEN_OUT ${CMAKE_BINARY_DIR}/test-output/golden)
set(GOLDEN_SIZE 160x120)
# lavapipe by name, so a machine with a GPU renders what the goldens were made with.
set(GOLDEN_DEVICE llvmpipe)

# Thresholds. Measured at 160x120 on lavapipe (Mesa 22.3.6), see docs/scenes.md:
#  - the same GPU render twice: identical (RMSE 0, no pixel over any threshold);
#  - GPU against the independent double-precision CPU renderer: RMSE at most 0.0095 (default and
#    cornell: the edges where walls meet and the light panel's rim, exact ties that either
#    renderer may resolve to the other triangle), at most 0.41 % of the pixels off by more than
#    2/255, max error 0.44 on those few edge pixels.
# A golden comparison is GPU against GPU, so any difference is a change; the limits let through a
# change as small as the gap between two correct renderers (a tie resolved the other way, one
# float ulp of shading) and fail anything larger: a lost shadow, a wrong Fresnel term or a moved
# camera changes thousands of pixels by far more than 2/255.
set(GOLDEN_THRESHOLD 2/255)
set(GOLDEN_MAX_RMSE 0.012)
set(GOLDEN_MAX_BAD_FRACTION 0.005)

file(GLOB golden_scenes CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.scene)
foreach(scene ${golden_scenes})
  # Scenes of fetched meshes (a `geo meshes/...` line) are too large for brute force on lavapipe
  # and may be absent; they are load-checked by tests/scene/mesh_scenes_test.cpp instead.
  file(STRINGS ${scene} fetched REGEX "^(geo|obj)[ \t]+meshes/")
  if(fetched)
    continue()
  endif()
  get_filename_component(name ${scene} NAME_WE)
  add_test(NAME golden.${name}
           COMMAND ${CMAKE_COMMAND}
                   -DVKRAY=$<TARGET_FILE:vkray> -DSCENE=${scene} -DGOLDEN=${GOLDEN_DIR}/${name}.png
                   -DOUT_DIR=${GOLDEN_OUT} -DNAME=${name} -DSIZE=${GOLDEN_SIZE} -DDEVICE=${GOLDEN_DEVICE}
                   -DTHRESHOLD=${GOLDEN_THRESHOLD} -DMAX_RMSE=${GOLDEN_MAX_RMSE}
                   -DMAX_BAD_FRACTION=${GOLDEN_MAX_BAD_FRACTION}
                   -P ${GOLDEN_DIR}/run_golden.cmake)
  set_tests_properties(golden.${name} PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")
endforeach()
