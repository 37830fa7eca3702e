# `make demo` and `make test` work on a fresh machine with Python 3.11 and make:
# they create .venv, install kinelab into it and run.
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test bench clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e ".[dev]"
	touch $(STAMP)

DEMO := examples/crank_rocker.toml

demo: $(STAMP)
	$(BIN)/kinelab check $(DEMO)
	$(BIN)/kinelab analyze $(DEMO) --out out/
	$(BIN)/kinelab plot $(DEMO) --out out/
	$(BIN)/kinelab animate $(DEMO) --out out/ --format gif

test: $(STAMP)
	$(BIN)/python -m pytest

bench: $(STAMP)
	for f in benchmarks/*.py; do $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) out .pytest_cache .hypothesis
