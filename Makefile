# `make figures` reproduces every figure of pipelines/thesis.yaml; `make test` runs the tests.
CARGO ?= cargo
PIPELINE ?= pipelines/thesis.yaml

.PHONY: figures test build schema clean-cache lint

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
