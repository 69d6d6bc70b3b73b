"""repro from Python: the solvers, the pipeline and the cache of the reproduction of
R. Nazari's thesis on adhesion and friction in soft contact mechanics.

>>> import repro
>>> repro.kinds()[:3]
['bem.maxima', 'bem.profile', 'bem.pulloff']
>>> repro.point("theory.persson", inv_k=2, V0=1)["mu_star"]
0.200392...
>>> df = repro.sweep("theory.persson", inv_k=[2, 10], V0=np.logspace(-2, 2, 9))

Every number comes from the same code as the command line's (``repro point``, ``repro
run``), and a sweep's points are cached under the keys ``repro run`` uses: a point computed
here is a cache hit there, and the other way round. docs/python.md is the guide.
"""

import io
import json
import keyword
import os
import sys
from dataclasses import dataclass, field
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _repro, errors
from .errors import (
    CacheBusy,
    CacheError,
    InvalidParameter,
    InvalidPipeline,
    NotConverged,
    ReproError,
    TaskFailed,
    UnknownKind,
    UsageError,
)

__version__ = _repro.__version__

__all__ = ["kinds", "describe", "point", "sweep", "run", "Run", "KindDescription", "Param", "Column"]
__all__ += errors.__all__

#: The cache folder used when a call names none: ``$REPRO_CACHE``, else ``cache`` in the
#: working folder (the command line's default).
DEFAULT_CACHE = "cache"


def _default_cache(cache):
    if cache is not None:
        return os.fspath(cache)
    return os.environ.get("REPRO_CACHE", DEFAULT_CACHE)


# ---------------------------------------------------------------------------------------
# Kinds


@dataclass(frozen=True)
class Param:
    """One parameter of a stage kind."""

    name: str
    type: str
    required: bool
    default: Any
    range: str
    sweepable: bool
    meaning: str


@dataclass(frozen=True)
class Column:
    """One output column of a stage kind, with its unit (``1``: dimensionless)."""

    name: str
    unit: str
    meaning: str


@dataclass(frozen=True)
class KindDescription:
    """What a stage kind takes and gives (``repro kinds KIND``)."""

    name: str
    version: int
    doc: str
    time_limit_s: float
    params: List[Param] = field(default_factory=list)
    columns: List[Column] = field(default_factory=list)

    def param(self, name: str) -> Param:
        for p in self.params:
            if p.name == name:
                return p
        raise KeyError(name)

    def column(self, name: str) -> Column:
        for c in self.columns:
            if c.name == name:
                return c
        raise KeyError(name)

    def __str__(self):
        lines = [f"{self.name} (code version {self.version}): {self.doc}", ""]
        for p in self.params:
            default = "(required)" if p.required else ("(none)" if p.default is None else repr(p.default))
            sweep = " sweepable" if p.sweepable else ""
            lines.append(f"  {p.name}: {p.type} = {default} {p.range}{sweep}  {p.meaning}")
        lines.append("")
        for c in self.columns:
            lines.append(f"  -> {c.name} [{c.unit}]  {c.meaning}")
        return "\n".join(lines)


def kinds() -> List[str]:
    """The names of the stage kinds, sorted (``repro kinds``)."""
    return list(_repro.kinds())


def describe(kind: str) -> KindDescription:
    """A kind's parameters (type, default, valid range, whether sweepable, meaning with
    units) and output columns (unit, meaning), from the declarations ``repro kinds KIND``
    prints."""
    d = json.loads(_repro.describe_json(kind))
    return KindDescription(
        name=d["name"],
        version=d["version"],
        doc=d["doc"],
        time_limit_s=d["time_limit_s"],
        params=[Param(**p) for p in d["params"]],
        columns=[Column(**c) for c in d["columns"]],
    )


# ---------------------------------------------------------------------------------------
# Parameters


def _plain(value):
    """A parameter value as JSON can hold it: NumPy arrays and scalars as lists and
    numbers, tuples as lists, mappings with string keys."""
    if hasattr(value, "tolist") and callable(value.tolist):  # NumPy arrays and scalars
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if hasattr(value, "__fspath__"):
        return os.fspath(value)
    return value


def _params(params: Optional[Mapping[str, Any]], kw: Mapping[str, Any]) -> Dict[str, Any]:
    """The parameters of a call: the dict given, then the keywords; a keyword that is a
    Python keyword spelled with a trailing underscore (``lambda_``) names the parameter
    without it."""
    out: Dict[str, Any] = {}
    for source in (params or {}, kw):
        for k, v in source.items():
            name = k[:-1] if k.endswith("_") and keyword.iskeyword(k[:-1]) else k
            if name in out:
                raise InvalidParameter(f"parameter `{name}` is given twice")
            out[name] = _plain(v)
    return out


def _json(params: Dict[str, Any]) -> str:
    try:
        # Python writes every float so that it reads back to the same bits.
        return json.dumps(params, allow_nan=False)
    except ValueError as e:
        raise InvalidParameter(f"parameters: {e} (NaN and infinity are not parameter values)") from None
    except TypeError as e:
        raise InvalidParameter(f"parameters: {e}") from None


# ---------------------------------------------------------------------------------------
# Points


def point(kind: str, params: Optional[Mapping[str, Any]] = None, /, *, raise_on_unconverged: bool = False, **kw):
    """Computes one point of ``kind``, as ``repro point`` does (the same numbers, bit for
    bit), held to the kind's time limit; no cache is read or written.

    Parameters are given as keywords (``lambda_`` for ``lambda``) or as a dict. Returns a
    dict of the output columns: numbers when the point's table has one row (most kinds),
    NumPy arrays when it has several (a shell cycle's states).

    Raises :class:`UnknownKind`, :class:`InvalidParameter`, :class:`TaskFailed`, or with
    ``raise_on_unconverged`` :class:`NotConverged` when a row did not converge. Ctrl-C
    stops the solver within a second (``KeyboardInterrupt``)."""
    cols = _repro.point(kind, _json(_params(params, kw)))
    n = len(next(iter(cols.values()), []))
    if raise_on_unconverged and "converged" in cols and not all(cols["converged"]):
        bad = [i for i, c in enumerate(cols["converged"]) if not c]
        why = sorted(set(cols["termination"][i] for i in bad)) if "termination" in cols else []
        raise NotConverged(f"{kind}: {len(bad)} of {n} rows did not converge ({', '.join(why)})", rows=bad)
    if n == 1:
        return {k: v[0] for k, v in cols.items()}
    import numpy as np

    return {k: np.asarray(v) for k, v in cols.items()}


# ---------------------------------------------------------------------------------------
# Tables


def _frame(parquet: bytes, backend: str):
    """A table's Parquet bytes as a DataFrame, with the units and meanings of its columns
    (``df.attrs["units"]``, ``df.attrs["meanings"]`` for pandas; the file's ``repro.*``
    metadata on the Arrow schema)."""
    import pyarrow.parquet as pq

    file = pq.ParquetFile(io.BytesIO(parquet))
    meta = {k.decode(): v.decode() for k, v in (file.metadata.metadata or {}).items() if k.startswith(b"repro.")}
    # The file's key-value metadata (units, meanings, parameters) kept on the Arrow schema.
    table = file.read()
    table = table.replace_schema_metadata({**(table.schema.metadata or {}), **{k: v for k, v in meta.items()}})
    columns = json.loads(meta.get("repro.columns", "{}"))
    if backend == "arrow":
        return table
    if backend == "polars":
        import polars as pl

        return pl.from_arrow(table)
    if backend != "pandas":
        raise ValueError(f"backend must be 'pandas', 'polars' or 'arrow', not {backend!r}")
    df = table.to_pandas()
    df.attrs["units"] = {k: v.get("unit", "") for k, v in columns.items()}
    df.attrs["meanings"] = {k: v.get("meaning", "") for k, v in columns.items()}
    df.attrs["params"] = json.loads(meta.get("repro.params", "{}"))
    df.attrs["code_version"] = meta.get("repro.code_version", "")
    return df


def _in_jupyter() -> bool:
    shell = sys.modules.get("IPython")
    try:
        return shell is not None and shell.get_ipython() is not None and "IPKernelApp" in shell.get_ipython().config
    except Exception:
        return False


class _Progress:
    """A tqdm bar (terminal or Jupyter) fed by the task counter of a run; with no tqdm,
    the command line's own bars in a terminal; silent otherwise or when asked."""

    def __init__(self, progress: Optional[bool], desc: str):
        self.bar = None
        self.native = False
        if progress is False:
            return
        interactive = progress is True or _in_jupyter() or sys.stderr.isatty()
        if not interactive:
            return
        try:
            from tqdm.auto import tqdm
        except ImportError:
            self.native = sys.stderr.isatty()
            return
        self.bar = tqdm(total=0, desc=desc, unit="task", leave=False)

    def callback(self):
        if self.bar is None:
            return None

        def update(done, total):
            self.bar.total = total
            self.bar.n = done
            self.bar.refresh()

        return update

    def close(self):
        if self.bar is not None:
            self.bar.close()


def _report(report_json: str) -> dict:
    return json.loads(report_json)


def _unconverged(df, what: str):
    if "converged" in getattr(df, "columns", []):
        bad = df[~df["converged"].astype(bool)]
        if len(bad):
            why = sorted(set(bad["termination"])) if "termination" in bad.columns else []
            raise NotConverged(f"{what}: {len(bad)} of {len(df)} rows did not converge ({', '.join(why)})", rows=bad)


def sweep(
    kind: str,
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Union[str, os.PathLike, None] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = "pandas",
    raise_on_unconverged: bool = False,
    wait: bool = True,
    **kw,
):
    """Computes ``kind`` over every combination of its swept parameters, in parallel
    (without the GIL), each point cached in ``cache`` under the key ``repro run`` gives it.

    A sweepable parameter (``describe(kind)``) may be a list, a NumPy array or a pipeline
    sweep (``{"logspace": [-3, 3, 61]}``, ``{"linspace": [a, b, n]}``); the others take
    one value. Returns a DataFrame (``backend``: ``"pandas"``, ``"polars"`` or
    ``"arrow"``) with one row per point (several for a kind whose points are curves), the
    kind's columns (``error_estimate``, ``converged`` and ``termination`` where the kind
    writes them), and each row's ``task_key``, ``code_version`` and ``wall_time_s``; for
    pandas, ``df.attrs`` holds the columns' ``units`` and ``meanings`` and the ``report``
    of the run (which points were computed, which came from the cache, and why).

    Another process holding the cache is waited for; with ``wait=False``,
    :class:`CacheBusy` is raised instead. Raises :class:`InvalidParameter` before any work,
    :class:`TaskFailed` if a point failed (the others are cached), :class:`NotConverged`
    if asked and a row did not converge. Ctrl-C stops within a second: finished points stay cached, a rerun computes
    the rest."""
    bar = _Progress(progress, kind)
    try:
        report_json, tables, failures = _repro.sweep(
            kind,
            _json(_params(params, kw)),
            _default_cache(cache),
            jobs,
            bar.native,
            bar.callback(),
            wait,
        )
    finally:
        bar.close()
    report = _report(report_json)
    if failures:
        raise TaskFailed(f"{kind}: {len(failures)} point(s) failed:\n  " + "\n  ".join(failures), failures)
    df = _frame(tables[kind], backend)
    if backend == "pandas":
        df.attrs["report"] = report
    if raise_on_unconverged:
        _unconverged(df if backend == "pandas" else _frame(tables[kind], "pandas"), kind)
    return df


# ---------------------------------------------------------------------------------------
# Runs


class Run:
    """A run of a pipeline: its report and the tables of the stages it completed.

    ``report`` is the run report (``repro run --report``) as a dict; ``computed``,
    ``cached`` and ``failed`` count its tasks; ``notes`` holds what its stages report at
    the end (the claims' verdict line among them); ``tables[stage]`` is a stage's table
    as a DataFrame (read when first asked for); ``published`` lists the files written."""

    report: Dict[str, Any]
    failures: List[str]

    def __init__(self, report: dict, tables: Dict[str, bytes], failures: List[str], backend: str):
        self.report = report
        self._parquet = tables
        self._frames: Dict[str, Any] = {}
        self.failures = failures
        self._backend = backend

    @property
    def stages(self) -> List[str]:
        """The stages the run completed (computed or from the cache)."""
        return list(self._parquet)

    @property
    def tables(self) -> Mapping[str, Any]:
        return _Tables(self)

    def table(self, stage: str) -> Any:
        if stage not in self._frames:
            if stage not in self._parquet:
                raise KeyError(f"stage `{stage}` did not complete in this run (completed: {', '.join(self._parquet)})")
            self._frames[stage] = _frame(self._parquet[stage], self._backend)
        return self._frames[stage]

    def _count(self, status: str) -> int:
        return sum(1 for t in self.report.get("tasks", []) if t.get("status") == status)

    @property
    def computed(self) -> int:
        return self._count("computed")

    @property
    def cached(self) -> int:
        return self._count("cached")

    @property
    def failed(self) -> int:
        return self._count("failed")

    @property
    def notes(self) -> List[str]:
        return list(self.report.get("notes", []))

    @property
    def verdict(self) -> Optional[str]:
        """The claims' verdict line (``"47 of 65 thesis claims reproduced, ..."``), when the
        run checked claims."""
        return next((n for n in self.notes if " thesis claims reproduced" in n), None)

    @property
    def published(self) -> List[str]:
        return list(self.report.get("published", []))

    @property
    def wall_time_s(self) -> float:
        return float(self.report.get("wall_time_s", 0.0))

    @property
    def claims(self) -> Any:
        """The claims checked by the run (the ``claims`` stage's table), or None."""
        return self.table("claims") if "claims" in self._parquet else None

    def __repr__(self):
        return (
            f"<repro.Run {self.report.get('pipeline')}: {self.computed} computed, {self.cached} cached, "
            f"{self.failed} failed, {len(self._parquet)} stages in {self.wall_time_s:.1f} s>"
        )


class _Tables(Mapping):
    def __init__(self, run: Run):
        self._run = run

    def __getitem__(self, stage):
        return self._run.table(stage)

    def __iter__(self):
        return iter(self._run._parquet)

    def __len__(self):
        return len(self._run._parquet)


def _override_value(v) -> str:
    return json.dumps(_plain(v), allow_nan=False)


def run(
    pipeline: Union[str, os.PathLike],
    targets: Optional[Sequence[str]] = None,
    *,
    set: Optional[Mapping[str, Any]] = None,
    cache: Union[str, os.PathLike, None] = None,
    figures: Union[str, os.PathLike, None] = None,
    tables: Union[str, os.PathLike, None] = None,
    jobs: Optional[int] = None,
    force: Sequence[str] = (),
    dry_run: bool = False,
    progress: Optional[bool] = None,
    backend: str = "pandas",
    raise_on_failure: bool = True,
    wait: bool = True,
    publish: bool = False,
) -> Run:
    """Runs a pipeline file as ``repro run`` does: its ``targets`` (every stage if none)
    and what they need, computing only what ``cache`` lacks, publishing into ``figures``
    and ``tables`` (default ``figures/`` and ``tables/``). ``set`` maps ``"stage.param"``
    to a value, as ``-S stage.param=value`` (the value a number, list, dict, or a YAML
    string); a run with ``set`` publishes into ``overrides/<pipeline>/<settings>/`` unless
    ``publish`` is true or ``figures``/``tables`` say where.

    Returns a :class:`Run`. Raises :class:`InvalidPipeline` (with each error's file, line
    and column) or :class:`UsageError` before any work; :class:`TaskFailed` (with the
    ``Run``) when a task failed, unless ``raise_on_failure`` is false; :class:`CacheBusy`
    when another process holds the cache and ``wait`` is false (else it is waited for)."""
    overrides = []
    for k, v in (set or {}).items():
        value = v if isinstance(v, str) else _override_value(v)
        overrides.append(f"{k}={value}")
    bar = _Progress(progress, os.path.basename(os.fspath(pipeline)))
    try:
        report_json, parquet, failures = _repro.run(
            os.fspath(pipeline),
            list(targets or []),
            overrides,
            _default_cache(cache),
            None if figures is None else os.fspath(figures),
            None if tables is None else os.fspath(tables),
            jobs,
            bar.native,
            dry_run,
            list(force),
            bar.callback(),
            wait,
            publish,
        )
    finally:
        bar.close()
    result = Run(_report(report_json), dict(parquet), failures, backend)
    if failures and raise_on_failure:
        raise TaskFailed(f"{len(failures)} task(s) failed:\n  " + "\n  ".join(failures), failures, run=result)
    return result
