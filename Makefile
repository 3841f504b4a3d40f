# The two commands of the README: `make run` and `make test`. Both install what is
# missing first (idempotent: stamps make the second run quick).

PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PY_STAMP  := $(VENV)/.installed
JS_STAMP  := clients/js/node_modules/.installed
CHROMIUM  := /usr/bin/chromium
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)
HOST ?= 127.0.0.1
PORT ?= 8000

.PHONY: run test bench install clean

run: install
	$(BIN)/vp-server --host $(HOST) --port $(PORT)

test: install $(CHROMIUM)
	$(BIN)/python -m pytest $(PYTEST_ARGS)

bench: install
	$(BIN)/python bench/tick.py
	$(BIN)/python bench/sensing.py
	$(BIN)/python bench/viewer_latency.py
	$(BIN)/python bench/flood.py

install: $(PY_STAMP) $(JS_STAMP)

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

$(PY_STAMP): $(BIN)/python pyproject.toml requirements-dev.txt clients/python/pyproject.toml
	$(BIN)/python -m pip install --quiet --disable-pip-version-check \
		-r requirements-dev.txt -e . -e clients/python
	touch $@

# three.js, lil-gui and ws: the JavaScript client's dependencies (Node), also served to
# browsers by the server (the viewer and the client share them).
$(JS_STAMP): clients/js/package.json clients/js/package-lock.json
	cd clients/js && npm ci --no-audit --no-fund --loglevel=error
	touch $@

# The browser tests drive Debian's chromium (headless, software WebGL).
$(CHROMIUM):
	$(SUDO) apt-get update -q
	DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -q --no-install-recommends chromium

clean:
	rm -rf $(VENV) clients/js/node_modules
