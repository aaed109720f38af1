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

.PHONY: deps build demo demo-bag test test-sanitizers fuzz bench validate-gap clean

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

test: build
	cd $(WS) && colcon test --event-handlers console_direct+ \
		&& colcon test-result --verbose

# The unit tests (every gtest target, the tools' process tests included) built in their own build
# and install spaces with AddressSanitizer and UndefinedBehaviorSanitizer; any finding fails.
SAN := --build-base $(WS)/sanitizers/build --install-base $(WS)/sanitizers/install
test-sanitizers: deps
	@mkdir -p $(WS)/src
	@ln -sfn $(CURDIR) $(WS)/src/propulsion_estimator
	cd $(WS) && colcon build $(SAN) --event-handlers console_direct+ \
		--cmake-args -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPE_SANITIZE=ON
	cd $(WS) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
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

# The gap diagnosis validated on simulated flights whose effect is withheld from it (44 random
# cases, about five minutes on 2 cores); rewrites VALIDATION.md. CASES=N for another count.
CASES ?= 44
validate-gap: build
	$(SETUP) && python3 scripts/validate_gap.py --cases $(CASES) --jobs 2 \
		--bin $(WS)/install/propulsion_estimator/lib/propulsion_estimator --repo $(CURDIR) \
		--work $(WS)/validate_gap --markdown VALIDATION.md

bench: build
	$(SETUP) && scripts/run_benchmarks.sh

clean:
	rm -rf $(WS)
