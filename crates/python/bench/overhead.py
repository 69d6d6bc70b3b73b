"""The binding's overhead (docs/performance.md, "From Python"): the 61-point BEM curve
mu*(V0) at lambda = 1, W = 1, k = 0.1 (V0 = 1e-3..1e3) through `repro.sweep` and through
`repro run`, from an empty cache (computed) and from a full one (cached), and as 61 calls
of `repro.point`; the median of REPEATS runs of each.

Run: python3 crates/python/bench/overhead.py [path/to/repro]   (after `make python-test`,
with target/python/bin/python)
"""

import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import repro

REPEATS = 5
ROOT = pathlib.Path(__file__).resolve().parents[3]
BIN = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target" / "debug" / "repro")
PARAMS = {"lambda": 1, "W": 1, "k": 0.1, "V0": {"logspace": [-3, 3, 61]}}
PIPELINE = "stages:\n  - name: curve\n    kind: bem.sweep\n    params: {lambda: 1, W: 1, k: 0.1, V0: {logspace: [-3, 3, 61]}}\n"


def timed(f):
    t = time.perf_counter()
    f()
    return time.perf_counter() - t


def median(f, fresh):
    times = []
    for _ in range(REPEATS):
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            if not fresh:
                f(d)  # fill the cache
            times.append(timed(lambda: f(d)))
    return statistics.median(times)


def cli(d):
    (d / "p.yaml").write_text(PIPELINE)
    args = [BIN, "run", str(d / "p.yaml"), "-q", "--cache", str(d / "cache"), "--figures", str(d / "f"), "--tables", str(d / "t")]
    subprocess.run(args, check=True, capture_output=True)


def sweep(d):
    df = repro.sweep("bem.sweep", PARAMS, cache=d / "cache", progress=False)
    assert len(df) == 61


def points(d):
    for v0 in np.logspace(-3, 3, 61):
        repro.point("bem.sweep", {**PARAMS, "V0": v0})


rows = [
    ("repro run (command line), computed", median(cli, True)),
    ("repro.sweep, computed", median(sweep, True)),
    ("61 x repro.point (no cache)", median(points, True)),
    ("repro run (command line), cached", median(cli, False)),
    ("repro.sweep, cached", median(sweep, False)),
]
print("| path | wall time (median of 5) | per point |")
print("|---|---|---|")
for name, t in rows:
    print(f"| {name} | {t:.3f} s | {1000 * t / 61:.2f} ms |")
