# Twister Station: thin wrapper over the CMake presets (the PX4 convention).
#   make demo   - install deps, build, run the simulated station demo (headless-safe)
#   make test   - install deps, build, run the whole test suite (what CI runs)
#   make soak   - the whole chain with every fault kind for SOAK_MINUTES (default 60)
# Other targets: deps build bench asan fuzz lint format clean

JOBS ?= $(shell nproc)
FUZZ_SECONDS ?= 600
SOAK_MINUTES ?= 60
SOAK_OUT ?= build/soak

.PHONY: all deps build test test-only fuzz-smoke demo bench soak asan fuzz lint format clean

all: build

deps:
	@.ci/deps.sh

build: deps
	cmake --preset release
	cmake --build --preset release -j $(JOBS)

# Full suite: fuzz harnesses under libFuzzer+ASan+UBSan (short bounded run), then
# every CTest test of the release build; the CTest summary is the last thing printed.
test: build fuzz-smoke test-only

test-only:
	ctest --preset release -j $(JOBS)

fuzz-smoke: deps
	cmake --preset fuzz -DTWISTER_FUZZ_SECONDS=10
	cmake --build --preset fuzz -j $(JOBS)
	ctest --preset fuzz -j $(JOBS)

demo: build
	.ci/demo.sh

bench: build
	.ci/bench.sh

# twister-sim (PTY) -> twister-station -> link -> twister-bridge with every fault kind,
# station SIGKILLs and link cuts; checks nothing committed is lost and RSS stays flat.
soak: build
	python3 tests/soak/soak.py --bin build/bin --deploy hal/twister-station/deploy \
	  --minutes $(SOAK_MINUTES) --out $(SOAK_OUT)

asan: deps
	cmake --preset asan
	cmake --build --preset asan -j $(JOBS)
	ctest --preset asan -j $(JOBS)

# Bounded libFuzzer run of every harness (FUZZ_SECONDS each, default 600).
fuzz: deps
	cmake --preset fuzz -DTWISTER_FUZZ_SECONDS=$(FUZZ_SECONDS)
	cmake --build --preset fuzz -j $(JOBS)
	ctest --preset fuzz -j $(JOBS) --timeout $$(( $(FUZZ_SECONDS) + 120 ))

lint: build
	.ci/lint.sh

format:
	.ci/source-files.sh '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build build-debug build-asan build-fuzz
