# The front door. Native code builds with CMake into build/ (and build-asan/
# for the sanitizer run, build-fuzz/ for libFuzzer); the firmware cross-builds
# with its own Makefile into build/firmware/.
.PHONY: all deps build build-asan firmware test test-native test-asan fuzz demo bench clean

JOBS      ?= $(shell nproc)
BUILD     := build
FUZZ_SECS ?= 60

all: build

deps:
	@tools/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

build-asan: deps
	@cmake -S . -B $(BUILD)-asan -DCMAKE_BUILD_TYPE=Debug -DMR_SANITIZE=ON >/dev/null
	@cmake --build $(BUILD)-asan -j $(JOBS)

firmware: deps
	@if [ -f firmware/Makefile ]; then $(MAKE) --no-print-directory -C firmware OUT=$(CURDIR)/$(BUILD)/firmware; fi

test-native: build firmware
	@cd $(BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS)

test-asan: build-asan firmware
	@cd $(BUILD)-asan && ctest --output-on-failure --no-tests=error -j $(JOBS)

# Bounded libFuzzer runs over the committed seed corpora (a scratch copy, so
# the committed corpus stays as reviewed).
fuzz: deps
	@cmake -S . -B $(BUILD)-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_FUZZ=ON >/dev/null
	@cmake --build $(BUILD)-fuzz -j $(JOBS) --target fuzz_targets
	@tests/fuzz/run.sh $(BUILD)-fuzz $(FUZZ_SECS)

test: test-native test-asan fuzz

demo: build
	@tools/demo.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(BUILD)-asan $(BUILD)-fuzz
