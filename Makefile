# Set-up on a fresh Debian bookworm machine (as root): `make demo` or `make test`.
# Every target installs what is missing first; a second run is quick.
.PHONY: setup build test test-long test-all test-sanitize lint demo demo-msf bench clean

setup:
	@bash scripts/setup.sh

build: setup
	@bash scripts/build.sh

# make test: the quick tier (every test but those marked long; under 25 min from a fresh clone, setup
# and build included: 23.5 min on the last run); make test-long: only the long tier; make test-all:
# both in one run. .ci/run runs lint, test and test-long (51 min on CI's last run).
test: build
	@ROTORS_TEST_TIER=quick bash scripts/run_tests.sh

test-long: build
	@ROTORS_TEST_TIER=long bash scripts/run_tests.sh

test-all: build
	@ROTORS_TEST_TIER=all bash scripts/run_tests.sh

# the gtests and the Python-module tests under ASan + UBSan, the batch / step_all tests under TSan
# (own workspaces in build/sanitize; scripts/test_sanitize.sh)
test-sanitize: build
	@bash scripts/test_sanitize.sh

lint: setup
	@bash scripts/lint.sh

demo: build
	@bash scripts/demo.sh

demo-msf: build
	@bash scripts/demo.sh msf

bench: build
	@bash scripts/bench.sh $(if $(ONLY),--only $(ONLY))

clean:
	rm -rf build/ws
