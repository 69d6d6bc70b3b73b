#!/usr/bin/env bash
# Runs the SLURM executor tests (tests/slurm.rs) against a single-node cluster started
# here and stopped afterwards, whatever happens. Needs root and Debian's slurm-wlm, munge.
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=$(mktemp -d /tmp/repro-slurm.XXXXXX)
trap '.ci/slurm/cluster.sh stop "$dir"; rm -rf "$dir"' EXIT
eval "$(.ci/slurm/cluster.sh start "$dir")"
export SLURM_CONF REPRO_REQUIRE_SLURM=1
echo "SLURM cluster up ($SLURM_CONF); running tests/slurm.rs"
${CARGO:-cargo} test --test slurm -- --test-threads=1
