# `make figures` reproduces every figure of pipelines/thesis.yaml; `make test` runs the tests.
CARGO ?= cargo
PIPELINE ?= pipelines/thesis.yaml

.PHONY: figures test build schema clean-cache lint bench-gamma-c

build:
	$(CARGO) build

figures: build
	$(CARGO) run --quiet -- run $(PIPELINE)

test:
	$(CARGO) test

schema: build
	$(CARGO) run --quiet -- schema > pipelines/schema.json

lint:
	$(CARGO) fmt --check
	$(CARGO) clippy --all-targets -- -D warnings

clean-cache:
	rm -rf cache

# Wall time of the full gamma_c map (Fig. 3.9: fem.gamma_c over h/R x mu and the buckling
# limits) from an empty cache, release build; see README "Chapter 3: adhesion and friction".
bench-gamma-c:
	$(CARGO) build --release
	rm -rf target/bench-gamma-c
	/usr/bin/time -f "gamma_c map: %e s wall, %U s user" ./target/release/repro run $(PIPELINE) --target gamma_c_map \
		--cache target/bench-gamma-c/cache --figures target/bench-gamma-c/figures --tables target/bench-gamma-c/tables -q
