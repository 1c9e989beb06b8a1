# racebot: `make run` drives the car, `make test` runs every test. Both set up what is missing first.
SHELL := /bin/bash
ROOT := $(CURDIR)
VENV := $(ROOT)/.venv
# ROS nodes must run on Debian's interpreter (rospy lives in its dist-packages), never a pyenv shim.
SYSTEM_PYTHON := /usr/bin/python3
IN_WS := source $(ROOT)/devel/setup.bash &&

.PHONY: setup debian venv build test unit lint run demo bench bench-quick soak corpus deps fresh-check clean help

help:
	@echo "make run    set up, build, start the simulator with the racebot in the room"
	@echo "make test   set up, build, run every test; ends with 'N passed, N failed'"
	@echo "make setup  install what is missing (Debian packages, .venv) and build into build/ devel/"
	@echo "make demo   headless: drive a scripted route, print it, draw it (out/demo/demo_path.png); where gmapping"
	@echo "            is built (make deps ARGS=gmapping) it maps the room too (out/demo/demo_map.png)"
	@echo "make unit   only the unit tests (no ROS master)"
	@echo "make lint   ruff over the repository (ruff.toml); make test runs it too"
	@echo "make corpus public ROS 1 robot and world packages run unchanged; the table in out/corpus/ (network,"
	@echo "            or RACEBOT_CORPUS_DIR=existing clones; ~1 h; docs/CORPUS.md)"
	@echo "make deps   ARGS='~/my_ws/src amcl': what a workspace or package needs that neither Debian nor racebot"
	@echo "            has, fetched at its Noetic release and built in an underlay (docs/DEPS.md)"
	@echo "make fresh-check  'make test' in a brand-new minimal Debian 12 root (root only; ~10 min); CI runs it"
	@echo "            extra roslaunch arguments: make run ARGS='paused:=true x_pos:=1'"
	@echo "make clean  remove build/ devel/ (keeps .venv)"

setup: debian venv build

debian:
	@tools/install_debian_packages.sh tools/debian-packages.txt

venv: $(VENV)/.racebot-installed $(VENV)/bin/.racebot-xacro

# A bare `xacro` on PATH (the venv's bin/ comes first) must be the Noetic xacro that `$(find xacro)/xacro`
# runs (upstream_compat/xacro), not the plain 1.13.3 console script pip installed: Noetic-era launch files
# call `command="xacro ..."` with `${xacro.load_yaml(...)}` inside.
$(VENV)/bin/.racebot-xacro: $(VENV)/.racebot-installed upstream_compat/xacro/xacro
	@printf '#!%s\n# racebot: Noetic xacro, i.e. upstream_compat/xacro/xacro (written by make venv)\nimport runpy, sys\nsys.argv[0] = %s\nrunpy.run_path(sys.argv[0], run_name="__main__")\n' \
	    '$(VENV)/bin/python3' "'$(ROOT)/upstream_compat/xacro/xacro'" > $(VENV)/bin/xacro
	@chmod +x $(VENV)/bin/xacro
	@touch $@

$(VENV)/.racebot-installed: tools/requirements.txt
	@test -x $(VENV)/bin/python3 || $(SYSTEM_PYTHON) -m venv --system-site-packages $(VENV)
	$(VENV)/bin/pip install --disable-pip-version-check -q -r tools/requirements.txt
	@touch $@

# out/ holds what tests, the bench, the demo and the soak write, generated catkin packages among them: its
# CATKIN_IGNORE keeps them out of this source space, so `make run` after `make test` builds.
# catkin_make is incremental: with nothing changed it only re-checks, in seconds. Building with the
# venv interpreter gives every node script a shebang that sees rospy and pybullet, whatever PATH says.
build: debian venv
	@mkdir -p build devel out && touch build/CATKIN_IGNORE devel/CATKIN_IGNORE out/CATKIN_IGNORE
	@PATH=$(VENV)/bin:$$PATH catkin_make -C $(ROOT) --source $(ROOT) --build $(ROOT)/build \
	    -DCATKIN_DEVEL_PREFIX=$(ROOT)/devel -DPYTHON_EXECUTABLE=$(VENV)/bin/python3 \
	    -DRACEBOT_VENV=$(VENV) > build/catkin_make.log 2>&1 \
	  || { tail -40 build/catkin_make.log; echo "racebot: build failed; full log in build/catkin_make.log" >&2; exit 1; }
	@echo "racebot: built; 'source devel/setup.bash' for a shell with every racebot command"

test: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/run_tests.py

# ruff with the repository's ruff.toml (make test runs it too, as one test)
lint: setup
	@$(VENV)/bin/ruff check $(ROOT)

unit: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/run_tests.py --unit-only

# With no display there is no window to drive from: headless, and say how to drive from a shell.
HEADLESS_ARGS = $(if $(DISPLAY),,gui:=false teleop:=false)
run: setup
	@$(if $(DISPLAY),,echo "racebot: no display (DISPLAY is unset): running headless. In another shell, drive with:"; \
	  echo "  cd $(ROOT) && source devel/setup.bash"; \
	  echo "  rostopic pub -r 10 /ackermann_cmd_mux/output ackermann_msgs/AckermannDriveStamped '{drive: {speed: 0.5, steering_angle: 0.45}}'";)
	@$(IN_WS) roslaunch racebot_gazebo racebot.launch $(HEADLESS_ARGS) $(ARGS)

# Headless: a scripted route through the room (~13 s of sim time), then the distance, the final pose
# and out/demo/demo_path.png (the path over the room's walls). Where make deps built gmapping, it maps the
# room too (racebot_gazebo's gmapping.launch): the map's size, its cells on the walls, out/demo/demo_map.png.
demo: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/demo.py

# Speed against the physics ceiling and fidelity against the kinematic model: prints the table, writes
# out/bench/ (bench.json, PNG plots), each key figure beside the one kept in tools/bench/last_figures.json.
# About 8 minutes; bench-quick runs every part briefly (about 3 min on a 2-core machine). Keep this run's figures as the
# reference (then commit the file): make bench ARGS=--save.
bench: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/run_bench.py $(ARGS)

bench-quick: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/run_bench.py --quick

# The soak: 30 min of sim time driving the room as fast as possible (memory, logs, /clock); report in
# out/soak/. Shorter or other: make soak ARGS='--sim-minutes 5'.
soak: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/soak.py $(ARGS)

# The corpus (tools/corpus/manifest.yaml): each public package cloned at its pinned commit into
# ~/.cache/racebot/corpus (RACEBOT_CORPUS_DIR: a folder of existing clones instead, no network), built on
# top of racebot, run headless with its own commands and checked; prints the table, writes
# out/corpus/corpus.md and corpus.json. One row: make corpus ARGS='--only husky'. docs/CORPUS.md.
corpus: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/corpus/run.py $(ARGS)

# Missing ROS 1 packages from source (tools/deps/, docs/DEPS.md): for each workspace or package folder (or package
# name) in ARGS, what its package.xml files and launch files need that neither Debian (rosdep, rospack) nor racebot
# provides, fetched with rosinstall_generator and vcstool at the Noetic release and built with catkin_make_isolated
# in ~/.cache/racebot/deps/ws on top of racebot's devel space; then `source ~/.cache/racebot/deps/ws/devel_isolated/
# setup.bash`. Offline: RACEBOT_CORPUS_MIRRORS=ROOT or RACEBOT_CORPUS_DIR=DIR (as make corpus), and the rosdistro from
# ROOT/ros+rosdistro/repo or --rosdistro PATH. A second run with nothing new takes about a second.
deps: setup
	@$(IN_WS) $(VENV)/bin/python3 tools/deps/run.py $(ARGS)

# The README's `make test` on a brand-new minimal Debian 12 (mmdebstrap, chroot) from a clone of HEAD:
# proves that `make setup` installs everything the suite calls. Needs root; CI runs it.
fresh-check: debian
	@tools/fresh_check.sh

clean:
	rm -rf build devel
