# Set-up on a fresh Debian bookworm machine (as root): `make demo` or `make test`.
# Every target installs what is missing first; a second run is quick.
.PHONY: setup build test lint demo demo-msf bench clean

setup:
	@bash scripts/setup.sh

build: setup
	@bash scripts/build.sh

test: build
	@bash scripts/run_tests.sh

lint: setup
	@bash scripts/lint.sh

demo: build
	@bash scripts/demo.sh

demo-msf: build
	@bash scripts/demo.sh msf

bench: build
	@bash scripts/bench.sh

clean:
	rm -rf build/ws
