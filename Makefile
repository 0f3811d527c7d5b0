# myrabot-desc: `make demo` sets up and runs the main job on the bundled MYRAbot;
# `make test` sets up and runs the tests. Everything installs from here.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
OUT    := out
# Debian peers used by tests and benchmarks: ign sdf -k / -p, check_urdf.
DEBS   := ignition-tools libsdformat-dev liburdfdom-tools
# render: offscreen OpenGL for MuJoCo (EGL with Mesa, or OSMesa); view's browser tests: Chromium + driver.
VIEW_DEBS := libegl1 libgl1-mesa-dri libosmesa6 chromium chromium-driver

.PHONY: install demo test bench fuzz clean system-tools view-tools

install: $(STAMP)

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[test]'
	# pip compiles what it installs, but not an editable project: compile ours too, so that no
	# command pays for compiling its modules (PYTHONDONTWRITEBYTECODE may be set)
	$(BIN)/python -m compileall -q myrabot_desc
	$(MAKE) --no-print-directory system-tools
	$(MAKE) --no-print-directory view-tools
	touch $(STAMP)

# Install the Debian peer tools when missing and when we may (root + apt-get).
system-tools:
	@if command -v ign >/dev/null 2>&1 && ign sdf --versions >/dev/null 2>&1 && command -v check_urdf >/dev/null 2>&1; then \
	  echo "system tools: ign sdf and check_urdf present"; \
	elif command -v apt-get >/dev/null 2>&1 && [ "$$(id -u)" = 0 ]; then \
	  echo "system tools: installing $(DEBS)"; \
	  apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEBS) >/dev/null; \
	else \
	  echo "system tools: cannot install $(DEBS) (need root and apt-get); tests that need them are skipped"; \
	fi

# Install the offscreen GL libraries and Chromium when missing and when we may (root + apt-get).
view-tools:
	@if command -v chromium >/dev/null 2>&1 && command -v chromedriver >/dev/null 2>&1 \
	    && ldconfig -p | grep -q 'libEGL.so.1 ' && ldconfig -p | grep -q 'libOSMesa.so'; then \
	  echo "view tools: EGL, OSMesa, chromium and chromedriver present"; \
	elif command -v apt-get >/dev/null 2>&1 && [ "$$(id -u)" = 0 ]; then \
	  echo "view tools: installing $(VIEW_DEBS)"; \
	  apt-get update -qq >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(VIEW_DEBS) >/dev/null; \
	else \
	  echo "view tools: cannot install $(VIEW_DEBS) (need root and apt-get); render and browser tests are skipped"; \
	fi

demo: install
	mkdir -p $(OUT)
	$(BIN)/myrabot-desc build -o $(OUT)/myrabot.urdf
	$(BIN)/myrabot-desc info --no-tree
	$(BIN)/myrabot-desc check --inertia
	$(BIN)/myrabot-desc convert --to sdf -o $(OUT)/myrabot.sdf
	$(BIN)/myrabot-desc convert --to world --layout escoja -o $(OUT)/escoja.sdf
	$(BIN)/myrabot-desc convert --to mjcf -o $(OUT)/mjcf/myrabot.xml
	$(BIN)/myrabot-desc sim vuelta --plot $(OUT)/vuelta.png --csv $(OUT)/vuelta.csv
	$(BIN)/myrabot-desc render --view all -o $(OUT)/myrabot.png
	@echo "demo outputs in $(OUT)/"
	@echo "see the robot in your browser (joint sliders, inertia boxes, check findings):"
	@echo "  $(BIN)/myrabot-desc view --open"

# The tests run on every core (pytest-xdist, work stealing: the slow corpus and browser tests are
# spread out). TEST_USUALLY: a whole run's wall time from a fresh clone on 2 cores, as measured.
TEST_WORKERS ?= auto
TEST_USUALLY := about 12-13 minutes of tests on 2 cores (2,680 tests), after the install
test: install
	@echo "make test: usually $(TEST_USUALLY); $(TEST_WORKERS) workers (pytest-xdist)"
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist worksteal

# Every bench runs, in one go (a missed target does not stop the others); the exit code says whether
# any bench failed or missed its target.
bench: install
	@failed=""; for b in bench/bench_*.py; do echo "== $$b"; $(BIN)/python $$b || failed="$$failed $$b"; done; \
	if [ -n "$$failed" ]; then echo "benches that failed or missed a target:$$failed"; exit 1; fi

# Hardening (issue 7): 10,000 mutated URDF/xacro/material cases through every command (~5 min, 2 workers).
fuzz: install
	$(BIN)/python bench/fuzz_long.py --cases 10000

clean:
	rm -rf $(OUT) .pytest_cache
