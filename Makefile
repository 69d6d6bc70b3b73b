# `make figures` reproduces every figure of pipelines/thesis.yaml; `make test` runs the tests.
CARGO ?= cargo
PIPELINE ?= pipelines/thesis.yaml

PYTHON ?= python3
PYENV ?= target/python

.PHONY: python-test coverage figures test build schema schema-check clean-cache lint bench bench-chapter3 bench-gamma-c validate-shell verify report report-check readme-example

build:
	$(CARGO) build

figures: build
	$(CARGO) run --quiet -- run $(PIPELINE)

# The SLURM executor tests need a cluster: .ci/slurm/test.sh starts a single-node one (root,
# Debian's slurm-wlm and munge; .ci/run installs them and sets REPRO_REQUIRE_SLURM=1).
test:
	env -u REPRO_REQUIRE_SLURM $(CARGO) test
	@if [ "$$(id -u)" = 0 ] && command -v slurmctld >/dev/null 2>&1 && command -v munged >/dev/null 2>&1; then \
		CARGO=$(CARGO) .ci/slurm/test.sh; \
	elif [ -n "$$REPRO_REQUIRE_SLURM" ]; then \
		echo "make test: REPRO_REQUIRE_SLURM is set but SLURM (slurm-wlm, munge) is not installed or this is not root" >&2; exit 1; \
	else \
		echo "make test: SLURM executor tests skipped (need root and Debian's slurm-wlm and munge; .ci/run installs them)"; \
	fi
	$(MAKE) python-test

# The Python package (crates/python, docs/python.md): built by maturin (from PyPI) into a
# virtual environment of its own, sharing the workspace's dependency build (target/debug),
# then its tests (pytest) against the command line and the example script.
python-test: build
	[ -x $(PYENV)/bin/python ] || $(PYTHON) -m venv --system-site-packages $(PYENV)
	$(PYENV)/bin/python -m pip install --quiet --disable-pip-version-check ./crates/python pytest numpy pandas pyarrow polars matplotlib
	REPRO_BIN=$(CURDIR)/target/debug/repro $(PYENV)/bin/python -m pytest -q crates/python/tests

# Every committed figure is what the code produces: the pipeline regenerated from an empty
# cache into target/artifacts (figures, tables, the run report), then compared with the
# committed figures/ (SVGs byte for byte, Parquet tables value by value).
ARTIFACTS ?= target/artifacts
verify: build
	rm -rf $(ARTIFACTS)
	$(CARGO) run --quiet -- run $(PIPELINE) -q --cache $(ARTIFACTS)/cache --figures $(ARTIFACTS)/figures \
		--tables $(ARTIFACTS)/tables --report $(ARTIFACTS)/run.json
	$(CARGO) run --quiet -- verify $(ARTIFACTS)/figures figures

# The reproduction report of the last run: report/index.html (open it from disk).
report: build
	$(CARGO) run --quiet -- report $(PIPELINE)

# The report of `make verify`'s run, loaded in headless Chromium (Debian's chromium, npm's
# playwright-core): every figure and claim rendered, no request left the page, a screenshot
# in $(ARTIFACTS)/report/screenshot.png.
report-check: build
	$(CARGO) run --quiet -- report $(PIPELINE) --cache $(ARTIFACTS)/cache --figures $(ARTIFACTS)/figures \
		--tables $(ARTIFACTS)/tables --out $(ARTIFACTS)/report/index.html
	mkdir -p target/report-check && cp .ci/report_check.mjs target/report-check/
	cd target/report-check && { [ -d node_modules/playwright-core ] || npm install --silent --no-save --no-package-lock playwright-core@1; }
	node target/report-check/report_check.mjs $(ARTIFACTS)/report/index.html $(PIPELINE) $(ARTIFACTS)/report/screenshot.png

# The README's pandas example, run against the tables of `make verify`'s run (needs pandas
# and pyarrow: pip install pandas pyarrow).
readme-example:
	python3 -c "import re,sys; t=open('README.md').read(); sys.stdout.write(re.search(r'\`\`\`python\n(.*?)\`\`\`', t, re.S).group(1))" > target/readme_example.py
	cd $(ARTIFACTS) && python3 $(CURDIR)/target/readme_example.py

schema: build
	$(CARGO) run --quiet -- schema > pipelines/schema.json

# pipelines/schema.json and the tool agree (Python's jsonschema and PyYAML): every pipeline
# of pipelines/ passes both, every file of .ci/schema/wrong/ fails both.
schema-check: build
	python3 .ci/schema/check.py target/debug/repro

lint:
	$(CARGO) fmt --check
	$(CARGO) clippy --all-targets -- -D warnings

# The Chapter 3 shell against CalculiX (Debian's calculix-ccx; a few minutes): the same
# mesh, St Venant-Kirchhoff law, apex force and penalty; prints the force path and the snap of
# both (docs/shell.md, "Validation against CalculiX").
validate-shell: build
	@command -v ccx >/dev/null 2>&1 || { echo "validate-shell needs CalculiX: apt-get install calculix-ccx" >&2; exit 1; }
	python3 validation/calculix/shell.py --out target/validate-shell --repro target/debug/repro

clean-cache:
	rm -rf cache

# Wall time of the full gamma_c map (Fig. 3.9: fem.gamma_c over h/R x mu and the buckling
# limits) from an empty cache, release build; see docs/shell.md, "Cost".
bench-gamma-c:
	$(CARGO) build --release
	rm -rf target/bench-gamma-c
	/usr/bin/time -f "gamma_c map: %e s wall, %U s user" ./target/release/repro run $(PIPELINE) --target gamma_c_map \
		--cache target/bench-gamma-c/cache --figures target/bench-gamma-c/figures --tables target/bench-gamma-c/tables -q

# Chapter 3's stages (every fem.* stage of the thesis pipeline) from an empty cache, in the
# profile `make figures` builds: the run's summary gives each stage's task time (docs/shell.md,
# "Cost").
CHAPTER3 = shell_mesh shell_indent shell_profile shell_indent_adhesive shell_indent_adhesive_energy \
	shell_gamma shell_mu buckling_vs_mu buckling_vs_gamma exp_rough exp_moderate exp_smooth \
	imperfection_apex \
	imperfection_dimple imperfection_perfect shell_material shell_material_svk shell_material_hencky \
	gamma_c buckling_limit gamma_c_map
bench-chapter3: build
	rm -rf target/bench-chapter3
	$(CARGO) run --quiet -- run $(PIPELINE) $(addprefix --target ,$(CHAPTER3)) --cache target/bench-chapter3/cache \
		--figures target/bench-chapter3/figures --tables target/bench-chapter3/tables --report target/bench-chapter3/run.json

# Run time against error (pipelines/bench.yaml: figures/bench_bem.svg, bench_bem24.svg, bench_fem.svg, bench_pulloff.svg and
# tables/pareto_*.parquet) on an empty cache so that every wall time is measured, the full
# stress grid (pipelines/stress.yaml: tables/stress_summary.parquet; its lambda = 30 point
# alone takes about 9 min on 2 cores; everything else about 2 min), then the
# micro-benchmarks and the orchestrator's scale benchmark.
bench:
	$(CARGO) build --release
	rm -rf target/bench-cache
	/usr/bin/time -f "bench pipeline: %e s wall" ./target/release/repro run pipelines/bench.yaml --cache target/bench-cache -q
	/usr/bin/time -f "stress grid: %e s wall" ./target/release/repro run pipelines/stress.yaml --cache target/bench-cache -q
	./target/release/repro show tables/stress_summary.parquet
	./target/release/repro show tables/pareto_bem.parquet --columns config,rel_error,wall_time_s,on_front,meets_tolerance
	./target/release/repro show tables/pareto_bem24.parquet --columns config,rel_error,wall_time_s,on_front,meets_tolerance
	./target/release/repro show tables/pareto_fem.parquet --columns config,rel_error,wall_time_s,on_front,meets_tolerance
	$(CARGO) bench --bench micro
	$(CARGO) bench --bench scale

# The BEM error estimate against the actual error over 225 points (lambda 0.1-10, W 0.1-10,
# k 0.01-0.5, V0 0.01-100; about 6 minutes on 2 cores): pipelines/coverage.yaml, its counts
# in target/coverage/tables/coverage.parquet (estimate_covers, error_over_estimate).
coverage: build
	$(CARGO) run --quiet -- run pipelines/coverage.yaml -q --cache target/coverage/cache \
		--figures target/coverage/figures --tables target/coverage/tables
