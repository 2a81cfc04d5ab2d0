# The two commands of the README:
#   make demo   install what is missing, build (Release), render scenes/default.scene to default.png
#   make test   the same install and build, the real meshes (scripts/fetch-scenes.sh), then the
#               whole test suite with CTest (on lavapipe when the machine has no GPU)
BUILD ?= build
JOBS ?= $(shell nproc)
SCENE ?= scenes/default.scene
OUT ?= default.png

.PHONY: all deps configure build meshes demo test clean
all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The real meshes of scenes/*.scene, from Debian packages (verified only, once fetched).
meshes:
	@scripts/fetch-scenes.sh

demo: build
	$(BUILD)/vkray render $(SCENE) -o $(OUT)

test: build meshes
	cd $(BUILD) && ctest --output-on-failure --timeout 900 -j $(JOBS)

clean:
	rm -rf $(BUILD)
