# Thin wrapper over CMake; the README's two commands use it.
#   make run    configure, build (Release) and run the main job
#   make test   configure, build and run the whole test suite
BUILD ?= build
JOBS  ?= $(shell nproc)

.PHONY: configure build run test bench clean

configure:
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DRINGCRUSH_WITH_MPI=ON

build: configure
	cmake --build $(BUILD) -j$(JOBS)

run: build
	./$(BUILD)/ringcrush formula data/scenes/thesis_static.toml -o results/thesis_formula

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --timeout 600

clean:
	rm -rf $(BUILD)
