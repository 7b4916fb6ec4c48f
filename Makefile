# The two entry points of the README. Both install missing Debian packages first
# (tools/bootstrap.sh), configure with the CMake presets and build with every core.
JOBS ?= $(shell nproc)

.PHONY: demo test deps build build-asan bench clean

demo: build
	./build/tessera demo -o out/demo

test: build build-asan
	ctest --preset release -j$(JOBS)
	ctest --preset asan -j$(JOBS)

deps:
	bash tools/bootstrap.sh

build: deps
	cmake --preset release >/dev/null
	cmake --build --preset release -j$(JOBS)

build-asan: deps
	cmake --preset asan >/dev/null
	cmake --build --preset asan -j$(JOBS)

clean:
	rm -rf build build-asan build-debug out
