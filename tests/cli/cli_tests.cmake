# End-to-end runs of the vkray binary as a user runs it. Included from tests/CMakeLists.txt.
set(CLI_DIR ${CMAKE_CURRENT_SOURCE_DIR}/cli)
set(CLI_DATA ${CLI_DIR}/data)
set(CLI_OUT ${CMAKE_BINARY_DIR}/test-output/cli)
file(MAKE_DIRECTORY ${CLI_OUT})

# Bad input: one "error: " line naming the cause (and file:line), a non-zero exit, never a crash.
function(vkray_expect_error name pattern)
  add_test(NAME cli.error.${name}
           COMMAND ${CLI_DIR}/expect_error.sh "${pattern}" $<TARGET_FILE:vkray> ${ARGN})
  set_tests_properties(cli.error.${name} PROPERTIES TIMEOUT 180 ENVIRONMENT "VKRAY_VALIDATION=1")
endfunction()

vkray_expect_error(missing_file "does_not_exist\\.scene" render ${CLI_DATA}/does_not_exist.scene)
vkray_expect_error(unknown_command "unknown_command\\.scene:3.*frobnicate" render ${CLI_DATA}/unknown_command.scene)
vkray_expect_error(too_few_args "too_few_args\\.scene:3" render ${CLI_DATA}/too_few_args.scene)
vkray_expect_error(too_many_args "too_many_args\\.scene:3" render ${CLI_DATA}/too_many_args.scene)
vkray_expect_error(non_numeric "non_numeric\\.scene:3.*abc" render ${CLI_DATA}/non_numeric.scene)
vkray_expect_error(nan_coordinate "nan_coordinate\\.scene:3" render ${CLI_DATA}/nan_coordinate.scene)
vkray_expect_error(inf_coordinate "inf_coordinate\\.scene:3" render ${CLI_DATA}/inf_coordinate.scene)
vkray_expect_error(index_out_of_range "index_out_of_range\\.scene:6.*5" render ${CLI_DATA}/index_out_of_range.scene)
vkray_expect_error(zero_size "zero_size\\.scene:2" render ${CLI_DATA}/zero_size.scene)
vkray_expect_error(absurd_size "absurd_size\\.scene:2" render ${CLI_DATA}/absurd_size.scene)
vkray_expect_error(negative_maxdepth "negative_maxdepth\\.scene:3" render ${CLI_DATA}/negative_maxdepth.scene)
vkray_expect_error(no_triangles "no_triangles\\.scene.*no triangles" render ${CLI_DATA}/no_triangles.scene)
vkray_expect_error(no_camera "no_camera\\.scene.*camera" render ${CLI_DATA}/no_camera.scene)
vkray_expect_error(size_flag_zero "--size 0x0" render ${CLI_DATA}/one_triangle.scene --size 0x0 -o ${CLI_OUT}/x.png)
vkray_expect_error(size_flag_absurd "--size 100000x100000" render ${CLI_DATA}/one_triangle.scene --size 100000x100000 -o ${CLI_OUT}/x.png)
vkray_expect_error(size_flag_garbage "--size big" render ${CLI_DATA}/one_triangle.scene --size big -o ${CLI_OUT}/x.png)
vkray_expect_error(view_flag_garbage "--view 'near': expected scene, close" render ${CLI_DATA}/one_triangle.scene --view near -o ${CLI_OUT}/x.png)
vkray_expect_error(view_flag_degenerate "--view '1,2,3,1,2,3': camera eye and look-at centre coincide" render ${CLI_DATA}/one_triangle.scene --view 1,2,3,1,2,3 -o ${CLI_OUT}/x.png)
# VKRAY_KERNEL_DIR (kernels from files, for A/B timing) naming a folder without the kernel.
add_test(NAME cli.error.kernel_dir_missing
         COMMAND ${CMAKE_COMMAND} -E env VKRAY_KERNEL_DIR=${CLI_OUT}/no-such-kernels
                 ${CLI_DIR}/expect_error.sh "VKRAY_KERNEL_DIR: cannot open .*render_bvh\\.spv"
                 $<TARGET_FILE:vkray> render ${CLI_DATA}/one_triangle.scene --accel bvh -o ${CLI_OUT}/x.png)
set_tests_properties(cli.error.kernel_dir_missing PROPERTIES TIMEOUT 180)
# A wrong command line: one "error: " line like every other error, exit 2 (docs/outputs.md).
function(vkray_expect_usage_error name pattern)
  add_test(NAME cli.usage.${name}
           COMMAND ${CMAKE_COMMAND} -E env EXPECT_RC=2 ${CLI_DIR}/expect_error.sh "${pattern}" $<TARGET_FILE:vkray> ${ARGN})
  set_tests_properties(cli.usage.${name} PROPERTIES TIMEOUT 60)
endfunction()
vkray_expect_usage_error(unexpected_in_order "unexpected arguments: --frobnicate --zap \\(see 'vkray render --help'\\)" render ${CLI_DATA}/one_triangle.scene --frobnicate --zap)
vkray_expect_usage_error(flag_typo "unexpected argument: --thread; did you mean --threads\\?" render ${CLI_DATA}/one_triangle.scene --thread 2)
vkray_expect_usage_error(command_typo "unknown command 'rendr' \\(did you mean 'render'\\?\\)" rendr ${CLI_DATA}/one_triangle.scene)
vkray_expect_usage_error(missing_value "--size: 1 required WxH missing" render ${CLI_DATA}/one_triangle.scene --size)
vkray_expect_usage_error(cpu_device "--cpu excludes --device" render ${CLI_DATA}/one_triangle.scene --cpu --device 7)
vkray_expect_usage_error(cpu_counters "--counters excludes --cpu|--cpu excludes --counters" render ${CLI_DATA}/one_triangle.scene --counters --cpu)
vkray_expect_usage_error(quiet_stats "--stats excludes --quiet" render ${CLI_DATA}/one_triangle.scene --quiet --stats)
# --quiet: the image is written and nothing is printed.
add_test(NAME cli.render_quiet
         COMMAND bash -c "out=$(\"$0\" render \"$1\" --cpu --size 8x8 --quiet -o \"$2\") && test -z \"$out\" && test -s \"$2\""
                 $<TARGET_FILE:vkray> ${CLI_DATA}/one_triangle.scene ${CLI_OUT}/quiet.png)
vkray_expect_error(spp_flag "--spp 0: must be 1\\.\\.4096" render ${CLI_DATA}/one_triangle.scene --spp 0 -o ${CLI_OUT}/x.png)
vkray_expect_error(background_flag "--background 1,-1,0: expected R,G,B" render ${CLI_DATA}/one_triangle.scene --background 1,-1,0 -o ${CLI_OUT}/x.png)
vkray_expect_error(maxdepth_flag "--maxdepth 0" render ${CLI_DATA}/one_triangle.scene --maxdepth 0 -o ${CLI_OUT}/x.png)
vkray_expect_error(unknown_accel "--accel warp" render ${CLI_DATA}/one_triangle.scene --accel warp -o ${CLI_OUT}/x.png)
vkray_expect_error(unknown_aov "unknown AOV 'albedo'" render ${CLI_DATA}/one_triangle.scene --aov albedo=a.pfm -o ${CLI_OUT}/x.png)
vkray_expect_error(unknown_device "--device 999" render ${CLI_DATA}/one_triangle.scene --device 999 -o ${CLI_OUT}/x.png)
vkray_expect_error(unwritable_output "${CLI_OUT}/no/such/dir/x\\.png" render ${CLI_DATA}/one_triangle.scene -o ${CLI_OUT}/no/such/dir/x.png)
# An output that cannot be written (a full disk, a link to /dev/full) keeps the previous file.
add_test(NAME cli.output_keeps_previous
         COMMAND ${CLI_DIR}/keeps_previous_output.sh $<TARGET_FILE:vkray> ${CLI_DATA}/one_triangle.scene
                 ${CLI_OUT}/keeps-previous)
set_tests_properties(cli.output_keeps_previous PROPERTIES TIMEOUT 300)
vkray_expect_error(unsupported_output "x\\.jpg.*supported: \\.png" render ${CLI_DATA}/one_triangle.scene -o ${CLI_OUT}/x.jpg)
vkray_expect_error(aov_not_pfm "d\\.png: AOV files are PFM or EXR: the name must end in \\.pfm or \\.exr" render ${CLI_DATA}/one_triangle.scene --aov depth=${CLI_OUT}/d.png -o ${CLI_OUT}/x.png)
vkray_expect_error(compare_missing "missing\\.png" compare ${CLI_OUT}/missing.png ${CLI_OUT}/missing2.png)

# Success paths: devices, a GPU render with AOVs, the CPU reference, and compare between them.
add_test(NAME cli.devices COMMAND ${CLI_DIR}/expect_output.sh "maxStorageBufferRange" $<TARGET_FILE:vkray> devices)
add_test(NAME cli.render_gpu
         COMMAND ${CLI_DIR}/expect_output.sh "left out:"
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96
                 --accel brute -o ${CLI_OUT}/default-gpu.png --aov depth=${CLI_OUT}/depth.pfm
                 --aov primid=${CLI_OUT}/primid.pfm --aov normal=${CLI_OUT}/normal.pfm --stats)
set_tests_properties(cli.render_gpu PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1"
  FIXTURES_SETUP default_renders)
add_test(NAME cli.render_cpu
         COMMAND $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96 --cpu
                 --accel brute -o ${CLI_OUT}/default-cpu.png --aov primid=${CLI_OUT}/primid-cpu.pfm)
set_tests_properties(cli.render_cpu PROPERTIES TIMEOUT 300 FIXTURES_SETUP default_renders)
# The summary's render-time line accounts for the whole command: a GPU render names the wait for
# its device, the CPU reference has none; both name the image's write.
add_test(NAME cli.render_time_gpu
         COMMAND ${CLI_DIR}/expect_output.sh
                 "^render time: [0-9.]+ ms \\(load [0-9.]+ ms, build [0-9.]+ ms, device start [0-9.]+ ms, write [0-9.]+ ms; total [0-9.]+ ms\\)$"
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 32x32 -o ${CLI_OUT}/time-gpu.png)
add_test(NAME cli.render_time_cpu
         COMMAND ${CLI_DIR}/expect_output.sh
                 "^render time: [0-9.]+ ms \\(load [0-9.]+ ms, build [0-9.]+ ms, write [0-9.]+ ms; total [0-9.]+ ms\\)$"
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 32x32 --cpu -o ${CLI_OUT}/time-cpu.png)
add_test(NAME cli.render_time_json
         COMMAND ${CLI_DIR}/expect_output.sh "\"device_ms\": [0-9]"
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 32x32 --json -o ${CLI_OUT}/time-json.png)
set_tests_properties(cli.render_time_gpu cli.render_time_cpu cli.render_time_json PROPERTIES TIMEOUT 300)
add_test(NAME cli.compare_gpu_cpu
         COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/default-gpu.png ${CLI_OUT}/default-cpu.png
                 --max-rmse 0.02 --max-bad-fraction 0.005 --threshold 0.0314 --diff ${CLI_OUT}/default-diff.png)
set_tests_properties(cli.compare_gpu_cpu PROPERTIES FIXTURES_REQUIRED default_renders)
add_test(NAME cli.compare_primid_gpu_cpu
         COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/primid.pfm ${CLI_OUT}/primid-cpu.pfm
                 --threshold 0 --max-bad-fraction 0.002)
# The bad fraction allows the pixel centres on the edges where the box walls meet (exact ties);
# tests/gpu/gpu_vs_cpu_test.cpp tells ties from disagreements and asks 99.9%.
set_tests_properties(cli.compare_primid_gpu_cpu PROPERTIES FIXTURES_REQUIRED default_renders)

# OFF meshes and procedural scenes: the OFF reader's errors name the OFF file, its line and
# column, and the scene line that loaded it; `vkray gen` refuses bad requests before writing.
vkray_expect_error(off_bad_index "off_bad_index\\.off:8:7: vertex index 4 out of range.*off_bad_index\\.scene:3" render ${CLI_DATA}/off_bad_index.scene)
vkray_expect_error(off_truncated "off_truncated\\.off:5: file ends early: 3 of the 4 vertices" render ${CLI_DATA}/off_truncated.scene)
vkray_expect_error(off_lying_counts "off_lying_counts\\.off:2:1: counts of 900000000 vertices.*cannot fit" render ${CLI_DATA}/off_lying_counts.scene)
vkray_expect_error(off_nan "off_nan\\.off:4:3: .*'nan', not a finite number" render ${CLI_DATA}/off_nan.scene)
vkray_expect_error(off_variant "off_variant\\.off:1:1: unsupported OFF variant 'NOFF'" render ${CLI_DATA}/off_variant.scene)
vkray_expect_error(off_missing "off_missing\\.scene:3: cannot open OFF file .*off_missing\\.off" render ${CLI_DATA}/off_missing.scene)
vkray_expect_error(generate_unknown "generate_unknown\\.scene:3:10: unknown generator 'teapot'" render ${CLI_DATA}/generate_unknown.scene)
vkray_expect_error(gen_unknown_kind "gen: unknown kind 'teapot'" gen teapot --triangles 10 -o ${CLI_OUT}/g.scene)
vkray_expect_error(gen_zero_triangles "gen: --triangles 0 is outside" gen soup --triangles 0 -o ${CLI_OUT}/g.scene)
vkray_expect_error(gen_not_scene "gen: -o .*g\\.txt: the output must be a \\.scene file" gen soup --triangles 10 -o ${CLI_OUT}/g.txt)
vkray_expect_error(gen_unwritable "no/such/dir/g\\.scene: cannot open for writing: No such file or directory" gen soup --triangles 10 -o ${CLI_OUT}/no/such/dir/g.scene)
vkray_expect_error(gen_exists "gen: -o .*one_triangle\\.scene: the file exists \\(--force replaces it\\)" gen soup --triangles 10 -o ${CLI_DATA}/one_triangle.scene)
vkray_expect_error(output_stdout "-o -: the image goes to a file, not to standard output" render ${CLI_DATA}/one_triangle.scene --cpu -o -)
vkray_expect_error(output_directory "-o .*: names a directory" render ${CLI_DATA}/one_triangle.scene --cpu -o ${CLI_OUT})
# -o must name its format: without an extension it is refused, naming the extensions (a typo is
# likelier than a wish for PNG); a scene's own `output` keeps CSE167's rule, PNG.
vkray_expect_error(output_no_extension "-o .*noext: no file extension to choose the format by \\(give \\.png, \\.bmp, \\.pfm, \\.exr\\)"
                   render ${CLI_DATA}/one_triangle.scene --cpu --size 8x8 -o ${CLI_OUT}/noext)
vkray_expect_error(convert_no_extension "OUT .*noext: no file extension" convert ${CMAKE_SOURCE_DIR}/docs/images/default.png ${CLI_OUT}/noext)
add_test(NAME cli.scene_output_png_default COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/output_noext_image\\.png"
                                          $<TARGET_FILE:vkray> render ${CLI_DATA}/output_noext.scene --cpu --size 8x8 --out-dir ${CLI_OUT})

# A mesh file renders by itself (scene/mesh_scene.h): on the GPU and the CPU reference, the same
# image up to the tolerance of cli.compare_gpu_cpu, written as MESH.png by default.
add_test(NAME cli.render_mesh COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/cube\\.png"
                                   $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/tests/scene/data/cube.off --size 96x72 --out-dir ${CLI_OUT})
add_test(NAME cli.render_mesh_cpu
         COMMAND $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/tests/scene/data/cube.off --size 96x72 --cpu -o ${CLI_OUT}/cube-cpu.png)
set_tests_properties(cli.render_mesh cli.render_mesh_cpu PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1" FIXTURES_SETUP mesh_renders)
add_test(NAME cli.compare_mesh_gpu_cpu
         COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/cube.png ${CLI_OUT}/cube-cpu.png
                 --max-rmse 0.02 --max-bad-fraction 0.005 --threshold 0.0314)
set_tests_properties(cli.compare_mesh_gpu_cpu PROPERTIES FIXTURES_REQUIRED mesh_renders)
add_test(NAME cli.render_mesh_obj COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/materials-mesh\\.png"
                                       $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/tests/scene/data/materials.obj --size 32x24 --cpu -o ${CLI_OUT}/materials-mesh.png)
vkray_expect_error(mesh_missing "no-such\\.obj: cannot open OBJ file '.*no-such\\.obj': no such file or directory" render ${CLI_DATA}/no-such.obj)
# PLY and glTF meshes by themselves, and a bad one of each.
add_test(NAME cli.render_mesh_ply COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/quad\\.png"
                                       $<TARGET_FILE:vkray> render ${CLI_DATA}/quad.ply --size 32x24 --cpu --out-dir ${CLI_OUT})
add_test(NAME cli.render_mesh_gltf COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/triangle\\.png"
                                        $<TARGET_FILE:vkray> render ${CLI_DATA}/triangle.gltf --size 32x24 --cpu --out-dir ${CLI_OUT})
vkray_expect_error(ply_bad_index "ply_bad_index\\.ply:13:7: element 'face' 0 of 1, property 'vertex_indices': vertex index 9 out of range"
                   render ${CLI_DATA}/ply_bad_index.ply)
vkray_expect_error(gltf_missing_bin "gltf_missing_bin\\.gltf: cannot open buffer file '.*gltf_missing\\.bin': no such file or directory"
                   render ${CLI_DATA}/gltf_missing_bin.gltf)
# A mesh of the repository's scenes, not fetched: the error names the scene line and the script.
vkray_expect_error(mesh_not_fetched "missing_mesh\\.scene:3: cannot open OBJ file '.*scenes/meshes/no-such-mesh\\.obj': no such file or directory \\(.*scripts/fetch-scenes\\.sh"
                   render ${CLI_DATA}/missing_mesh.scene)
# --view fit: a camera that sees the whole scene (tests/scene checks every corner of its bounds).
add_test(NAME cli.render_view_fit COMMAND ${CLI_DIR}/expect_output.sh "output: +.*/view-fit\\.png"
                                       $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/cornell.scene --view fit --cpu --size 32x24 -o ${CLI_OUT}/view-fit.png)
# --build-only says what it built and wrote, and no image size.
add_test(NAME cli.build_only_summary
         COMMAND bash -c "out=$(\"$0\" render \"$1\" --save-accel \"$2\" --build-only) || exit 1; echo \"$out\"; grep -Eq '^built: +bvh structure of .*one_triangle\\.scene \\(1 triangle\\) in ' <<<\"$out\" && grep -Eq '^accel file: +saved to .*build-only\\.vkacc' <<<\"$out\" && ! grep -Eq 'resolution|32x24' <<<\"$out\""
                 $<TARGET_FILE:vkray> ${CLI_DATA}/one_triangle.scene ${CLI_OUT}/build-only.vkacc)
# `vkray render --help` fits a screen: at most 50 lines of at most 100 columns; bench's lines too.
add_test(NAME cli.help_fits
         COMMAND bash -c "\"$0\" render --help >/tmp/vkray-help-$$ && lines=$(wc -l </tmp/vkray-help-$$) && wide=$( (cat /tmp/vkray-help-$$; \"$0\" bench --help; \"$0\" render --accel help) | awk 'length($0) > 100' | wc -l); rm -f /tmp/vkray-help-$$; echo \"$lines lines, $wide over 100 columns\"; test $lines -le 50 -a $wide -eq 0"
                 $<TARGET_FILE:vkray>)

# `vkray gen` writes a scene that renders (CPU reference, tiny: brute force over 1000 triangles).
add_test(NAME cli.gen_terrain COMMAND ${CLI_DIR}/expect_output.sh "terrain, 1012 triangles \\+ 2 floor, seed 3"
                                     $<TARGET_FILE:vkray> gen terrain --triangles 1000 --seed 3 --force -o ${CLI_OUT}/gen-terrain.scene)
set_tests_properties(cli.gen_terrain PROPERTIES FIXTURES_SETUP gen_scene)
add_test(NAME cli.gen_render COMMAND ${CLI_DIR}/expect_output.sh "scene: +1014 triangles" $<TARGET_FILE:vkray> render ${CLI_OUT}/gen-terrain.scene --cpu --size 32x24
                                    -o ${CLI_OUT}/gen-terrain.png --stats)
set_tests_properties(cli.gen_render PROPERTIES FIXTURES_REQUIRED gen_scene TIMEOUT 300)

# Every accelerator end to end on the GPU (default.scene, 96x96; `bvh` is the default), each image
# compared with the CPU reference like cli.compare_gpu_cpu (primary hits are compared, ties told
# apart, by tests/gpu/*), and the CPU renderer with a BVH (what makes --cpu usable on big meshes).
add_test(NAME cli.render_accel.bvh
         COMMAND ${CLI_DIR}/expect_output.sh "accel bvh" $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96
                 -o ${CLI_OUT}/default-bvh.png --stats)
set_tests_properties(cli.render_accel.bvh PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1"
  FIXTURES_SETUP accel_bvh)
foreach(accel bvh bvh-fast bvh-hq bvh-sah bvh-stackless bvh-packet bvh-sphere kd-stack kd-shortstack kd-packet kd-restart kd-pushdown kd-ropes kd-backtrack)
  if(NOT accel STREQUAL "bvh")
    add_test(NAME cli.render_accel.${accel}
             COMMAND ${CLI_DIR}/expect_output.sh "accel ${accel}"
                     $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96
                     --accel ${accel} -o ${CLI_OUT}/default-${accel}.png --stats)
    set_tests_properties(cli.render_accel.${accel} PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1"
      FIXTURES_SETUP accel_${accel})
  endif()
  # Bounds of tests/gpu/gpu_vs_cpu_test.cpp (the pixels over 8/255 lie on the edges where two
  # walls meet, where float and double may pick either triangle of a tie).
  add_test(NAME cli.compare_accel.${accel}
           COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/default-${accel}.png ${CLI_OUT}/default-cpu.png
                   --max-rmse 0.025 --max-bad-fraction 0.01 --threshold 0.0314)
  set_tests_properties(cli.compare_accel.${accel} PROPERTIES FIXTURES_REQUIRED "accel_${accel};default_renders")
endforeach()
# Beyond one storage buffer: the 4M-triangle soup's triangles are 184 MiB, more than lavapipe's 128 MiB
# maxStorageBufferRange; read through texel views they render, and name the same primary
# triangles as the CPU reference.
add_test(NAME cli.render_beyond_storage_range
         COMMAND $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/scaling/soup-4m.scene --size 16x12
                 -o ${CLI_OUT}/soup-4m.png --aov primid=${CLI_OUT}/soup-4m-primid.pfm)
set_tests_properties(cli.render_beyond_storage_range PROPERTIES TIMEOUT 600 ENVIRONMENT "VKRAY_VALIDATION=1"
  FIXTURES_SETUP soup_4m)
add_test(NAME cli.render_beyond_storage_range_cpu
         COMMAND $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/scaling/soup-4m.scene --size 16x12 --cpu
                 --accel bvh -o ${CLI_OUT}/soup-4m-cpu.png --aov primid=${CLI_OUT}/soup-4m-primid-cpu.pfm)
set_tests_properties(cli.render_beyond_storage_range_cpu PROPERTIES TIMEOUT 600 FIXTURES_SETUP soup_4m)
add_test(NAME cli.compare_beyond_storage_range
         COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/soup-4m-primid.pfm ${CLI_OUT}/soup-4m-primid-cpu.pfm
                 --threshold 0 --max-bad-fraction 0.01)
set_tests_properties(cli.compare_beyond_storage_range PROPERTIES FIXTURES_REQUIRED soup_4m)
add_test(NAME cli.render_cpu_bvh
         COMMAND $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96 --cpu
                 --accel bvh -o ${CLI_OUT}/default-cpu-bvh.png)
set_tests_properties(cli.render_cpu_bvh PROPERTIES TIMEOUT 300 FIXTURES_SETUP cpu_bvh)
# The CPU BVH traversal answers exactly like brute force, so the two CPU images are identical.
add_test(NAME cli.compare_cpu_bvh_brute
         COMMAND $<TARGET_FILE:vkray> compare ${CLI_OUT}/default-cpu-bvh.png ${CLI_OUT}/default-cpu.png
                 --max-rmse 0 --threshold 0 --max-bad-fraction 0)
set_tests_properties(cli.compare_cpu_bvh_brute PROPERTIES FIXTURES_REQUIRED "cpu_bvh;default_renders")
# Tuning follows the accelerator's name (`--accel help` lists the options); each error names the
# whole --accel text and the option.
vkray_expect_error(aac_epsilon "--accel bvh:aac-epsilon=0.7: aac-epsilon must be in" render ${CLI_DATA}/one_triangle.scene --accel bvh:aac-epsilon=0.7 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_empty_bonus "kd-empty-bonus must be in \\[0, 1\\]" render ${CLI_DATA}/one_triangle.scene --accel kd-stack:kd-empty-bonus=-0.5 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_empty_min "kd-empty-min must be in \\[0, 1\\]" render ${CLI_DATA}/one_triangle.scene --accel kd-restart:kd-empty-min=2 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_cost_nan "'kd-intersection-cost=nan': the value is not a number" render ${CLI_DATA}/one_triangle.scene --accel kd-stack:kd-intersection-cost=nan -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_max_duplication "kd-max-duplication must be a number of references per triangle, 1 or more" render ${CLI_DATA}/one_triangle.scene --accel kd-stack:kd-max-duplication=0.5 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_max_duplication_bvh "--accel bvh:kd-max-duplication=4: kd-max-duplication applies to kd-restart, kd-pushdown, kd-ropes, kd-backtrack, kd-stack, kd-shortstack, kd-packet only" render ${CLI_DATA}/one_triangle.scene --accel bvh:kd-max-duplication=4 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_short_stack_range "kd-short-stack must be 1..56 \\(got 0\\)" render ${CLI_DATA}/one_triangle.scene --accel kd-shortstack:kd-short-stack=0 -o ${CLI_OUT}/x.png)
vkray_expect_error(kd_short_stack_kd_stack "--accel kd-stack:kd-short-stack=2: kd-short-stack applies to kd-shortstack only" render ${CLI_DATA}/one_triangle.scene --accel kd-stack:kd-short-stack=2 -o ${CLI_OUT}/x.png)
vkray_expect_error(aac_delta_absurd "aac-delta must be 1..1024" render ${CLI_DATA}/one_triangle.scene --accel bvh:aac-delta=1000000 -o ${CLI_OUT}/x.png)
vkray_expect_error(treelet_passes "bvh-treelet-passes must be 0..16" render ${CLI_DATA}/one_triangle.scene --accel bvh:bvh-treelet-passes=17 -o ${CLI_OUT}/x.png)
vkray_expect_error(reinsert_batch "bvh-reinsert-batch must be in \\[0.001, 1\\]" render ${CLI_DATA}/one_triangle.scene --accel bvh:bvh-reinsert-batch=2 -o ${CLI_OUT}/x.png)
vkray_expect_error(treelet_min_kd "bvh-treelet-min applies to bvh, bvh-fast, bvh-hq, bvh-sah, bvh-stackless, bvh-packet only" render ${CLI_DATA}/one_triangle.scene --accel kd-stack:bvh-treelet-min=4 -o ${CLI_OUT}/x.png)
# A mistyped accelerator or option gets the nearest name; `--accel help` lists them all, no scene needed.
vkray_expect_error(accel_typo "--accel kd-rope: unknown accelerator 'kd-rope' \\(did you mean 'kd-ropes'\\?\\)" render ${CLI_DATA}/one_triangle.scene --accel kd-rope -o ${CLI_OUT}/x.png)
vkray_expect_error(accel_option_typo "unknown tuning option 'aac-delt' \\(did you mean 'aac-delta'\\?\\)" render ${CLI_DATA}/one_triangle.scene --accel bvh:aac-delt=8 -o ${CLI_OUT}/x.png)
vkray_expect_error(bench_accel_typo "--accel kd-stak: unknown accelerator 'kd-stak' \\(did you mean 'kd-stack'\\?\\)" bench ${CLI_DATA}/one_triangle.scene --accel bvh,kd-stak --out ${CLI_OUT}/bench-typo)
add_test(NAME cli.accel_help COMMAND ${CLI_DIR}/expect_output.sh "^  kd-short-stack +1\\.\\.56 " $<TARGET_FILE:vkray> render --accel help)
add_test(NAME cli.bench_accel_help COMMAND ${CLI_DIR}/expect_output.sh "^  aac-delta +1\\.\\.1024 " $<TARGET_FILE:vkray> bench --accel help)
# The tuning options are not flags of their own.
vkray_expect_usage_error(tuning_flag_gone "unexpected argument.*--aac-delta" render ${CLI_DATA}/one_triangle.scene --aac-delta 8)

# Hardened input: every case is one "error: " line naming the cause (and file:line where
# there is one) and a non-zero exit, never a crash, a hang or a silently wrong image. Inputs too
# large or too binary to commit (UTF-16, 10 MB lines, garbage) are written at test time.
set(BAD_IN ${CLI_OUT}/bad-inputs)
add_test(NAME cli.make_bad_inputs COMMAND ${CLI_DIR}/make_bad_inputs.sh ${BAD_IN} $<TARGET_FILE:vkray>)
set_tests_properties(cli.make_bad_inputs PROPERTIES FIXTURES_SETUP bad_inputs)
function(vkray_expect_error_generated name pattern)
  vkray_expect_error(${name} "${pattern}" ${ARGN})
  set_tests_properties(cli.error.${name} PROPERTIES FIXTURES_REQUIRED bad_inputs)
endfunction()

vkray_expect_error(truncated_line "truncated\\.scene:3:1: expected 3 numbers after 'vertex' \\(x y z\\), got 2" render ${CLI_DATA}/truncated.scene)
vkray_expect_error(binary_scene "vkray:1:1: binary data \\(control byte 0x7F\\)" render $<TARGET_FILE:vkray>)
vkray_expect_error(device_file "/dev/zero: cannot open scene file: is a character device, not a regular file" render /dev/zero)
vkray_expect_error(directory_scene "data: cannot open scene file: is a directory" render ${CLI_DATA})
vkray_expect_error_generated(utf16_bom "utf16le_bom\\.scene:1: UTF-16 is not supported; save as UTF-8" render ${BAD_IN}/utf16le_bom.scene)
vkray_expect_error_generated(utf16le_no_bom "utf16le\\.scene:1: UTF-16 is not supported \\(no byte-order mark" render ${BAD_IN}/utf16le.scene)
vkray_expect_error_generated(utf16be_no_bom "utf16be\\.scene:1: UTF-16 is not supported \\(no byte-order mark" render ${BAD_IN}/utf16be.scene)
vkray_expect_error_generated(utf16_obj "utf16\\.obj:1: UTF-16 is not supported.*OBJ loaded at .*utf16_obj\\.scene:2" render ${BAD_IN}/utf16_obj.scene)
vkray_expect_error_generated(long_line "long_line\\.scene:2: line is 10000011 bytes long, more than the 65536" render ${BAD_IN}/long_line.scene)
# The message quotes the start of the 10 MB number and its length, not the whole of it.
vkray_expect_error_generated(long_number_obj "long_number\\.obj:3:7: value 3 of 'v' '1{48}\\.\\.\\.' \\(10000000 bytes\\) is out of range" render ${BAD_IN}/long_number_obj.scene)
vkray_expect_error_generated(binary_obj "garbage\\.obj:1:[0-9]+: binary data.*OBJ loaded at .*garbage_obj\\.scene:2" render ${BAD_IN}/garbage_obj.scene)
vkray_expect_error_generated(obj_big_polygon "big_polygon\\.obj:2001:1: face of 2000 vertices, more than the 1024" render ${BAD_IN}/big_polygon.scene)
vkray_expect_error_generated(push_depth "push_depth\\.scene:1026:1: pushTransform nested more than 1024 deep" render ${BAD_IN}/push_depth.scene)
vkray_expect_error(negative_index "negative_index\\.scene:6:7: vertex index -1 out of range \\(3 defined, valid 0\\.\\.2\\)" render ${CLI_DATA}/negative_index.scene)
vkray_expect_error(obj_truncated "obj_truncated\\.obj:3:1: expected 3 to 7 numbers after 'v', got 2" render ${CLI_DATA}/obj_truncated.scene)
vkray_expect_error(obj_missing_mtl "obj_missing_mtl\\.scene:3: cannot open material library '.*obj_missing_mtl\\.mtl'.*no such file" render ${CLI_DATA}/obj_missing_mtl.scene)
vkray_expect_error(obj_bad_index "obj_bad_index\\.obj:5:7: vertex index 7 out of range: the file defines 3 vertices" render ${CLI_DATA}/obj_bad_index.scene)
vkray_expect_error(obj_negative_index "obj_negative_index\\.obj:4:9: relative vertex index -4 reaches before the first one" render ${CLI_DATA}/obj_negative_index.scene)
vkray_expect_error(obj_nan "obj_nan\\.obj:2:5: value 2 of 'v' is 'NaN', not a finite number" render ${CLI_DATA}/obj_nan.scene)
vkray_expect_error(obj_bad_polygon "obj_bad_polygon\\.scene:3: .*triangulated the faces into 0 triangles instead of 3" render ${CLI_DATA}/obj_bad_polygon.scene)
# Includes cannot cycle: geo/obj load only OBJ and OFF meshes, OBJ loads only MTL, and OBJ's own
# include (`call`) is refused rather than silently skipped. A .obj given to render is read as OBJ.
vkray_expect_error(geo_self "geo_self\\.scene:3: cannot load .*geo_self\\.scene': unsupported mesh format '\\.scene'" render ${CLI_DATA}/geo_self.scene)
vkray_expect_error(obj_self "obj_self\\.obj:2:1: unknown OBJ statement 'camera'" render ${CLI_DATA}/obj_self.obj)
vkray_expect_error(obj_call "obj_call\\.obj:6:1: OBJ statement 'call' is not supported" render ${CLI_DATA}/obj_call.scene)
vkray_expect_error(transform_underflow "transform_underflow\\.scene:13:1: the transform overflows or becomes singular" render ${CLI_DATA}/transform_underflow.scene)
vkray_expect_error(maxdepth_huge "huge_maxdepth\\.scene:3:10: maxdepth 1000000000 is outside 1\\.\\.64" render ${CLI_DATA}/huge_maxdepth.scene)
vkray_expect_error(maxdepth_flag_negative "--maxdepth -1: must be 1\\.\\.64" render ${CLI_DATA}/one_triangle.scene --maxdepth -1 -o ${CLI_OUT}/x.png)
vkray_expect_error(maxdepth_flag_huge "--maxdepth 1000000000: must be 1\\.\\.64" render ${CLI_DATA}/one_triangle.scene --maxdepth 1000000000 -o ${CLI_OUT}/x.png)
vkray_expect_error(threads_flag_huge "--threads must be 0 \\(all cores\\) or 1\\.\\.1024" render ${CLI_DATA}/one_triangle.scene --cpu --threads 100000 -o ${CLI_OUT}/x.png)
# Larger than any device: refused by its count before anything is generated (a scene that grows
# past 2^26 triangles line by line is refused at the line that would cross it: tests/scene).
vkray_expect_error(generate_huge "generate_huge\\.scene:3:15: triangle count 50000000 is outside 1\\.\\.33554432" render ${CLI_DATA}/generate_huge.scene)

# Structure files: a render that saves its structure (--save-accel) and one that loads it
# (--load-accel) write the same image byte for byte; `bvh` has a triangle order and nodes,
# `kd-backtrack` nodes, indices and extra arrays. Files for another scene, accelerator or the CPU
# renderer are refused before anything is rendered.
foreach(accel bvh kd-backtrack)
  set(file ${CLI_OUT}/default-${accel}.vkacc)
  add_test(NAME cli.accel_file.save.${accel}
           COMMAND ${CLI_DIR}/expect_output.sh "accel file: +saved to .*default-${accel}\\.vkacc in"
                   $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96 --accel ${accel}
                   -o ${CLI_OUT}/accel-file-built-${accel}.png --save-accel ${file})
  set_tests_properties(cli.accel_file.save.${accel} PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1"
    FIXTURES_SETUP accel_file_${accel})
  add_test(NAME cli.accel_file.load.${accel}
           COMMAND ${CLI_DIR}/expect_output.sh "accel: +${accel}, loaded from .*default-${accel}\\.vkacc in .* \\(not built\\)"
                   $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 96x96 --accel ${accel}
                   -o ${CLI_OUT}/accel-file-loaded-${accel}.png --load-accel ${file} --stats)
  set_tests_properties(cli.accel_file.load.${accel} PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1"
    FIXTURES_REQUIRED accel_file_${accel} FIXTURES_SETUP accel_file_loaded_${accel})
  add_test(NAME cli.accel_file.same_image.${accel}
           COMMAND ${CMAKE_COMMAND} -E compare_files ${CLI_OUT}/accel-file-built-${accel}.png
                   ${CLI_OUT}/accel-file-loaded-${accel}.png)
  set_tests_properties(cli.accel_file.same_image.${accel} PROPERTIES FIXTURES_REQUIRED accel_file_loaded_${accel})
endforeach()
add_test(NAME cli.accel_file.json
         COMMAND ${CLI_DIR}/expect_output.sh "\"loaded_from\": \".*default-bvh\\.vkacc\""
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/default.scene --size 32x32
                 -o ${CLI_OUT}/accel-file-json.png --load-accel ${CLI_OUT}/default-bvh.vkacc --json)
set_tests_properties(cli.accel_file.json PROPERTIES TIMEOUT 300 FIXTURES_REQUIRED accel_file_bvh)
# A file made for one_triangle.scene, then read for the same triangle moved (same count).
add_test(NAME cli.accel_file.save_one_triangle
         COMMAND $<TARGET_FILE:vkray> render ${CLI_DATA}/one_triangle.scene -o ${CLI_OUT}/accel-file-one.png
                 --save-accel ${CLI_OUT}/one-triangle.vkacc)
set_tests_properties(cli.accel_file.save_one_triangle PROPERTIES TIMEOUT 180 FIXTURES_SETUP accel_file_one)
function(vkray_expect_accel_file_error name fixture pattern)
  vkray_expect_error(${name} "${pattern}" ${ARGN})
  set_tests_properties(cli.error.${name} PROPERTIES FIXTURES_REQUIRED ${fixture})
endfunction()
vkray_expect_accel_file_error(accel_file_moved_geometry accel_file_one
  "one-triangle\\.vkacc: built for another scene \\(geometry hash differs\\); rebuild it with --save-accel"
  render ${CLI_DATA}/one_triangle_moved.scene --load-accel ${CLI_OUT}/one-triangle.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_accel_file_error(accel_file_other_scene accel_file_bvh
  "default-bvh\\.vkacc: built for another scene \\([0-9]+ triangles, this one has 1\\)"
  render ${CLI_DATA}/one_triangle.scene --load-accel ${CLI_OUT}/default-bvh.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_accel_file_error(accel_file_other_accel accel_file_bvh
  "default-bvh\\.vkacc: built for --accel bvh, not kd-stack; rebuild it with --save-accel"
  render ${CMAKE_SOURCE_DIR}/scenes/default.scene --accel kd-stack --load-accel ${CLI_OUT}/default-bvh.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_accel_file_error(accel_file_cpu accel_file_bvh
  "--load-accel .*default-bvh\\.vkacc: the file holds the GPU's arrays only; --cpu builds its own structure"
  render ${CMAKE_SOURCE_DIR}/scenes/default.scene --cpu --load-accel ${CLI_OUT}/default-bvh.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_error(accel_file_brute "--load-accel: --accel brute uses no structure to load"
  render ${CLI_DATA}/one_triangle.scene --accel brute --load-accel ${CLI_OUT}/x.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_error(accel_file_not_one "one_triangle\\.scene: not a vkray structure file"
  render ${CLI_DATA}/one_triangle.scene --load-accel ${CLI_DATA}/one_triangle.scene -o ${CLI_OUT}/x.png)
vkray_expect_error(accel_file_missing "no-such\\.vkacc: cannot open structure file: No such file"
  render ${CLI_DATA}/one_triangle.scene --load-accel ${CLI_OUT}/no-such.vkacc -o ${CLI_OUT}/x.png)
vkray_expect_error(accel_file_unwritable "no/such/dir/s\\.vkacc: cannot write: directory .* does not exist"
  render ${CLI_DATA}/one_triangle.scene --save-accel ${CLI_OUT}/no/such/dir/s.vkacc -o ${CLI_OUT}/x.png)
include(${CLI_DIR}/render_window_tests.cmake)

# EXR, `vkray convert`, `vkray assemble` and --quiet (docs/outputs.md): a render to EXR converted to
# PNG and back to PFM, the floats unchanged; --quiet prints nothing and keeps the exit status.
add_test(NAME cli.render_exr_convert
         COMMAND bash -c "\"$0\" render \"$1\" --cpu --size 16x12 --quiet -o \"$2/r.exr\" && \"$0\" convert \"$2/r.exr\" \"$2/r.png\" --quiet && \"$0\" convert \"$2/r.exr\" \"$2/r.pfm\" --quiet && \"$0\" compare \"$2/r.exr\" \"$2/r.pfm\" --threshold 0 --max-bad-fraction 0 --quiet && test -s \"$2/r.png\""
                 $<TARGET_FILE:vkray> ${CLI_DATA}/one_triangle.scene ${CLI_OUT})
add_test(NAME cli.compare_quiet_fails_silently
         COMMAND bash -c "\"$0\" render \"$1\" --cpu --size 8x8 --quiet -o \"$2/q.pfm\" && \"$0\" render \"$1\" --cpu --size 8x8 --quiet --background 1,0,0 -o \"$2/q2.pfm\"; out=$(\"$0\" compare \"$2/q.pfm\" \"$2/q2.pfm\" --quiet --max-rmse 0); rc=$?; test $rc -eq 1 && test -z \"$out\""
                 $<TARGET_FILE:vkray> ${CLI_DATA}/one_triangle.scene ${CLI_OUT})
add_test(NAME cli.gen_quiet
         COMMAND bash -c "out=$(\"$0\" gen soup --triangles 10 --force --quiet -o \"$1\") && test -z \"$out\" && test -s \"$1\""
                 $<TARGET_FILE:vkray> ${CLI_OUT}/gen-quiet.scene)
vkray_expect_error(convert_unsupported "x\\.jpg: unsupported image file extension.*\\.exr" convert ${CMAKE_SOURCE_DIR}/docs/images/default.png ${CLI_OUT}/x.jpg)
vkray_expect_error(convert_missing "no-such\\.exr: cannot open" convert ${CLI_OUT}/no-such.exr ${CLI_OUT}/x.png)
vkray_expect_error(assemble_not_exr "default\\.png: a tile must be an EXR" assemble ${CMAKE_SOURCE_DIR}/docs/images/default.png -o ${CLI_OUT}/x.exr)
vkray_expect_error(aov_not_float "d\\.bmp: AOV files are PFM or EXR" render ${CLI_DATA}/one_triangle.scene --aov depth=${CLI_OUT}/d.bmp -o ${CLI_OUT}/x.exr)
# --stats says which normalisation each SAH cost has (a BVH's and a kd-tree's are in different units).
add_test(NAME cli.stats_sah_units
         COMMAND ${CLI_DIR}/expect_output.sh "SAH cost relative to the root's surface area, Ct=1 a node, Ci=20 a triangle"
                 $<TARGET_FILE:vkray> render ${CMAKE_SOURCE_DIR}/scenes/cornell.scene --cpu --size 8x6 --accel kd-stack --stats
                 -o ${CLI_OUT}/sah-units.png)
# A scene that does not fit in the memory `ulimit -v` leaves is refused with one line at its
# generate line, before any of its triangles is made (docs/outputs.md, "Memory: the estimate and the
# refusal"): a GPU render, a CPU render and bench alike, in well under a second. Not in the
# sanitizer build: AddressSanitizer reserves terabytes of address space for its shadow memory, so
# its binary cannot start under any `ulimit -v`.
if(NOT VKRAY_SANITIZE)
set(MEMORY_REFUSAL "many_triangles\\.scene:7[:0-9]*: 30000000 triangles need an estimated [0-9.]+ GB of host memory with --accel bvh, but the process's limit \\(ulimit -v\\) leaves [0-9.]+ [MG]B")
foreach(run "render;-o;${CLI_OUT}/memory.png" "render;--cpu;-o;${CLI_OUT}/memory.png" "bench;--out;${CLI_OUT}/bench-memory")
  list(GET run 0 command)
  list(FIND run "--cpu" cpu)
  set(name ${command})
  if(cpu GREATER -1)
    set(name ${command}_cpu)
  endif()
  list(REMOVE_AT run 0)
  add_test(NAME cli.error.memory_ulimit_${name}
           COMMAND ${CLI_DIR}/expect_error.sh "${MEMORY_REFUSAL}"
                   sh -c "ulimit -v 1500000; exec \"$0\" \"$@\"" $<TARGET_FILE:vkray> ${command}
                   ${CLI_DATA}/many_triangles.scene ${run})
  set_tests_properties(cli.error.memory_ulimit_${name} PROPERTIES TIMEOUT 60)
endforeach()
endif()

# The README's examples, run as a new user runs them after `make test` has fetched the meshes
# (tests/cli/readme_examples.sh). Named outside cli.* so that the sanitizer build's CTest run
# leaves it out: its benchmark example alone takes about a minute on 2 cores.
add_test(NAME readme.examples
         COMMAND ${CLI_DIR}/readme_examples.sh ${CMAKE_SOURCE_DIR} $<TARGET_FILE_DIR:vkray> ${CLI_OUT}/readme)
set_tests_properties(readme.examples PROPERTIES TIMEOUT 900 ENVIRONMENT "VKRAY_VALIDATION=1")
