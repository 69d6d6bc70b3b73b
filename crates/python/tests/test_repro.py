"""The Python package against the command line: the same numbers, the same cache, the same
messages; interrupts leave the cache whole."""

import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import repro

from conftest import ROOT

# One point of each family: a closed form (Appendix A), the BEM (Chapter 5 pull-off), the
# shell (Chapter 3 cycle, a coarse mesh: 18 states in about 0.1 s).
POINTS = [
    ("theory.persson", {"inv_k": 2, "V0": 0.37}),
    ("bem.pulloff", {"V": 0.1, "k": 0.5, "lambda": 1}),
    ("fem.indent", {"shell": {"R": 15, "h": 1, "n_meridian": 24, "n_thickness": 2}, "delta_max": 0.1, "steps": 8}),
]


def cli_value(v):
    return json.dumps(v) if isinstance(v, (dict, list)) else str(v)


@pytest.mark.parametrize("kind,params", POINTS, ids=[k for k, _ in POINTS])
def test_point_equals_the_command_line_bit_for_bit(cli, kind, params):
    out = cli("point", kind, *[f"{k}={cli_value(v)}" for k, v in params.items()], "--json").stdout
    expected = json.loads(out)
    got = repro.point(kind, params)
    assert set(got) == set(expected)
    for name, values in expected.items():
        if name == "wall_time_s":  # a measurement, not a result
            continue
        mine = np.atleast_1d(got[name]).tolist()
        # Equality of floats, not closeness: the same code on the same parameters.
        assert mine == values, name
    assert len(expected["F_bar" if kind == "fem.indent" else "k" if kind != "theory.persson" else "mu_star"]) >= 1


def test_keywords_and_a_dict_give_the_same_point_and_lambda_is_spelled_lambda_():
    a = repro.point("bem.pulloff", V=0.1, k=0.5, lambda_=1)
    b = repro.point("bem.pulloff", {"V": 0.1, "k": 0.5, "lambda": 1})
    assert {k: v for k, v in a.items() if k != "wall_time_s"} == {k: v for k, v in b.items() if k != "wall_time_s"}
    # NumPy scalars are numbers.
    c = repro.point("theory.persson", inv_k=np.float64(2), V0=np.float32(0.5))
    assert c["V0"] == 0.5
    with pytest.raises(repro.InvalidParameter, match="given twice"):
        repro.point("bem.pulloff", {"lambda": 1}, V=0.1, k=0.5, lambda_=1)


def test_a_point_with_several_rows_gives_arrays():
    kind, params = POINTS[2]
    p = repro.point(kind, params)
    assert isinstance(p["F_bar"], np.ndarray) and p["F_bar"].shape == (18,)
    assert list(p["leg"][:2]) == ["loading", "loading"]


def test_describe_gives_parameters_and_columns_with_units():
    d = repro.describe("theory.persson")
    inv_k = d.param("inv_k")
    assert (inv_k.type, inv_k.required, inv_k.range, inv_k.sweepable) == ("number", True, "> 1", True)
    assert d.param("rel_tol").default == 1e-8
    assert d.column("mu_star").unit == "1"
    assert "Persson" in d.doc
    assert set(repro.kinds()) >= {"theory.persson", "bem.sweep", "fem.indent"}


def test_errors_carry_the_command_lines_messages(cli, tmp_path):
    p = cli("point", "theory.persson", "inv_k=-1", "V0=1", check=False)
    assert p.returncode == 2
    with pytest.raises(repro.InvalidParameter) as e:
        repro.point("theory.persson", inv_k=-1, V0=1)
    assert str(e.value) == "parameter `inv_k`: must be > 1, got -1"
    assert p.stderr.strip() == f"repro: error: {e.value}"
    with pytest.raises(repro.UnknownKind, match="unknown stage kind `theory.perss`"):
        repro.point("theory.perss", inv_k=2)
    with pytest.raises(repro.InvalidParameter, match="NaN and infinity"):
        repro.point("theory.persson", inv_k=2, V0=float("nan"))
    # A sweep's parameters are checked before any work, with the same words.
    with pytest.raises(repro.InvalidParameter, match="parameter `bogus`: unknown field `bogus`"):
        repro.sweep("theory.persson", inv_k=2, V0=[1, 2], bogus=3, cache=tmp_path / "cache")
    assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").rglob("*.json"))
    # A pipeline's errors are located as `repro run` locates them.
    bad = tmp_path / "bad.yaml"
    bad.write_text("stages:\n  - name: s\n    kind: theory.persson\n    params: {inv_k: 2, V0: [1, 2], bogus: 3}\n")
    p = cli("run", bad, "--cache", tmp_path / "c2", check=False)
    with pytest.raises(repro.InvalidPipeline) as e:
        repro.run(bad, cache=tmp_path / "c2")
    assert e.value.diagnostics[0][:3] == (str(bad), 4, 36)  # `bogus`
    assert p.stderr.startswith(f"{bad}:4:36: error: ")
    assert str(e.value) in p.stderr
    # An unknown target, with the command line's words.
    good = write_good(tmp_path)
    p = cli("run", good, "--target", "persso", "--cache", tmp_path / "c3", check=False)
    with pytest.raises(repro.UsageError) as e:
        repro.run(good, ["persso"], cache=tmp_path / "c3")
    assert "persson" in str(e.value) and p.stderr.strip() == f"repro: error: {e.value}"


def write_good(tmp_path):
    good = tmp_path / "good.yaml"
    good.write_text(
        "stages:\n  - name: persson\n    kind: theory.persson\n    params: {inv_k: [2, 10], V0: {logspace: [-2, 2, 5]}}\n"
    )
    return good


def test_a_sweep_and_a_run_share_the_cache_both_ways(cli, tmp_path):
    cache = tmp_path / "cache"
    df = repro.sweep("theory.persson", inv_k=[2, 10], V0=np.logspace(-2, 2, 5), cache=cache)
    assert len(df) == 10 and df.attrs["report"]["counts"] == {"computed": 10}
    assert df.attrs["units"]["mu_star"] == "1"
    # The same points through `repro run` (np.logspace and {logspace: ...} agree to the bit
    # here: 10^-2, 10^-1, ... as the pipeline computes them).
    good = write_good(tmp_path)
    rep = tmp_path / "run.json"
    cli("run", good, "--cache", cache, "--figures", tmp_path / "f", "--tables", tmp_path / "t", "--report", rep)
    counts = json.loads(rep.read_text())["counts"]
    assert counts == {"cached": 10}, counts
    # The other way round: points first computed by the command line are cache hits here.
    cache2 = tmp_path / "cache2"
    cli("run", good, "--cache", cache2, "--figures", tmp_path / "f", "--tables", tmp_path / "t")
    df2 = repro.sweep("theory.persson", {"inv_k": [2, 10], "V0": {"logspace": [-2, 2, 5]}}, cache=cache2)
    assert df2.attrs["report"]["counts"] == {"cached": 10}
    assert df2["mu_star"].tolist() == df["mu_star"].tolist()
    assert df2["task_key"].tolist() == df["task_key"].tolist()


def test_run_returns_the_report_and_tables(tmp_path):
    good = write_good(tmp_path)
    r = repro.run(good, cache=tmp_path / "cache", figures=tmp_path / "f", tables=tmp_path / "t", set={"persson.inv_k": 3})
    assert (r.computed, r.cached, r.failed) == (5, 0, 0)
    assert r.stages == ["persson"]
    t = r.tables["persson"]
    assert (t["inv_k"] == 3).all() and len(t) == 5
    assert r.report["overrides"] == ["persson.inv_k=3"]
    assert (tmp_path / "t" / "persson.parquet").exists()
    assert r.verdict is None  # no claims in this pipeline
    again = repro.run(good, cache=tmp_path / "cache", figures=tmp_path / "f", tables=tmp_path / "t", set={"persson.inv_k": 3})
    assert (again.computed, again.cached) == (0, 5)


def test_a_run_with_settings_publishes_apart_unless_asked(tmp_path, monkeypatch):
    # As `repro run -S`: into overrides/<pipeline>/<settings>/, never over tables/.
    monkeypatch.chdir(tmp_path)
    good = write_good(tmp_path)
    repro.run(good, cache=tmp_path / "cache", set={"persson.inv_k": 3})
    stem = os.path.splitext(os.path.basename(good))[0]
    assert (tmp_path / "overrides" / stem / "persson.inv_k=3" / "tables" / "persson.parquet").exists()
    assert not (tmp_path / "tables").exists()
    repro.run(good, cache=tmp_path / "cache", set={"persson.inv_k": 3}, publish=True)
    assert (tmp_path / "tables" / "persson.parquet").exists()


def test_a_failed_point_raises_with_its_reason_and_the_others_are_cached(tmp_path):
    with pytest.raises(repro.TaskFailed) as e:
        repro.sweep("util.fail", message="boom", x=[1, 0], cache=tmp_path / "cache")
    assert len(e.value.failures) == 1 and "boom" in e.value.failures[0]


def test_unconverged_rows_raise_only_when_asked(tmp_path):
    # The BEM at a tensile load beyond pull-off finds no state: recorded, not raised.
    df = repro.sweep("bem.sweep", V0=1, k=0.5, W=-100, cache=tmp_path / "cache", **{"lambda": 1})
    assert not df["converged"].any() and df["termination"].iloc[0] != "converged"
    with pytest.raises(repro.NotConverged) as e:
        repro.sweep("bem.sweep", V0=1, k=0.5, W=-100, cache=tmp_path / "cache", raise_on_unconverged=True, lambda_=1)
    assert len(e.value.rows) == 1


def interrupt_after(seconds):
    # Python raises KeyboardInterrupt only if SIGINT was not ignored when it started (a
    # process started in the background by a non-interactive shell inherits it ignored):
    # the handler is installed here, as an interactive session has it.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    t = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    t.start()
    return t


def test_ctrl_c_stops_a_sweep_within_a_second_and_a_rerun_completes_it(tmp_path):
    cache = tmp_path / "cache"
    # 8 points of 1 s on 2 threads: 4 s of work, interrupted after 1.5 s.
    x = list(range(8))
    interrupt_after(1.5)
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        repro.sweep("util.sleep", x=x, ms=1000, cache=cache, jobs=2, progress=False)
    assert time.monotonic() - t0 < 2.6
    # No half-written entry: each is its header line and the JSON of its own key, and no
    # temporary is left.
    entries = list(cache.rglob("*.entry"))
    assert 2 <= len(entries) <= 6, len(entries)
    for p in entries:
        header, body = p.read_text().split("\n", 1)
        assert header.startswith("repro-entry-1 ")
        assert json.loads(body)["key"] == p.stem
    assert not [p for p in cache.rglob("*.tmp")]
    df = repro.sweep("util.sleep", x=x, ms=1000, cache=cache, jobs=2, progress=False)
    counts = df.attrs["report"]["counts"]
    assert counts == {"cached": len(entries), "computed": 8 - len(entries)}, counts
    # The rerun recomputed only what was missing, none because it found an entry corrupted.
    reasons = [json.dumps(t.get("reason")) for t in df.attrs["report"]["tasks"] if t["status"] == "computed"]
    assert reasons and all("corrupt" not in r for r in reasons), reasons
    assert df["x"].tolist() == [float(v) for v in x]


def test_ctrl_c_stops_a_point():
    interrupt_after(0.5)
    t0 = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        repro.point("util.sleep", x=1, ms=20000)
    assert time.monotonic() - t0 < 1.5


def test_the_example_script_runs(tmp_path):
    script = ROOT / "docs" / "examples" / "notebook.py"
    env = {**os.environ, "MPLBACKEND": "Agg", "REPRO_CACHE": str(tmp_path / "cache")}
    p = subprocess.run([sys.executable, str(script), str(tmp_path)], capture_output=True, text=True, env=env, timeout=300)
    assert p.returncode == 0, p.stderr
    assert (tmp_path / "notebook.png").exists()


def test_the_type_stubs_are_current_and_declare_every_public_name():
    from repro import _stubs

    committed = (ROOT / "crates" / "python" / "python" / "repro" / "__init__.pyi").read_text()
    assert committed == _stubs.render(), "regenerate: python3 -m repro._stubs > crates/python/python/repro/__init__.pyi"
    for name in repro.__all__:
        assert f"def {name}(" in committed or f"class {name}" in committed or f" as {name}," in committed, name
    # Each kind's parameters are keywords of its overload, `lambda` as `lambda_`.
    assert 'kind: Literal["bem.pulloff"]' in committed and "lambda_: float = ..." in committed


def test_progress_reaches_a_tqdm_bar_task_by_task(tmp_path, monkeypatch):
    import types

    seen = []

    class FakeBar:
        def __init__(self, total, desc, unit, leave):
            self.total, self.n, self.closed = total, 0, False

        def refresh(self):
            seen.append((self.n, self.total))

        def close(self):
            self.closed = True

    fake = types.ModuleType("tqdm.auto")
    fake.tqdm = FakeBar
    monkeypatch.setitem(sys.modules, "tqdm", types.ModuleType("tqdm"))
    monkeypatch.setitem(sys.modules, "tqdm.auto", fake)
    repro.sweep("util.sleep", x=[1, 2, 3, 4], ms=150, cache=tmp_path / "cache", jobs=2, progress=True)
    assert seen[-1] == (4, 4), seen
    assert all(b >= a for a, b in zip([n for n, _ in seen], [n for n, _ in seen][1:]))
    # Silent when asked.
    seen.clear()
    repro.sweep("util.sleep", x=[5, 6], cache=tmp_path / "cache", progress=False)
    assert seen == []


def test_a_busy_cache_is_waited_for_or_refused(repro_bin, tmp_path):
    good = tmp_path / "slow.yaml"
    good.write_text("stages:\n  - name: slow\n    kind: util.sleep\n    params: {x: [1, 2], ms: 1500}\n")
    cache = tmp_path / "cache"
    holder = subprocess.Popen([repro_bin, "run", str(good), "-q", "--cache", str(cache), "--figures", str(tmp_path / "f"), "--tables", str(tmp_path / "t")])
    try:
        time.sleep(0.5)
        with pytest.raises(repro.CacheBusy, match="pid"):
            repro.sweep("util.sleep", x=3, cache=cache, wait=False)
        # Waited for: the holder's points are then cache hits.
        df = repro.sweep("util.sleep", x=[1, 2], ms=1500, cache=cache)
        assert df.attrs["report"]["counts"] == {"cached": 2}
    finally:
        holder.wait(timeout=60)


def test_tables_as_polars_and_arrow(tmp_path):
    pl = pytest.importorskip("polars")
    df = repro.sweep("theory.persson", inv_k=2, V0=[0.5, 1], cache=tmp_path / "cache", backend="polars")
    assert isinstance(df, pl.DataFrame) and df["mu_star"].len() == 2
    t = repro.sweep("theory.persson", inv_k=2, V0=[0.5, 1], cache=tmp_path / "cache", backend="arrow")
    assert t.num_rows == 2 and b"repro.columns" in t.schema.metadata
