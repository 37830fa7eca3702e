# `make demo` and `make test` work on a fresh machine with Python 3.11 and make:
# they create .venv, install kinelab into it (with the versions in constraints.txt) and run.
PYTHON ?= $(shell command -v python3.11 || command -v python3)
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed
CONSTRAINTS := constraints.txt
# the newest versions pip resolves today, in a virtual environment of their own
LATEST := .venv-latest

.PHONY: demo test test-latest lock bench docs clean

$(STAMP): pyproject.toml $(CONSTRAINTS)
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -c $(CONSTRAINTS) -e ".[dev]"
	touch $(STAMP)

# kinelab's modules compiled to bytecode, as pip compiles an installed package: an editable
# install leaves that to the first import of each module, and where PYTHONDONTWRITEBYTECODE
# is set nothing keeps it, so that every command would compile the modules it imports
# (a third of `kinelab check`'s time)
BYTECODE := $(VENV)/.bytecode

$(BYTECODE): $(STAMP) $(shell find kinelab -name '*.py')
	$(BIN)/python -m compileall -q kinelab
	touch $(BYTECODE)

DEMO := examples/crank_rocker.toml

demo: $(STAMP) $(BYTECODE)
	$(BIN)/kinelab check $(DEMO)
	$(BIN)/kinelab analyze $(DEMO) --out out/
	$(BIN)/kinelab plot $(DEMO) --out out/
	$(BIN)/kinelab animate $(DEMO) --out out/ --format gif

test: $(STAMP) $(BYTECODE)
	$(BIN)/python -m pytest

# The suite against the newest release of every dependency (no constraints): a new release
# that breaks kinelab shows up here as a failing run.
test-latest:
	rm -rf $(LATEST)
	$(PYTHON) -m venv $(LATEST)
	$(LATEST)/bin/python -m pip install --quiet --upgrade pip
	$(LATEST)/bin/python -m pip install --quiet --upgrade -e ".[dev]"
	$(LATEST)/bin/python -m pip freeze --exclude-editable > $(LATEST)/versions.txt
	$(LATEST)/bin/python -m pytest -p no:cacheprovider

# Refresh constraints.txt to the newest versions, once the suite passes with them.
lock: test-latest
	{ sed -n '/^#/p' $(CONSTRAINTS); cat $(LATEST)/versions.txt; } > $(CONSTRAINTS).new
	mv $(CONSTRAINTS).new $(CONSTRAINTS)

# The documentation site, in English and Portuguese (docs/site/, one configuration for both):
# warnings are errors, and the figures and examples run as the pages are built.  Not nitpicky
# (-n): the docstrings name numpy's and the standard library's types, which an offline build
# cannot resolve.
DOCS := docs/_build/html
SPHINX := $(BIN)/sphinx-build -W --keep-going -q -c docs/site

docs: $(STAMP)
	$(SPHINX) -D language=en docs/site/en $(DOCS)/en
	$(SPHINX) -D language=pt docs/site/pt $(DOCS)/pt
	cp docs/site/index.html $(DOCS)/index.html

bench: $(STAMP)
	for f in benchmarks/*.py; do $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) $(LATEST) out .pytest_cache .hypothesis docs/_build
