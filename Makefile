# The two entry points of the README. Both install missing Debian packages first
# (tools/bootstrap.sh), configure with the CMake presets and build with every core.
JOBS ?= $(shell nproc)
# `make fuzz`: seconds per target, and libFuzzer worker processes per target (fuzz/README.md).
SECONDS ?= 60
FUZZ_JOBS ?= 1

.PHONY: demo test deps build build-asan bench clean fuzz

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

# Optional: clang + libFuzzer (bootstrap --fuzz), an instrumented build in build-fuzz/, then every fuzz
# target for SECONDS seconds; findings go to build-fuzz/crashes/<target>/, the summary to
# build-fuzz/fuzz-summary.json. Never part of demo / test / CI.
fuzz:
	bash tools/bootstrap.sh --fuzz
	cmake -S . -B build-fuzz -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DTESSERA_FUZZ=ON \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" >/dev/null
	cmake --build build-fuzz --target fuzzers -j$(JOBS)
	python3 fuzz/run_fuzz.py --build build-fuzz --seconds $(SECONDS) --jobs $(FUZZ_JOBS)

clean:
	rm -rf build build-asan build-debug build-fuzz out
