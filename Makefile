# The front door. Native code builds with CMake into build/ (and build-asan/
# for the sanitizer run, build-clang/ for the second compiler, build-fuzz/
# for libFuzzer); the firmware cross-builds with its own Makefile into
# build/firmware/.
.PHONY: all deps build build-asan build-clang build-tsan firmware test test-native test-asan \
        test-clang test-tsan fuzz \
        demo gallery bench bench-count variants install flash format clean

JOBS      ?= $(shell nproc)
BUILD     := build
FUZZ_SECS ?= 60
PREFIX    ?= /usr/local
# udev reads rules from /usr/lib/udev/rules.d and /etc/udev/rules.d only:
# PREFIX=/usr puts the rule in the first, the default /usr/local in the
# second, and any other prefix (a home folder, a staging tree) keeps it under
# $(PREFIX)/lib/udev/rules.d, to be copied to /etc/udev/rules.d by hand.
ifeq ($(PREFIX),/usr)
UDEV_RULES_DIR ?= /usr/lib/udev/rules.d
else ifeq ($(PREFIX),/usr/local)
UDEV_RULES_DIR ?= /etc/udev/rules.d
else
UDEV_RULES_DIR ?= $(PREFIX)/lib/udev/rules.d
endif

# A build is a means, not the show: no "Entering directory" lines from make,
# and CMake's output (configure and build) goes to a log in the build
# folder, named by the one line per step below; when a step fails, the
# build runs again on one job (so that the first error ends the log) and
# the log's last lines and its path are printed. V=1 shows it all instead.
MAKEFLAGS += --no-print-directory
ifeq ($(V),1)
define cmake_build
	@cmake -S . -B $(1) $(2)
	@cmake --build $(1) -j $(JOBS) $(3) || cmake --build $(1) -j 1 $(3)
endef
else
# The log's last lines and its path, then failure: $(1) the build folder,
# $(2) the step.
build_failed = { tail -n 25 $(1)/build.log >&2; \
  echo "make: $(2) $(1)/ failed; the whole log: $(1)/build.log" >&2; exit 1; }
define cmake_build
	@mkdir -p $(1) && cmake -S . -B $(1) $(2) >$(1)/build.log 2>&1 || $(call build_failed,$(1),configuring)
	@echo "make: building $(1)/ (log: $(1)/build.log; V=1 shows it)"
	@cmake --build $(1) -j $(JOBS) $(3) >>$(1)/build.log 2>&1 || \
	  { cmake --build $(1) -j 1 $(3) >>$(1)/build.log 2>&1; $(call build_failed,$(1),building); }
endef
endif

all: build

# apt's output goes to $(BUILD)/deps.log, one line says what is installed
# (V=1: apt's output on the screen).
deps:
	@tools/install-deps.sh$(if $(filter 1,$(V)),, --log $(BUILD)/deps.log)

# PREFIX is built in too: scenes look for their models in the installed
# PREFIX/share/marionette/scenes (host/scenes/FORMAT.md), so build and
# install with the same one (make PREFIX=/usr; sudo make install PREFIX=/usr).
build: deps
	$(call cmake_build,$(BUILD),-DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_INSTALL_PREFIX=$(PREFIX),)

build-asan: deps
	$(call cmake_build,$(BUILD)-asan,-DCMAKE_BUILD_TYPE=Debug -DMR_SANITIZE=ON,)

# The tests that pin numbers (label `numbers`: physics, solvers, scenes and
# their pinned state hashes, the examples, the build's floating-point
# options), built with clang and run: states must be bit-identical under
# both compilers. Only what they need is built (the target numbers_tests).
build-clang: deps
	$(call cmake_build,$(BUILD)-clang,-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo,--target numbers_tests)

# The tests of what runs on two threads (label `threads`: the show's
# physics thread, its triple buffer and command queue, marionette run in a
# window and replaying on a thread), built with ThreadSanitizer: a data
# race fails the test. Only what they need is built (threads_tests).
build-tsan: deps
	$(call cmake_build,$(BUILD)-tsan,-DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_TSAN=ON,\
	  --target threads_tests)

firmware: deps
	@if [ -f firmware/Makefile ]; then $(MAKE) -C firmware OUT=$(CURDIR)/$(BUILD)/firmware; fi

test-native: build firmware
	@cd $(BUILD) && ctest --output-on-failure --no-tests=error -j $(JOBS)

# tests/lsan.supp: allocations made inside libfyaml and the GL drivers,
# matched by library name, each with its reason.
test-asan: build-asan firmware
	@cd $(BUILD)-asan && LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	  ctest --output-on-failure --no-tests=error -j $(JOBS)

test-clang: build-clang
	@cd $(BUILD)-clang && ctest --output-on-failure --no-tests=error -j $(JOBS) -L numbers

# tests/tsan.supp: races inside the uninstrumented GL driver and SDL,
# matched by library name, each with its reason.
test-tsan: build-tsan
	@cd $(BUILD)-tsan && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1 \
	  suppressions=$(CURDIR)/tests/tsan.supp" \
	  ctest --output-on-failure --no-tests=error -j $(JOBS) -L threads

# The sanitizer run again with clang, whose UBSan checks pointer arithmetic
# that GCC's does not (NULL + 0 in the scene reader went unseen): the scene
# reader's tests and its fuzz target, each fuzz seed run once, any report
# fatal. Only these are built, to keep CI short.
.PHONY: build-asan-clang test-asan-clang
ASAN_CLANG_TESTS := scene_load scene_yaml_ahead scene_index scene_puppets
build-asan-clang: deps
	$(call cmake_build,$(BUILD)-asan-clang,-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_BUILD_TYPE=Debug -DMR_SANITIZE=ON -DMR_FUZZ=ON,--target $(ASAN_CLANG_TESTS) fuzz_scene)

test-asan-clang: build-asan-clang
	@cd $(BUILD)-asan-clang && LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 \
	  ctest --output-on-failure --no-tests=error -j $(JOBS) -R '^($(subst $(eval) ,|,$(ASAN_CLANG_TESTS)))$$'
	@tests/fuzz/run.sh $(BUILD)-asan-clang 0

# Bounded libFuzzer runs over the committed seed corpora (a scratch copy, so
# the committed corpus stays as reviewed).
fuzz: deps
	$(call cmake_build,$(BUILD)-fuzz,-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMR_FUZZ=ON,--target fuzz_targets)
	@tests/fuzz/run.sh $(BUILD)-fuzz $(FUZZ_SECS)

test: test-native test-asan test-clang test-asan-clang test-tsan fuzz

demo: build
	@tools/demo.sh $(BUILD)

# The README's gallery: one still of each example scene and of each display
# mode, drawn by marionette render into docs/pictures/ (tools/gallery.sh).
gallery: build
	@tools/gallery.sh $(BUILD)

# The glove's firmware into the Black Pill over USB DFU (tools/flash.sh):
# hold BOOT0, tap NRST, release BOOT0, then `make flash`.
# BOARD=blackpill_f411_8mhz for a board with an 8 MHz crystal; DRY_RUN=1
# prints the dfu-util command and touches no USB. It builds nothing (make
# firmware first), so that `sudo make flash` never writes into the build tree.
BOARD ?= blackpill_f411
flash:
	@tools/flash.sh $(if $(filter 1,$(DRY_RUN)),--dry-run )$(abspath $(BUILD)/firmware/$(BOARD)/fw.bin)

# Rewrites every C and C++ file in the one .clang-format style (the test
# style_format fails on a file that is not).
format:
	@find protocol firmware host tools tests \( -name '*.c' -o -name '*.h' -o -name '*.cpp' \) \
	  -type f -exec clang-format -i {} +

# The decoder's throughput and the wire cost of a SAMPLE frame; then what
# accuracy costs in time (marionette-bench: the accuracy-cost sweep with its
# plots, the paper's sec. 7 run, capacity, scene load times up to 100 000
# particles, latency), its CSV files and plots in $(BUILD)/bench/.
# BENCH_FLAGS=--quick for a run of about a minute.
bench: build
	@$(BUILD)/tools/protocol-bench/protocol-bench
	@$(BUILD)/tools/marionette-bench/marionette-bench --out $(BUILD)/bench $(BENCH_FLAGS)

# Stable figures for regressions: instruction counts (callgrind) of fixed
# runs, the puppet for 10 s and 10 000 decoded frames, the start-up of
# `marionette sim`, and every setting of the sweep.
bench-count: build
	@tools/marionette-bench/count.sh $(BUILD)

# Random scenes of the kinds hard cases 25 and 26 are (frames jumping at
# their limits, parts thrown at 40 m/s), each run with its case's checks
# (tools/hard-variants): VARIANTS of each family, from seed SEED on.
VARIANTS ?= 500
SEED     ?= 1
variants: build
	@tools/hard-variants/hard-variants --marionette $(BUILD)/host/app/marionette \
	  --count $(VARIANTS) --seed $(SEED)

# The programs, their man pages and the udev rule, under $(DESTDIR)$(PREFIX)
# (the udev rule under $(DESTDIR)$(UDEV_RULES_DIR)): `make`, then
# `sudo make install`. It builds nothing, so that root never writes into the
# build tree.
install:
	@[ -x $(BUILD)/host/app/marionette ] || \
	  { echo "make install: nothing built in $(BUILD)/ yet; run make first" >&2; exit 1; }
	@MR_UDEV_RULES_DIR=$(UDEV_RULES_DIR) cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(BUILD)-asan $(BUILD)-clang $(BUILD)-fuzz $(BUILD)-asan-clang
