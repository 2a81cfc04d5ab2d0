# Slurm for real (docs/cluster.md): each test starts a throwaway single-node Slurm (munged,
# slurmctld, slurmd on localhost; tests/slurm/slurm_cluster.sh), runs the scripts of scripts/slurm/
# through it and checks their outputs. A Slurm that cannot start (not installed: scripts/install-deps.sh)
# fails the test, saying why. Each Slurm picks its own free ports, so the tests may run in parallel.
set(SLURM_OUT ${CMAKE_BINARY_DIR}/test-output)

add_test(NAME slurm.bench_sweep
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/slurm_bench_test.sh $<TARGET_FILE:vkray> ${CMAKE_SOURCE_DIR}
                 ${SLURM_OUT}/slurm-bench)
set_tests_properties(slurm.bench_sweep PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")

add_test(NAME slurm.render_farm
         COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/slurm/slurm_render_test.sh $<TARGET_FILE:vkray> ${CMAKE_SOURCE_DIR}
                 ${SLURM_OUT}/slurm-render)
set_tests_properties(slurm.render_farm PROPERTIES TIMEOUT 300 ENVIRONMENT "VKRAY_VALIDATION=1")
