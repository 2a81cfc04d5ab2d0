# The two commands of the README:
#   make demo   install what is missing, build the vkray binary alone (Release; its shaders with
#               it), render scenes/default.scene to default.png
#   make test   the same install, the whole build (every test binary), the real meshes
#               (scripts/fetch-scenes.sh), then the whole test suite with CTest (on lavapipe when
#               the machine has no GPU)
# More checks (CI runs them after `make test`), each in its own build directory:
#   make sanitize   the unit and GPU tests built with AddressSanitizer + UndefinedBehaviorSanitizer (g++)
#   make fuzz       a libFuzzer target per reader (clang): each on its seed corpus for FUZZ_SECONDS
BUILD ?= build
JOBS ?= $(shell nproc)
SCENE ?= scenes/default.scene
OUT ?= default.png
# A new build directory gets Ninja (ninja-build, from install-deps.sh): it compiles a library's sources
# while the libraries it links are still building, where Make's generator waits for each one. A
# directory configured earlier keeps the generator it has.
generator = $(if $(wildcard $(1)/CMakeCache.txt),,-G Ninja)

.PHONY: all deps configure build vkray meshes demo test sanitize fuzz clean
all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) $(call generator,$(BUILD)) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# What the demo needs: the binary and the SPIR-V it embeds, none of the tests or benchmark programs.
vkray: configure
	@cmake --build $(BUILD) -j $(JOBS) --target vkray

# The real meshes of scenes/*.scene, from Debian packages (verified only, once fetched).
meshes:
	@scripts/fetch-scenes.sh

demo: vkray
	$(BUILD)/vkray render $(SCENE) -o $(OUT)

test: build meshes
	cd $(BUILD) && ctest --output-on-failure --timeout 900 -j $(JOBS)

# ---- make sanitize --------------------------------------------------------------------------------
ASAN_BUILD ?= build-asan
# Every GoogleTest binary: the unit tests, the GPU tests on lavapipe, the stress scenes through every
# accelerator and the bench pipeline (lavapipe's JIT-compiled shaders run uninstrumented; the
# validation layer loads), then the sanitized vkray binary through CTest's tests/cli (every bad
# input of the command line), tests/bench and tests/golden.
SANITIZE_TESTS = vkray_core_tests vkray_scene_tests vkray_image_tests vkray_geometry_tests vkray_cpu_tests vkray_accel_tests \
                 vkray_accel_bvh_tests vkray_accel_kd_tests vkray_gpu_tests vkray_stress_tests \
                 vkray_bench_tests vkray_cli_tests

sanitize: deps meshes
	@cmake -S . -B $(ASAN_BUILD) $(call generator,$(ASAN_BUILD)) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVKRAY_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS) --target $(SANITIZE_TESTS) vkray
	@scripts/run-sanitized-tests.sh $(ASAN_BUILD) $(SANITIZE_TESTS)

# ---- make fuzz ------------------------------------------------------------------------------------
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
# Targets run at once (each is one process): two keep a 2-core machine busy.
FUZZ_PARALLEL ?= 2
# One libFuzzer target per reader (tests/fuzz/NAME_fuzz.cpp): scene, obj, off, ply, gltf, image.
FUZZ_TARGETS ?=

# Seeds and dictionaries: tests/fuzz/make_corpus.sh. Each target runs FUZZ_SECONDS (tests/fuzz/run_fuzz.sh);
# a crash, a sanitizer report, a leak, a 10 s input or 2 GiB of memory fails the run, which leaves the
# input in $(FUZZ_BUILD)/artifacts/ and prints the report.
fuzz:
	@scripts/install-deps.sh fuzz
	@cmake -S . -B $(FUZZ_BUILD) $(call generator,$(FUZZ_BUILD)) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	       -DVKRAY_FUZZ=ON -DVKRAY_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(FUZZ_BUILD) -j $(JOBS) --target vkray_fuzz_targets
	@tests/fuzz/make_corpus.sh $(FUZZ_BUILD)/corpus
	@tests/fuzz/run_fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_PARALLEL) $(FUZZ_TARGETS)

clean:
	rm -rf $(BUILD)
