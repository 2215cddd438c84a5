# rockarch: two commands, both create .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
OUT ?= demo-output

.PHONY: demo test test-all test-perturbed test-oldest docs bench golden lock validate clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)

# Locked versions first (requirements.lock, made by `make lock`), then rockarch itself:
# with uv (installed into .venv; a few seconds from its cache), or with pip (~50 s) where uv
# cannot be had. Then compiled to bytecode, the packages' own tests left out, and rockarch's
# sources: a process that imports rockarch starts in 1 s, not 5, even where
# PYTHONDONTWRITEBYTECODE keeps Python from writing it (docs/performance.md, "Compile time").
UV_OR_PIP = ((test -x $(BIN)/uv || $(BIN)/python -m pip install --quiet uv >/dev/null 2>&1) \
	&& $(BIN)/uv pip install --python $(BIN)/python --quiet $(1)) \
	|| $(BIN)/python -m pip install --quiet $(1)
SITE_PACKAGES = $$($(BIN)/python -c "import sysconfig; print(sysconfig.get_paths()['purelib'])")

$(VENV)/.installed: pyproject.toml requirements.lock | $(BIN)/python
	$(call UV_OR_PIP,-r requirements.lock)
	$(call UV_OR_PIP,--no-deps -e .)
	$(BIN)/python -m compileall -q -j 0 -x '[/\\]tests?[/\\]' $(SITE_PACKAGES) src >/dev/null
	touch $@

demo: $(VENV)/.installed
	$(BIN)/python examples/demo.py --out $(OUT)

# The fast suite on every core (at most 4 workers: each holds its own numba kernels), after
# the kernels are compiled once (tests/warm_kernels.py): the general contact stepper in the
# background while the suite starts with the tests that do not need it.
test: $(VENV)/.installed
	$(BIN)/ruff check src tests examples benchmarks validation
	$(BIN)/python tests/warm_kernels.py --overlap
	$(BIN)/python -m pytest -q -m "not slow" -n auto --maxprocesses 4 --dist worksteal

test-all: $(VENV)/.installed
	$(BIN)/python tests/warm_kernels.py
	$(BIN)/python -m pytest -q
	$(MAKE) docs

# The docs as a static site: site/index.html (MkDocs + Material + mkdocstrings, MathJax copied
# from a package: it opens offline). Strict: a broken link or reference fails the build.
# (NO_MKDOCS_2_WARNING silences Material's banner about its end of life, not a warning of ours.)
docs: $(VENV)/.installed-docs
	NO_MKDOCS_2_WARNING=1 $(BIN)/mkdocs build --strict --quiet
	@echo "docs: open site/index.html"

$(VENV)/.installed-docs: requirements-docs.lock | $(VENV)/.installed
	$(call UV_OR_PIP,-r requirements-docs.lock)
	touch $@

# The fast suite again with every ground motion moved in its last bit (tests/perturb/):
# results move in their last bits, as on another machine; CI runs it after `make test`.
test-perturbed: $(VENV)/.installed
	$(BIN)/python tests/warm_kernels.py
	ROCKARCH_PERTURB=1 $(BIN)/python -m pytest -q -m "not slow" -n auto --maxprocesses 4 --dist worksteal

# The fast suite on the oldest versions pyproject.toml allows (.venv-oldest, made with uv's
# lowest-direct resolution for this Python).
test-oldest: | $(BIN)/python
	$(BIN)/python -m pip install --quiet uv
	$(BIN)/uv pip compile pyproject.toml --extra test --resolution lowest-direct --quiet \
		-o .venv-oldest.lock
	test -x .venv-oldest/bin/python || $(PYTHON) -m venv .venv-oldest
	.venv-oldest/bin/python -m pip install --quiet -r .venv-oldest.lock
	.venv-oldest/bin/python -m pip install --quiet --no-deps -e .
	ROCKARCH_JIT_CACHE=.venv-oldest/jit .venv-oldest/bin/python -m pytest -q -m "not slow"

# benchmarks/qp_libraries.py and lu_choice.py measure libraries the engine does not use
# (docs/performance.md); they skip one that could not be installed.
bench: $(VENV)/.installed
	-$(BIN)/python -m pip install --quiet "clarabel==0.11.1" "osqp==1.1.3" "proxsuite==0.8.0" \
		"qdldl==0.1.9.post1" || echo "bench: could not install the QP libraries (no network?)"
	for f in benchmarks/*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

# Bit-identical guard for refactors, on this machine only (benchmarks/golden.py).
golden: $(VENV)/.installed
	$(BIN)/python benchmarks/golden.py

# Refresh requirements.lock from the ranges of pyproject.toml (Python >= 3.10, any platform).
lock: | $(BIN)/python
	$(BIN)/python -m pip install --quiet uv
	$(BIN)/uv pip compile pyproject.toml --extra test --universal --python-version 3.10 \
		--quiet -o requirements.lock
	sed -i '1i # Locked versions that `make demo` and `make test` install (rockarch itself is installed\n# from the working tree on top, without dependencies). Refresh with `make lock`.' \
		requirements.lock
	$(BIN)/uv pip compile pyproject.toml --extra docs --universal --python-version 3.10 \
		--constraint requirements.lock --no-emit-package rockarch --quiet -o requirements-docs.lock
	sed -i '1i # What `make docs` installs on top of requirements.lock. Refresh with `make lock`.' \
		requirements-docs.lock

# Oracles (docs/validation.md): Siconos (python3-siconos for /usr/bin/python3, where apt-get
# can) and LMGC90 (compas-lmgc90 in its own virtual environment .venv-lmgc90: one simulation
# per process, its Fortran state is global). Each skips cleanly where it cannot be installed.
LMGC90_VENV := .venv-lmgc90

validate: $(VENV)/.installed
	-(apt-get update -qq && apt-get install -y -qq python3-siconos) >/dev/null 2>&1 \
		|| echo "validate: could not install python3-siconos (not root or no apt)"
	-(test -x $(LMGC90_VENV)/bin/python || $(PYTHON) -m venv $(LMGC90_VENV)) \
		&& $(LMGC90_VENV)/bin/python -m pip install --quiet "compas-lmgc90==0.1.11" \
		>/dev/null 2>&1 || echo "validate: could not install compas-lmgc90 (no wheel or no network)"
	s=0; $(BIN)/python validation/siconos_compare.py || s=1; \
		$(BIN)/python validation/lmgc90_compare.py --python $(LMGC90_VENV)/bin/python || s=1; \
		exit $$s

clean:
	rm -rf $(VENV) $(LMGC90_VENV) .venv-oldest .venv-oldest.lock $(OUT) build site src/*.egg-info
