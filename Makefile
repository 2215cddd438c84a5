# rockarch: two commands, both create .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
OUT ?= demo-output

.PHONY: demo test test-all bench validate clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e ".[test]"
	touch $@

demo: $(VENV)/.installed
	$(BIN)/python examples/demo.py --out $(OUT)

test: $(VENV)/.installed
	$(BIN)/ruff check src tests examples benchmarks validation
	$(BIN)/python -m pytest -q -m "not slow"

test-all: $(VENV)/.installed
	$(BIN)/python -m pytest -q

bench: $(VENV)/.installed
	for f in benchmarks/*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

# Siconos oracle (docs/validation.md): installs python3-siconos for /usr/bin/python3 where
# apt-get can, and skips cleanly where it cannot.
validate: $(VENV)/.installed
	-(apt-get update -qq && apt-get install -y -qq python3-siconos) >/dev/null 2>&1 \
		|| echo "validate: could not install python3-siconos (not root or no apt)"
	$(BIN)/python validation/siconos_compare.py

clean:
	rm -rf $(VENV) $(OUT) build src/*.egg-info
