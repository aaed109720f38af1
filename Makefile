# The README's commands. Everything builds in a colcon workspace under .ws/ whose src/ links
# back to this repository; Debian's ROS 1 lives in /usr, and /usr/bin goes first on PATH so that
# catkin, roslaunch and rostest use the system python3 (a pyenv one has no ROS modules).
SHELL := /bin/bash
export PATH := /usr/bin:$(PATH)
export PYTHONDONTWRITEBYTECODE := 1
# Everything runs on this machine: ROS nodes address each other as localhost, which works where
# the host name does not resolve (containers, fresh CI machines).
export ROS_HOSTNAME ?= localhost

WS := $(CURDIR)/.ws
SETUP := source $(WS)/install/setup.sh
COLCON_BUILD := colcon build --event-handlers console_direct+ \
	--cmake-args -DCMAKE_BUILD_TYPE=Release

.PHONY: deps build demo demo-bag test docs sizes check test-sanitizers fuzz bench validate-gap validate-gap-fixed ros-free arm64 arm64-build bench-arm64 clean

deps:
	@scripts/install_deps.sh

build: deps
	@mkdir -p $(WS)/src
	@ln -sfn $(CURDIR) $(WS)/src/propulsion_estimator
	cd $(WS) && $(COLCON_BUILD)

# Replays the bundled hover-flight bag through the node and prints the payload estimates.
demo: build
	$(SETUP) && scripts/run_demo.sh

# Regenerates the bundled demo flight (bag and manifest) with the simulator; see the comment at the
# top of config/demo/demo_flight_profile.yaml.
demo-bag: build
	$(SETUP) && rosrun propulsion_estimator simulate flight --params config/sim/e300_dji2212_dji9443.yaml \
		--profile config/demo/demo_flight_profile.yaml --seed 1 --compression bz2 \
		--bag config/demo/demo_flight.bag --manifest config/demo/demo_flight.manifest.yaml

# All tests: the API reference without a warning, the size rules, the colcon tests (unit, rostests
# with the soak and the kill-during-tare tests, bag replays, fleet), then the Raspberry Pi's
# ROS-free tree built natively under the sanitizers and its unit tests run there (ros-free).
# Three builds (Release, the ROS-free tree, the whole package again under the sanitizers) came to
# about 80 minutes of a clean clone on 2 cores, and CI stopped at its 90 on 2026-12-03: the ROS-free
# tree is the sanitizer build, and the whole package under the sanitizers (its ROS adapters, tools
# and fuzz corpora included) is make test-sanitizers, to run when those change.
test: docs sizes check ros-free

# The API reference of the public headers (docs/Doxyfile), HTML in .ws/docs/html/index.html. Any
# warning fails it: an undocumented public declaration, a broken reference.
docs: deps
	@mkdir -p $(WS)/docs
	PE_DOCS_OUT=$(WS)/docs doxygen docs/Doxyfile

# No function in src/ over 120 lines, no file over 600 (the guide's rule); the checker first shows
# that it flags a long function and a long file.
sizes: deps
	python3 scripts/check_sizes.py --self-test
	python3 scripts/check_sizes.py

# The colcon tests alone, in the Release build.
# Earlier results are removed first: a test binary renamed since would leave its old results behind.
check: build
	rm -f $(WS)/build/propulsion_estimator/test_results/propulsion_estimator/*.xml
	cd $(WS) && colcon test --event-handlers console_direct+ \
		&& colcon test-result --verbose

# The unit tests (every gtest target, the tools' process tests included) built in their own build
# and install spaces with AddressSanitizer and UndefinedBehaviorSanitizer; any finding fails.
# -O1 -g1 (line tables, enough for the sanitizers' stack traces) compiles three times faster than
# -O2 -g under the sanitizers (src/gap/diagnosis.cpp: 20 s against 61 s on the 2-core VM), and
# the sanitizer build was most of CI's time.
SAN := --build-base $(WS)/sanitizers/build --install-base $(WS)/sanitizers/install
# The long statistical tests: each flies tens to hundreds of simulated flights or family packs
# (under the sanitizers 90-150 s each, and the packs' own curves 400 s; in Release 10-80 s). They
# run once, in the Release build of make check; the sanitizer run and the ROS-free run leave them
# out, as the same code runs there in the short tests of the same modules
# (TheHoverTimeLeftOverAFlightWithItsInterval, TwoPacksAlikeAboveTheirKnee..., TwoPacksLearnedAlike...,
# PackLearner.*,
# ModelCheckFlight's fault tests, DynamicFlight's other tests).
LONG_TESTS := CapabilityFlight.HoverEnduranceOnFamilyPacksDevelopmentSeeds \
	CapabilityFlight.HoverEnduranceOnFamilyPacksHeldOutSeeds \
	CapabilityFlight.HoverEnduranceOnFamilyPacksFreshSeeds \
	CapabilityFlight.HoverEnduranceWithThePacksOwnCurve \
	CapabilityFlight.HoverEnduranceWithTheOwnCurveOfWarmNewPacks \
	CapabilityFlight.TheEnduranceIntervalIsCalibratedOnTheDevelopmentPacks \
	CapabilityFlight.TheEnduranceIntervalHoldsTheTruthOnHeldOutPacks \
	CapabilityFlight.TheEnduranceIntervalHoldsTheTruthOnHeldOutPacksOfKnownTemperature \
	CapabilityFlight.APackFlownOnceBeforeDevelopmentPacks \
	CapabilityFlight.APackFlownOnceBeforeHeldOutPacks \
	CapabilityFlight.APackFlownOnceBeforeWithItsOwnCurveDevelopmentPacks \
	CapabilityFlight.APackFlownOnceBeforeWithItsOwnCurveHeldOutPacks \
	CapabilityFlight.LearnedPacksThatHaveATwinFrom30Percent \
	ModelCheckFlight.NoFlagOnTwoHundredFlightsWithoutAFault \
	DynamicFlight.TheSameFlightsLoggedAtAnyRateKeepTheSameBlocksAndSelectAlike
space := $(subst ,, )
LONG_TESTS_GTEST_FILTER := -$(subst $(space),:,$(strip $(LONG_TESTS)))
LONG_TESTS_CTEST_REGEX := ^($(subst $(space),|,$(subst .,\.,$(strip $(LONG_TESTS)))))$$
test-sanitizers: deps
	@mkdir -p $(WS)/src
	@ln -sfn $(CURDIR) $(WS)/src/propulsion_estimator
	cd $(WS) && colcon build $(SAN) --event-handlers console_direct+ \
		--cmake-args -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
		-DPE_SANITIZE=ON
	rm -f $(WS)/sanitizers/build/propulsion_estimator/test_results/propulsion_estimator/*.xml
	cd $(WS) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
		GTEST_FILTER='$(LONG_TESTS_GTEST_FILTER)' \
		colcon test $(SAN) --event-handlers console_direct+ --ctest-args -R _gtest_ \
		&& colcon test-result --test-result-base $(WS)/sanitizers/build --verbose

# Every input reader fuzzed with libFuzzer for SECONDS seconds each (clang, AddressSanitizer and
# UndefinedBehaviorSanitizer), in its own build and install spaces, from a working copy of its
# corpus in test/fuzz/corpus/; findings land in .ws/fuzz/findings/. MERGE=1 merges what the run
# found new into the committed corpora. See test/fuzz/README.md.
FUZZ := --build-base $(WS)/fuzz/build --install-base $(WS)/fuzz/install
SECONDS ?= 60
fuzz:
	@scripts/install_deps.sh fuzz
	@mkdir -p $(WS)/src
	@ln -sfn $(CURDIR) $(WS)/src/propulsion_estimator
	cd $(WS) && colcon build $(FUZZ) --event-handlers console_direct+ --cmake-target fuzzers \
		--cmake-args -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DPE_FUZZ=ON -DCATKIN_ENABLE_TESTING=OFF
	scripts/run_fuzzers.sh --bin $(WS)/fuzz/build/propulsion_estimator/devel/lib/propulsion_estimator \
		--work $(WS)/fuzz --seconds $(SECONDS) $(if $(MERGE),--merge)

# The gap diagnosis validated on simulated flights whose effect is withheld from it: 44 random
# cases, each drawing its hardware and vehicle from the randomized family, on a fresh seed each run
# (printed; SEED=N repeats one); about seven minutes on 2 cores; writes the seed's section of
# docs/VALIDATION.md. validate-gap-fixed runs the old suite (seed 2026, the thesis hardware). CASES=N for
# another count; PLAIN=1 flies the family without its background physics and law forms.
CASES ?= 44
SEED ?=
validate-gap: build
	$(SETUP) && nice python3 scripts/validate_gap.py --family $(if $(PLAIN),--plain-world) --cases $(CASES) --jobs 2 $(if $(SEED),--seed $(SEED)) \
		--bin $(WS)/install/propulsion_estimator/lib/propulsion_estimator --repo $(CURDIR) \
		--work $(WS)/validate_gap_family --markdown docs/VALIDATION.md --compare-rpm-view
validate-gap-fixed: build
	$(SETUP) && nice python3 scripts/validate_gap.py --cases $(CASES) --jobs 2 --seed 2026 \
		--bin $(WS)/install/propulsion_estimator/lib/propulsion_estimator --repo $(CURDIR) \
		--work $(WS)/validate_gap --markdown docs/VALIDATION.md

# Every benchmark (google benchmark, the node end to end against two transport floors and a rospy
# peer, callgrind's instructions per message, diagnose_gap on an hour of flight), then rewrites
# docs/BENCHMARKS.md with the figures, the machine, the date and the commands: 12.5 minutes after the
# build (measured 2026-11-23 on the quiet 2-core VM). QUICK=1 tries it in about 3 minutes (one round
# of 10 s per system, 500 messages under callgrind, no diagnose_gap) and writes
# .ws/bench/BENCHMARKS.md instead; BENCH_DURATION_S=N sets the end-to-end load per system and round
# (default 60), BENCH_ROUNDS=N the rounds (default 2).
QUICK ?= 0
bench: build
	$(SETUP) && QUICK=$(QUICK) scripts/run_benchmarks.sh

# The ROS-free tree that make arm64 cross-builds for the Raspberry Pi (cmake/ros_free.cmake: the
# modules that compute, their unit tests, the core benchmark; no catkin), built natively with plain
# cmake in .ws/ros_free/ with AddressSanitizer and UndefinedBehaviorSanitizer (-O1 -g1, as
# test-sanitizers) and its tests run with ctest, the long statistical ones left out; fails when it
# does not build, any test fails or a sanitizer finds anything, so that make test (and CI) catches a
# change that breaks the Pi's build or the memory of the code that computes.
ROS_FREE := $(WS)/ros_free
ros-free: deps
	cmake -S . -B $(ROS_FREE) -DPE_ROS_FREE=ON -DPE_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
		"-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"
	cmake --build $(ROS_FREE) -j 2
	cd $(ROS_FREE) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
		ctest -j 2 --output-on-failure --no-tests=error -E '$(LONG_TESTS_CTEST_REGEX)'

# Raspberry Pi: the ROS-free modules, their unit tests and the core benchmark cross-compiled for
# arm64 in .ws/arm64/ (no catkin, no ROS for arm64), the tests run under qemu-user; fails when any
# test fails. Installs its own packages (scripts/install_arm64_deps.sh).
ARM64 := $(WS)/arm64
QEMU_ARM64 := qemu-aarch64 -L /usr/aarch64-linux-gnu
arm64-build:
	@scripts/install_arm64_deps.sh
	cmake -S . -B $(ARM64) -DPE_ROS_FREE=ON -DCMAKE_BUILD_TYPE=Release \
		-DCMAKE_TOOLCHAIN_FILE=$(CURDIR)/cmake/aarch64-linux-gnu.cmake
	cmake --build $(ARM64) -j 2

arm64: arm64-build
	cd $(ARM64) && ctest -j 2 --output-on-failure

# The core per-message benchmark, arm64 emulated: rewrites docs/BENCHMARKS.arm64.md, which make bench
# pastes into docs/BENCHMARKS.md.
bench-arm64: arm64-build
	$(QEMU_ARM64) $(ARM64)/bench_estimator --benchmark_out=$(ARM64)/bench_estimator.json \
		--benchmark_out_format=json
	python3 scripts/write_arm64_benchmarks.py --json $(ARM64)/bench_estimator.json --out docs/BENCHMARKS.arm64.md \
		--command "make bench-arm64"

clean:
	rm -rf $(WS)
