# The two commands of the README: `make run` and `make test`. Both install what is
# missing first (idempotent: stamps make the second run quick).

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PY_STAMP  := $(VENV)/.installed
SERVER_STAMP := $(VENV)/.server-installed
JS_STAMP  := clients/js/node_modules/.installed
CHROMIUM  := /usr/bin/chromium
NATS      := /usr/sbin/nats-server
NGINX     := /usr/sbin/nginx
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
HOST ?= 127.0.0.1
PORT ?= 8000

COMPOSE   := /usr/bin/docker-compose
DEBIAN_PROGRAMS := $(CHROMIUM) $(COMPOSE) $(NATS) $(NGINX)
HOST_CA   ?= /etc/ssl/certs/ca-certificates.crt

.PHONY: run test test-long test-container bench bench-quick bench-browser generate install install-server js-packages bytecode clean

run: install
	$(BIN)/vp-server --host $(HOST) --port $(PORT) $(if $(STATE_DIR),--state-dir $(STATE_DIR))

test: install $(DEBIAN_PROGRAMS)
	$(BIN)/python -m pytest $(PYTEST_ARGS)

# The fuzzers at full length, 10 000 cases each (the suite runs 500 of each; CI does
# not run this): a few minutes, and a hang guard of 20 minutes a fuzzer.
test-long: install $(DEBIAN_PROGRAMS)
	VP_FUZZ_CASES=10000 $(BIN)/python -m pytest -m fuzz --timeout 1200 $(PYTEST_ARGS)

# The image built and its tests run inside it (the tests service: `make test` there).
# Needs a Docker engine. The host's certificate authorities go into the image (a proxy
# that inspects TLS needs them; elsewhere they add nothing); the base image is made with
# debootstrap where it cannot be pulled (docker/base-image.sh).
test-container: $(COMPOSE)
	docker/engine.sh
	if [ -f $(HOST_CA) ]; then cp $(HOST_CA) docker/certs/host.crt; fi
	VP_BASE_IMAGE=$$(docker/base-image.sh) $(COMPOSE) build tests
	$(COMPOSE) run --rm tests

# Every file written from a source of truth (generate/): api.json, the typed messages, the
# JS client's skeletons, the bundled meshes; tests/generate/test_generated.py finds drift.
generate: install
	$(BIN)/python -m generate

# Every figure of bench/results.json, written with bench/RESULTS.md (a few minutes; run it
# on a quiet machine). bench-quick runs the same code on tiny scenes (the test suite does).
bench: install
	$(BIN)/python -m bench.run

BENCH_OUT ?= $(or $(TMPDIR),/tmp)/vp-bench-quick
bench-quick: install
	$(BIN)/python -m bench.run --quick --out $(BENCH_OUT)

# The browser and flood measures (separate: they take minutes and a browser).
bench-browser: install $(CHROMIUM)
	$(BIN)/python bench/viewer_latency.py
	$(BIN)/python bench/viewer_pictures.py
	$(BIN)/python bench/flood.py

install: $(PY_STAMP) $(JS_STAMP) bytecode

# The project's own modules compiled once, before anything runs them: where
# PYTHONDONTWRITEBYTECODE is set (as on our machines) no process writes them, and every
# one of a test run's hundreds of processes (servers, their fork servers, scripts) compiled
# them again, 0.2-0.3 CPU-s each (the packages in .venv are compiled when installed)
bytecode: $(PY_STAMP)
	$(BIN)/python -m compileall -q -j 0 server clients/python/virtual_prosthetics bench generate tests

# The server image's two halves (Dockerfile): the server alone in .venv (no test tools,
# no client) and the npm packages it serves (fetched where Node is).
install-server: $(SERVER_STAMP)
js-packages: $(JS_STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# uv (PyPI, pinned) installs the pinned packages: 13 s where pip took 42 on a fresh clone,
# the same packages at the same versions, compiled as pip compiles them (without, every
# process took twice the CPU to import them)
UV := uv==0.13.9
$(PY_STAMP): $(BIN)/python pyproject.toml requirements-dev.txt clients/python/pyproject.toml
	$(BIN)/python -m pip install --quiet --disable-pip-version-check $(UV)
	$(BIN)/python -m uv pip install --quiet --compile-bytecode --python $(BIN)/python \
		-r requirements-dev.txt -e . -e clients/python
	touch $@

$(SERVER_STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e .
	touch $@

# three.js, lil-gui and ws: the JavaScript client's dependencies (Node), also served to
# browsers by the server (the viewer and the client share them).
$(JS_STAMP): clients/js/package.json clients/js/package-lock.json
	cd clients/js && npm ci --no-audit --no-fund --loglevel=error
	touch $@

# The browser tests drive Debian's chromium (headless, software WebGL); the container
# files are checked with docker-compose (no engine needed for that); the cluster's tests
# start Debian's nats-server (the bus) and nginx (the gateways' load balancer). Each
# program is its package's name; those missing are installed together, with one update.
$(DEBIAN_PROGRAMS):
	missing="$$(for p in $(DEBIAN_PROGRAMS); do [ -x $$p ] || basename $$p; done)"; \
	if [ -n "$$missing" ]; then \
		$(SUDO) apt-get update -q && \
		DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -q --no-install-recommends \
			$$missing; \
	fi

clean:
	rm -rf $(VENV) clients/js/node_modules
