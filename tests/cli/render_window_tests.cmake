# `vkray render`'s windows (--crop, --pixel-bounds, --pixel, --tile), `vkray assemble` of its tiles,
# the full camera line of --camera and several scenes in one call. Included from cli_tests.cmake.
add_test(NAME cli.render_windows
         COMMAND ${CLI_DIR}/render_windows.sh $<TARGET_FILE:vkray> ${CMAKE_SOURCE_DIR}/scenes ${CLI_OUT})
set_tests_properties(cli.render_windows PROPERTIES TIMEOUT 600 ENVIRONMENT "VKRAY_VALIDATION=1")

set(one ${CLI_DATA}/one_triangle.scene)
vkray_expect_error(crop_outside "--crop 0,1.5,0,1: the fractions must lie in \\[0, 1\\]" render ${one} --crop 0,1.5,0,1 -o ${CLI_OUT}/x.png)
vkray_expect_error(crop_three "--crop 0.25,0.75,0.25: expected X0,X1,Y0,Y1" render ${one} --crop 0.25 0.75 0.25 -o ${CLI_OUT}/x.png)
vkray_expect_usage_error(crop_five "--crop: At Most 4 required but received 5" render ${one} --crop 0.1,0.2,0.3,0.4,0.5 -o ${CLI_OUT}/x.png)
vkray_expect_error(crop_empty "--crop 0.5,0.5,0,1: pixels .* are not a non-empty part of the" render ${one} --crop 0.5,0.5,0,1 -o ${CLI_OUT}/x.png)
vkray_expect_error(pixel_bounds_outside "--pixel-bounds 0,9999,0,1: pixels \\[0, 9999\\) x \\[0, 1\\) are not a non-empty part of the"
                   render ${one} --pixel-bounds 0,9999,0,1 -o ${CLI_OUT}/x.png)
vkray_expect_error(pixel_outside "--pixel 5,-1: pixels" render ${one} --size 8x8 --cpu --pixel 5,-1)
vkray_expect_error(tile_index "--tile 4/4: I must be 0..3" render ${one} --tile 4/4 -o ${CLI_OUT}/x.exr)
vkray_expect_error(tile_too_many "--tile 0/9: more tiles than the 8 rows of the image" render ${one} --size 8x8 --tile 0/9 -o ${CLI_OUT}/x.exr)
vkray_expect_error(several_scenes_one_output "-o with 2 scenes: it names one image; give --out-dir DIR"
                   render ${one} ${one} -o ${CLI_OUT}/x.png)
vkray_expect_error(several_scenes_same_output "one_triangle\\.scene: its image .*one_triangle\\.png is also .*one_triangle\\.scene's"
                   render ${one} ${one} --cpu --size 8x8 --out-dir ${CLI_OUT})
vkray_expect_error(out_dir_missing "--out-dir .*no-such-dir: no such folder" render ${one} --out-dir ${CLI_OUT}/no-such-dir)
vkray_expect_usage_error(crop_and_tile "--crop excludes --tile|--tile excludes --crop" render ${one} --crop 0,1,0,1 --tile 0/2)
vkray_expect_usage_error(encoding_unknown "--encoding: gamma not in \\{auto,srgb,linear\\}|--encoding" render ${one} --encoding gamma)
# --camera takes the scene file's whole camera line.
add_test(NAME cli.render_camera_line
         COMMAND ${CLI_DIR}/expect_output.sh "output: +.*camera-line\\.png" $<TARGET_FILE:vkray> render ${one} --cpu --size 16x16
                 --camera 0,0,3,0,0,0,0,1,0,45 -o ${CLI_OUT}/camera-line.png)
vkray_expect_usage_error(build_only_needs_save "--build-only requires --save-accel" render ${one} --build-only)
vkray_expect_usage_error(build_only_no_image "-o excludes --build-only|--build-only excludes -o|--output excludes --build-only|--build-only excludes --output"
                         render ${one} --build-only --save-accel ${CLI_OUT}/b.vkacc -o ${CLI_OUT}/x.png)
