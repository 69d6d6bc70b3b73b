"""Type stubs of repro, generated from the stage kinds' declarations by
``python3 -m repro._stubs`` (do not edit)."""

import os
from dataclasses import dataclass
from typing import Any, Callable, Dict, List, Literal, Mapping, Optional, Sequence, Union, overload

import numpy as np

from .errors import (
    CacheBusy as CacheBusy,
    CacheError as CacheError,
    InvalidParameter as InvalidParameter,
    InvalidPipeline as InvalidPipeline,
    NotConverged as NotConverged,
    ReproError as ReproError,
    TaskFailed as TaskFailed,
    UnknownKind as UnknownKind,
    UsageError as UsageError,
)

__version__: str
DEFAULT_CACHE: str

@dataclass(frozen=True)
class Param:
    name: str
    type: str
    required: bool
    default: Any
    range: str
    sweepable: bool
    meaning: str

@dataclass(frozen=True)
class Column:
    name: str
    unit: str
    meaning: str

@dataclass(frozen=True)
class KindDescription:
    name: str
    version: int
    doc: str
    time_limit_s: float
    params: List[Param]
    columns: List[Column]
    def param(self, name: str) -> Param: ...
    def column(self, name: str) -> Column: ...

class Run:
    report: Dict[str, Any]
    failures: List[str]
    @property
    def stages(self) -> List[str]: ...
    @property
    def tables(self) -> Mapping[str, Any]: ...
    def table(self, stage: str) -> Any: ...
    @property
    def computed(self) -> int: ...
    @property
    def cached(self) -> int: ...
    @property
    def failed(self) -> int: ...
    @property
    def notes(self) -> List[str]: ...
    @property
    def verdict(self) -> Optional[str]: ...
    @property
    def published(self) -> List[str]: ...
    @property
    def wall_time_s(self) -> float: ...
    @property
    def claims(self) -> Any: ...

def kinds() -> List[str]: ...
def describe(kind: str) -> KindDescription: ...
def run(pipeline: Union[str, os.PathLike], targets: Optional[Sequence[str]] = None, *, set: Optional[Mapping[str, Any]] = None, cache: Union[str, os.PathLike, None] = None, figures: Union[str, os.PathLike, None] = None, tables: Union[str, os.PathLike, None] = None, jobs: Optional[int] = None, force: Sequence[str] = (), dry_run: bool = False, progress: Optional[bool] = None, backend: str = 'pandas', raise_on_failure: bool = True, wait: bool = True, publish: bool = False) -> Run: ...

Sweep = Union[float, Sequence[float], np.ndarray, Mapping[str, Any]]
Path = Union[str, os.PathLike]

@overload
def point(
    kind: Literal["bem.maxima"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V0_range: Any = ...,
    W: float = ...,
    grid: int = ...,
    half_length: Optional[float] = ...,
    k: float = ...,
    lambda_: float = ...,
    log_tol: float = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    rel_tol: Optional[float] = ...,
) -> Dict[str, Any]:
    """Chapter 4 BEM: maximum over V0 of mu* for one (lambda, W, k), by bracketing and golden-section
    search

    Parameters:
        V0_range (array; default [0.001, 1000.0]): Speeds searched, [from, to].
        W (number; required, sweepable): Dimensionless load (sweepable).
        grid (integer; default 13, 3..=1000): Log-spaced bracketing points over the range.
        half_length (number or null; default None, > 0):
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter (sweepable).
        log_tol (number; default 0.01, (0, 1)): Golden-section tolerance in log10 V0.
        n (integer or null; default None, 16..=32000): Mesh rules of each solve, as in `bem.sweep`.
        n_max (integer or null; default None, 16..=32000):
        rel_tol (number or null; default None, (0, 1)):

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        mu_star_max [1]: maximum of μ* over V0
        V0_at_max [1]: the V0 of that maximum
        mu_adh [1]: the adhesive part of μ*
        mu_comp [1]: the compressive part of μ*
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        evaluations [count]: solves made by a search (maximum, pull-off)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["bem.profile"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V0: float = ...,
    W: float = ...,
    half_length: Optional[float] = ...,
    k: float = ...,
    lambda_: float = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    newton_tol: Optional[float] = ...,
    per_decade: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    prony: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
    s: Optional[float] = ...,
    start: Optional[str] = ...,
    tau_ratio: Optional[float] = ...,
) -> Dict[str, Any]:
    """Chapter 4 BEM: pressure P(X), displacement U(X), gap H(X) and friction integrand P dU/dX of one
    point

    Parameters:
        V0 (number; required, >= 0, sweepable): Dimensionless speed V0 = v tau / a0 (Eq. 4.18; a0 the
            Hertz half-width of |W|), >= 0 (sweepable).
        W (number; required, sweepable): Dimensionless load W (Eq. 4.6), nonzero (sweepable). Negative:
            a tensile load (the cylinder beneath the substrate, Chapter 5), reached on the stable branch
            by walking down from |W| by pseudo-arclength continuation; beyond the pull-off the point is
            reported as not converged.
        half_length (number or null; default None, > 0): Half-length of the domain in units of beta;
            default: chosen from lambda, W and rel_tol (`bem::solver::domain_half_length`).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (the error is then
            estimated against n/2); default: the mesh is chosen from `rel_tol`.
        n_max (integer or null; default None, 16..=32000): The largest mesh of the refinement (default
            16000).
        newton_tol (number or null; default None, (0, 1)): Newton's tolerance on the max-norm residual
            in units of H (default 1e-9, `bem::solver::TOLERANCE`); for the accuracy-cost bench.
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh: `linear`
            between the element centres (the default: second order at every speed) or `uniform` on each
            element (the thesis' strips, Eq. 4.12: first order where the elements are longer than the
            creep length, as at low speed; docs/bem.md, "Discretisation").
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of mu* (default
            1e-3): starting from `bem::solver::starting_mesh`, the number of elements is doubled until
            the Richardson error estimate meets it, up to `n_max`.
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        start (string or null; default None): A stage of `needs` whose rows hold converged states (a
            `bem.profile`'s: `X`, `H`, `approach`), best read row by row (`needs: [{stage: S, match:
            [lambda, W, k]}]`): the refinement's first mesh starts by Newton from the state, among those
            of this lambda, W, k and material, at the speed nearest V0 (in log V0), instead of the
            continuation from the relaxed state (the continuation if that fails). mu* changes within
            Newton's tolerance only; without such rows the point is solved from scratch. Not with a
            fixed `n`.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
        X [β]: position along the interface
        P [σ0]: interface pressure P(X), compression positive
        U [β²/R]: surface displacement U(X)
        H [β²/R]: gap H(X) = (h - ε) R/β² (Eq. 4.7)
        P_dU_dX [σ0]: the friction integrand P dU/dX
        mu_integrand [1 per β]: the local contribution to μ* (Fig. 4.4's quantity)
        surface [β²/R]: the deformed surface, -U
        indenter [β²/R]: the indenter's profile X²/2 - approach
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        approach [β²/R]: approach Δ of the cylinder (Eq. 4.7)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["bem.pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V: float = ...,
    k: float = ...,
    lambda_: float = ...,
    n: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
) -> Dict[str, Any]:
    """Chapters 4-5 BEM: pull-off load (minimum W on the equilibrium branch, walked by pseudo-arclength in
    approach and load) at speed V

    Parameters:
        V (number; required, >= 0, sweepable): Speed V = v tau/beta >= 0 (sweepable): independent of the
            load, which is the unknown here; the table also gives V0 = V/a0 with a0 the Hertz half-width
            of the pull-off load.
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (default: from
            `bem::solver::starting_mesh`, doubled until the Richardson estimate of the pull-off load
            meets rel_tol).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh, as in
            `bem.sweep` (default `linear`).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of the pull-off load
            (default 1e-3).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        k [1]: modulus ratio E0/E∞
        V [1]: speed in the relaxation time of the pull-off stages
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        W_pulloff [W]: pull-off load at speed V
        A [β]: contact half-width at pull-off (gap below the separation of peak tension)
        two_A [β]: contact width 2A at pull-off (Fig. 5.8)
        x_lead [β]: leading edge of the contact
        x_trail [β]: trailing edge of the contact
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        F_T [1]: rolling friction force F_T* = μ* |W| (Eq. 5.6)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        evaluations [count]: solves made by a search (maximum, pull-off)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        half_length [β (BEM length unit)]: half-length of the BEM domain
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["bem.sweep"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V0: float = ...,
    W: float = ...,
    half_length: Optional[float] = ...,
    k: float = ...,
    lambda_: float = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    newton_tol: Optional[float] = ...,
    per_decade: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    prony: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
    s: Optional[float] = ...,
    start: Optional[str] = ...,
    tau_ratio: Optional[float] = ...,
) -> Dict[str, Any]:
    """Chapter 4 BEM: friction mu* (Eq. 4.16) of a cylinder sliding on an adhesive SLS half-plane, one
    point per task

    Parameters:
        V0 (number; required, >= 0, sweepable): Dimensionless speed V0 = v tau / a0 (Eq. 4.18; a0 the
            Hertz half-width of |W|), >= 0 (sweepable).
        W (number; required, sweepable): Dimensionless load W (Eq. 4.6), nonzero (sweepable). Negative:
            a tensile load (the cylinder beneath the substrate, Chapter 5), reached on the stable branch
            by walking down from |W| by pseudo-arclength continuation; beyond the pull-off the point is
            reported as not converged.
        half_length (number or null; default None, > 0): Half-length of the domain in units of beta;
            default: chosen from lambda, W and rel_tol (`bem::solver::domain_half_length`).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (the error is then
            estimated against n/2); default: the mesh is chosen from `rel_tol`.
        n_max (integer or null; default None, 16..=32000): The largest mesh of the refinement (default
            16000).
        newton_tol (number or null; default None, (0, 1)): Newton's tolerance on the max-norm residual
            in units of H (default 1e-9, `bem::solver::TOLERANCE`); for the accuracy-cost bench.
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh: `linear`
            between the element centres (the default: second order at every speed) or `uniform` on each
            element (the thesis' strips, Eq. 4.12: first order where the elements are longer than the
            creep length, as at low speed; docs/bem.md, "Discretisation").
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of mu* (default
            1e-3): starting from `bem::solver::starting_mesh`, the number of elements is doubled until
            the Richardson error estimate meets it, up to `n_max`.
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        start (string or null; default None): A stage of `needs` whose rows hold converged states (a
            `bem.profile`'s: `X`, `H`, `approach`), best read row by row (`needs: [{stage: S, match:
            [lambda, W, k]}]`): the refinement's first mesh starts by Newton from the state, among those
            of this lambda, W, k and material, at the speed nearest V0 (in log V0), instead of the
            continuation from the relaxed state (the continuation if that fails). mu* changes within
            Newton's tolerance only; without such rows the point is solved from scratch. Not with a
            fixed `n`.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        mu_adh [1]: the adhesive part of μ*
        mu_comp [1]: the compressive part of μ*
        F_T [1]: rolling friction force F_T* = μ* |W| (Eq. 5.6)
        x_lead [β]: leading edge of the contact
        x_trail [β]: trailing edge of the contact
        approach [β²/R]: approach Δ of the cylinder (Eq. 4.7)
        p_max_bar [σ0]: largest compressive pressure
        p_min_bar [σ0]: largest tension
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        termination [text]: why the solver stopped. `bem.sweep`: `converged`, `iteration_limit`,
            `stalled` (line searches cut the step to 1/16 several times in a row), `step_too_small` (no
            step lowered the residual), `diverged` (non-finite residual or direction), `off_branch` (a
            tensile state left the stable branch), `beyond_pull_off` (no stable state at that tensile
            load), `non_finite_friction`. `fem.indent` (per state): `converged`, `iteration_limit`,
            `no_step` (every trial step inverted an element), `no_descent` (the energy descent found no
            shift that lowers the potential), `unstable` (an equilibrium at a tangent that is not
            positive definite), `inverted` (the state could not be evaluated), `not_solved` (the
            reference state taken as the start when no adhering state was found)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        residual [units of the solved equation]: the final residual's max-norm
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        half_length [β (BEM length unit)]: half-length of the BEM domain
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        start_V0 [v τ/a0]: with `start`: the speed of the state the point's first mesh started from (-1:
            no row matched, solved from scratch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["bench.pareto"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    candidates: Any = ...,
    default: str = ...,
    error: Optional[str] = ...,
    error_resolution: float = ...,
    match: Any = ...,
    reference: str = ...,
    time_resolution: float = ...,
    tolerance: float = ...,
    value: str = ...,
) -> Dict[str, Any]:
    """Run time against error: per solver configuration, max relative error vs a reference, wall time,
    Pareto front

    Parameters:
        candidates (array; required): The configurations: stages with one row per physical point (each
            must be in `needs`).
        default (string; required): The candidate that the thesis pipeline uses (its defaults).
        error (string or null; default None): The candidates' column holding the error estimate of
            `value` (absolute, in its units), if any: each candidate is then checked against the
            reference, with the columns `estimate_covers` (the fraction of its points whose actual error
            is within the estimate) and `error_over_estimate` (the largest actual error over estimate).
        error_resolution (number; default 0.0): Relative errors within this fraction of each other count
            as equal (default 0: compared exactly).
        match (array; required): Columns that identify a physical point (matched between candidates and
            reference).
        reference (string; required): The converged reference: a stage with the same physical points.
        time_resolution (number; default 0.0): Wall times within this fraction of each other count as
            equal (default 0).
        tolerance (number; required, > 0): The declared tolerance on the relative error (e.g. 0.005).
        value (string; required): The quantity whose relative error is measured (e.g. `mu_star`,
            `F_buckling_bar`).

    Columns:
        config [text]: the configuration's parameters
        rel_error [1]: the largest relative error against the reference
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
        points [count]: points compared
        configs [count]: the configurations a `bench.pareto` table compares (every row the same)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        on_front [boolean]: on the Pareto front of error against time
        on_front_resolved [boolean]: on the front at the error resolution
        is_default [boolean]: the configuration the thesis pipeline uses
        meets_tolerance [boolean]: within it
        tolerance [1]: the declared tolerance
        value [units of the column]: the quantity measured (1/0 for increasing, decreasing)
    """

@overload
def point(
    kind: Literal["bench.summary"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    stages: Any = ...,
) -> Dict[str, Any]:
    """Summary of a stress grid: per stage points, converged, max iterations, worst residual

    Parameters:
        stages (array; required): The stages summarised (each must be in `needs`), one row each.

    Columns:
        stage [text]: the stage whose table it reads
        points [count]: points compared
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        not_converged [count]: points that did not converge
        max_iterations [count]: the largest Newton iteration count over the task's solves
        worst_residual [units of the solved equation]: the largest final residual
    """

@overload
def point(
    kind: Literal["claim"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    docs: str = ...,
    expect: Any = ...,
    id: str = ...,
    independent: Optional[Any] = ...,
    quantity: Any = ...,
    reason: str = ...,
    source: str = ...,
    statement: str = ...,
    thesis: Any = ...,
) -> Dict[str, Any]:
    """A statement of the thesis checked against a published table: the quantity, the thesis' value, the
    verdict

    Parameters:
        docs (string; default None): The docs section that explains it, e.g. `docs/shell.md#claims`.
        expect (Verdict; required): The verdict recorded at the last review: a claim recorded as
            reproduced that no longer is, is a regression.
        id (string; required): A short identifier, e.g. `ch2.jkr_pulloff`.
        independent (Independent or null; default None):
        quantity (Quantity; required): The measured quantity.
        reason (string; default None): Why the reproduction differs (required with `expect: differs`).
        source (string; required): Where the thesis states it: section, equation or figure.
        statement (string; required): The statement, in a few words.
        thesis (Expected; required): The thesis' value with the tolerance its text implies, or its
            bound.

    Columns:
        id [text]: the claim's identifier, e.g. `ch2.md_jkr_limit`
        source [text]: where the thesis states it
        statement [text]: the statement
        stage [text]: the stage whose table it reads
        column [text]: the column reduced
        aggregate [text]: how (value, max, slope, increasing, ...)
        value [units of the column]: the quantity measured (1/0 for increasing, decreasing)
        thesis [text]: the thesis' condition in words (`-1.5 ± 0.1 %`, `< 280.25`)
        thesis_value [units of the column]: its value, or a bound
        has_independent [boolean]: an independent value is given
        independent_value [units of the column]: the independent value (0 without one)
        independent_source [text]: what it is
        verdict [text]: `reproduced` or `differs`
        expected [text]: the verdict recorded at the last review
        regression [boolean]: recorded as reproduced and now differing
        reason [text]: why it differs
        docs [text]: the docs section that explains it
    """

@overload
def point(
    kind: Literal["claims"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    claims: Any = ...,
) -> Dict[str, Any]:
    """The verdicts of claim stages in one table, and the run's verdict line

    Parameters:
        claims (array; required): The `claim` stages gathered (each must be in `needs`).

    Columns:
        id [text]: the claim's identifier, e.g. `ch2.md_jkr_limit`
        verdict [text]: `reproduced` or `differs`
        expected [text]: the verdict recorded at the last review
    """

@overload
def point(
    kind: Literal["fem.buckling"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    apex_force: Optional[float] = ...,
    dimple: Optional[float] = ...,
    dissipation: bool = ...,
    gamma_over_Eh: float = ...,
    h_over_R: float = ...,
    mesh_study: bool = ...,
    model: Any = ...,
    mu: float = ...,
) -> Dict[str, Any]:
    """Chapter 3: F_buckling, delta at it and the dissipated energy W at one (h/R, gamma/(E h), mu)

    Parameters:
        apex_force (number or null; default None, sweepable): The apex force of the imperfection in
            units of F_c = E h^3 / R (sweepable; default: `model.imperfection.apex_force`).
        dimple (number or null; default None, sweepable): The dimple depth of the imperfection in units
            of h (sweepable; default: `model.imperfection.dimple`).
        dissipation (boolean; default True): Also unload, for the dissipated energy W (default true;
            false stops at the snap).
        gamma_over_Eh (number; default 0.0, >= 0, sweepable): Work of adhesion gamma/(E h) (sweepable;
            default 0).
        h_over_R (number; required, (0, 0.5), sweepable): Thickness over radius h/R (sweepable).
        mesh_study (boolean; default False): Estimate the mesh's share of the errors of F_buckling and W
            at this point by a second cycle on twice the meridian elements, run alongside (`MeshStudy`;
            default false: the declared errors of the default mesh, none on other meshes). Three to four
            times the CPU time.
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).

    Columns:
        h_over_R [1]: thickness over inner radius
        gamma_over_Eh [1]: work of adhesion over E h
        mu [1]: Coulomb friction coefficient
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        buckled [boolean]: the shell snapped through on loading
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        F_contact_buckling_bar [F_c]: contact force at the snap
        F_adhesive_buckling_bar [F_c]: adhesive pull at the snap
        F_buckling_error_bar [F_c]: its error estimate (bisection bracket and mesh)
        F_buckling_mesh_error_bar [F_c]: the mesh's share
        delta_buckling_over_R [R]: plate displacement at the snap
        delta_buckling_error_over_R [R]: its error estimate
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        delta_landing_over_R [R]: where the snap lands on the inverted branch
        W_bar [E h³ (F_c R)]: dissipated energy W = ∮ F dδ of the cycle
        W_Nmm [N mm]: the dissipated energy W in N mm
        W_error_bar [E h³]: its error estimate
        W_error_Nmm [N mm]: W's error estimate in N mm
        W_mesh_error_Nmm [N mm]: the mesh's share of W's error, in N mm
        W_friction_Nmm [N mm]: the part of W dissipated by friction, in N mm
        n_meridian [count]: elements along the meridian
        mesh_error_source [text]: where the mesh error comes from (`study`: a cycle on a mesh twice as
            fine along the meridian; `declared`: the default mesh's measured errors,
            `fem::mesh::default_mesh_rel_error` and `default_mesh_w_rel_error`; `none`)
        mesh_study_agrees [boolean]: both meshes agree on whether the shell snaps
        complete [boolean]: the cycle (or probe) reached its end
        max_iterations [count]: the largest Newton iteration count over the task's solves
        max_residual [E h^2 (shell), H (BEM)]: the largest final residual over the task's solves
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["fem.buckling_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    gamma_over_Eh: float = ...,
    h_hi: float = ...,
    h_lo: float = ...,
    model: Any = ...,
    mu: float = ...,
    tol: float = ...,
) -> Dict[str, Any]:
    """Chapter 3: the h/R above which the shell does not snap through before delta_max, by bisection

    Parameters:
        gamma_over_Eh (number; default 0.0, >= 0, sweepable): Work of adhesion gamma/(E h) (default 0).
        h_hi (number; default 0.4, (0, 0.5)):
        h_lo (number; default 0.1, (0, 0.5)): The search interval of h/R (default [0.1, 0.4]) and its
            tolerance (default 0.005).
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).
        tol (number; default 0.005, > 0):

    Columns:
        mu [1]: Coulomb friction coefficient
        gamma_over_Eh [1]: work of adhesion over E h
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        h_limit_over_R [1]: thickness above which the shell does not snap before δ_max
        h_lo_over_R [1]: the bisection's snapping end
        h_hi_over_R [1]: its non-snapping end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        buckles_at_h_lo [boolean]: the shell snaps at h_lo
        buckles_at_h_hi [boolean]: the shell snaps at h_hi
        probes [count]: loading runs made by the bracketing
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["fem.gamma_c"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    apex_force: Optional[float] = ...,
    dimple: Optional[float] = ...,
    g0: Optional[float] = ...,
    gamma_max: float = ...,
    growth: float = ...,
    guess: float = ...,
    h_over_R: float = ...,
    model: Any = ...,
    mu: float = ...,
    rel_tol: float = ...,
) -> Dict[str, Any]:
    """Chapter 3: critical adhesion gamma_c/(E h) above which the shell does not snap, by bracketing, with
    Eq. 3.7

    Parameters:
        apex_force (number or null; default None, >= 0, sweepable): The apex force of the imperfection
            in units of F_c = E h^3 / R (sweepable; default: `model.imperfection.apex_force`).
        dimple (number or null; default None, sweepable): The dimple depth of the imperfection in units
            of h (sweepable; default: `model.imperfection.dimple`).
        g0 (number or null; default None, > 0, sweepable): The Lennard-Jones range g0 in mm (sweepable;
            default: `model.g0`; the default mesh follows it), for studies of gamma_c's limit as the
            regularisation goes.
        gamma_max (number; default 0.1, > 0):
        growth (number; default 2.0, > 1):
        guess (number; default 0.02, > 0): The first gamma/(E h) tried per unit of the adhesionless
            snap's distance from delta_max: the first trial is guess (1 - delta_snap(0) / delta_max)
            (default 2e-2; `fem::critical::bracket`), the factor of the steps taken without a secant
            estimate (default 2), the largest gamma/(E h) tried (default 0.1).
        h_over_R (number; required, (0, 0.5), sweepable): Thickness over radius h/R (sweepable).
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).
        rel_tol (number; default 0.1, (0, 10)): Bracketing tolerance: the search stops when gamma_hi /
            gamma_lo - 1 < rel_tol.

    Columns:
        h_over_R [1]: thickness over inner radius
        mu [1]: Coulomb friction coefficient
        g0 [mm]: equilibrium distance (range) g0 of the Lennard-Jones law (Eqs. 3.3-3.4); the default
            mesh resolves it
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        gamma_max_over_Eh [1]: the largest γ/(E h) the bracket tries: where the shell snaps up to it,
            γ_c is only bounded below (0 on the map's rows of the buckling limit)
        n_meridian [count]: elements along the meridian
        gamma_c_over_Eh [1]: critical adhesion γ_c/(E h): above it no snap before δ_max (geometric mid
            of the bracket)
        gamma_lo_over_Eh [1]: the bracket's buckling end
        gamma_hi_over_Eh [1]: the bracket's non-buckling end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        rel_tol [1]: the requested relative accuracy
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        reliable [boolean]: both bracket ends rest on converged probes
        buckles_without_adhesion [boolean]: the shell snaps at γ = 0
        gamma_c_N_per_mm [N/mm]: γ_c in N/mm
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        eq3_7_over_Eh [1]: Eq. 3.7's estimate (r/R)⁴
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        probes [count]: loading runs made by the bracketing
        unconverged_probes [count]: those that did not converge
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["fem.gamma_c_map"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    gamma_c: str = ...,
    limit: Optional[str] = ...,
) -> Dict[str, Any]:
    """Chapter 3: the buckling map gamma_c/(E h) vs h/R per mu (Fig. 3.9), from fem.gamma_c points

    Parameters:
        gamma_c (string; required): The `fem.gamma_c` stage swept over h_over_R and mu.
        limit (string or null; default None): The `fem.buckling_limit` stage swept over mu (optional):
            each mu's boundary is closed at gamma_c = 0 there.

    Columns:
        mu [1]: Coulomb friction coefficient
        h_over_R [1]: thickness over inner radius
        gamma_c_over_Eh [1]: critical adhesion γ_c/(E h): above it no snap before δ_max (geometric mid
            of the bracket)
        gamma_lo_over_Eh [1]: the bracket's buckling end
        gamma_hi_over_Eh [1]: the bracket's non-buckling end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        h_error_over_R [1]: error of the map's h/R (the bisection's half-width; 0 for given points)
        eq3_7_over_Eh [1]: Eq. 3.7's estimate (r/R)⁴
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        reliable [boolean]: both bracket ends rest on converged probes
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        gamma_max_over_Eh [1]: the largest γ/(E h) the bracket tries: where the shell snaps up to it,
            γ_c is only bounded below (0 on the map's rows of the buckling limit)
    """

@overload
def point(
    kind: Literal["fem.indent"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    base: Any = ...,
    bisections: int = ...,
    delta_max: float = ...,
    g0: float = ...,
    gamma: float = ...,
    hold: Any = ...,
    lift_threshold: float = ...,
    mesh_study: bool = ...,
    mu: float = ...,
    penalty: float = ...,
    shell: Any = ...,
    snap: Any = ...,
    stability: Any = ...,
    steps: int = ...,
) -> Dict[str, Any]:
    """Chapter 3: load-unload cycle of a shell pressed by a rigid plate (snap-through, snap-back, unstable
    branch)

    Parameters:
        base (Support; default 'clamped'): Base support: `clamped` (default, as the experiments) or
            `roller`.
        bisections (integer; default 6, >= 0): Bisections locating the snap-through in delta (default 6:
            to steps/64).
        delta_max (number; required, (0, 1)): Largest plate displacement delta/R.
        g0 (number; default 0.1, > 0): Equilibrium distance g0 of the Lennard-Jones law (mm; default 0.1
            as the thesis).
        gamma (number; default 0.0, >= 0, sweepable): Work of adhesion dgamma of the Lennard-Jones law,
            Eq. 3.3 (N/mm; default 0).
        hold (Hold; default 'free'): What holds touching points of an adhesive contact in the stability
            test: `free` (default) or `lennard_jones` (16 dgamma / g0^2).
        lift_threshold (number; default 0.02, (0, 1)): With `stability: lift_threshold`: contact nodes
            pressed above this fraction of the peak pressure are held against lifting off, the others
            are free to (default 0.02).
        mesh_study (boolean; default False): Estimate the mesh's share of the errors of every state's
            force, F_buckling and W by a second cycle on twice the meridian elements, run alongside
            (`Cycles`; default false: the declared errors of the default mesh, none on other meshes).
            Three to four times the CPU time.
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (default 0).
        penalty (number; default 1000.0, > 0): Contact penalty in units of E/h: the penetration is about
            p h/(penalty E).
        shell (ShellParams; required): The shell and its mesh, as for `fem.mesh`.
        snap (SnapCriterion; default None): What counts as the snap-through: `instability` (default, the
            stability test), `energy` (the inverted state stores less total potential energy; the whole
            cycle, `fem::cycle::energy`) or the thesis' staggered procedure, `{thesis: {passes: n,
            first_pass: ...}}` (`map::SnapCriterion`), which runs the loading leg only (W is then 0: no
            loop).
        stability (Stability; default None): Stability test: `lift_threshold` (default) or `tangent`
            (`shell::Stability`).
        steps (integer; required, 1..=100000): Equal load steps to delta_max (and back).

    Columns:
        leg [text]: `loading`, `unloading` or `unstable` (the unstable branch traced by arc length)
        leg_id [0, 1, 2]: the leg as a number (loading 0, unloading 1, unstable 2)
        state [text]: `flattened` or `inverted` branch
        R_mm [mm]: the shell's inner radius R
        h_mm [mm]: the shell's thickness h
        h_over_R [1]: thickness over inner radius
        gamma [N/mm]: work of adhesion Δγ
        mu [1]: Coulomb friction coefficient
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        delta_over_R [R]: plate displacement δ/R
        F_bar [F_c]: net plate force (contact minus adhesion), the force the figures draw
        F_error_bar [F_c]: the mesh's share of its error
        F_contact_bar [F_c]: the compressive contact force alone
        F_adhesive_bar [F_c]: the adhesive pull (negative); F_bar = F_contact_bar + F_adhesive_bar
        slip_fraction [1]: fraction of the contact nodes that slip
        p_max_over_E [E]: peak contact pressure
        p_apex_over_E [E]: contact pressure at the apex (0 once the contact is a ring)
        A_bar [Maugis' A]: contact radius
        contact_radius_over_R [R]: outermost contact radius
        max_penetration_over_h [h]: largest penetration of the penalty contact
        stable [boolean]: the state is stable under prescribed δ
        held [boolean]: a flattened state past the stability test with no inverted state reachable: the
            shell stays there
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        termination [text]: why the solver stopped. `bem.sweep`: `converged`, `iteration_limit`,
            `stalled` (line searches cut the step to 1/16 several times in a row), `step_too_small` (no
            step lowered the residual), `diverged` (non-finite residual or direction), `off_branch` (a
            tensile state left the stable branch), `beyond_pull_off` (no stable state at that tensile
            load), `non_finite_friction`. `fem.indent` (per state): `converged`, `iteration_limit`,
            `no_step` (every trial step inverted an element), `no_descent` (the energy descent found no
            shift that lowers the potential), `unstable` (an equilibrium at a tangent that is not
            positive definite), `inverted` (the state could not be evaluated), `not_solved` (the
            reference state taken as the start when no adhering state was found)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        residual [units of the solved equation]: the final residual's max-norm
        buckled [boolean]: the shell snapped through on loading
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        F_buckling_error_bar [F_c]: its error estimate (bisection bracket and mesh)
        F_buckling_mesh_error_bar [F_c]: the mesh's share
        delta_buckling_over_R [R]: plate displacement at the snap
        delta_landing_over_R [R]: where the snap lands on the inverted branch
        delta_snap_back_over_R [R]: where the shell snaps back on unloading
        W_bar [E h³ (F_c R)]: dissipated energy W = ∮ F dδ of the cycle
        W_error_bar [E h³]: its error estimate
        W_mesh_error_bar [E h³]: the mesh's share
        W_friction_bar [E h³]: the part of W dissipated by friction
        n_meridian [count]: elements along the meridian
        mesh_error_source [text]: where the mesh error comes from (`study`: a cycle on a mesh twice as
            fine along the meridian; `declared`: the default mesh's measured errors,
            `fem::mesh::default_mesh_rel_error` and `default_mesh_w_rel_error`; `none`)
        mesh_study_agrees [boolean]: both meshes agree on whether the shell snaps
        complete [boolean]: the cycle (or probe) reached its end
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["fem.mesh"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    E: float = ...,
    R: float = ...,
    grading: float = ...,
    h: float = ...,
    imperfection: Any = ...,
    integration: Any = ...,
    material: Any = ...,
    n_meridian: Optional[int] = ...,
    n_thickness: int = ...,
    nu: float = ...,
) -> Dict[str, Any]:
    """Chapter 3: the meridian mesh of a hemispherical shell (8-node elements), one row per node

    Parameters:
        E (number; default 1.3, > 0): Young's modulus E (N/mm^2), default 1.3.
        R (number; required, > 0): Inner radius R (mm).
        grading (number; default 3.0, > 0): Ratio of the last to the first element size along the
            meridian (default 3: fine enough at the apex for the first contact, and at r ~ 0.6 R for the
            inverted state's ring).
        h (number; required, > 0): Thickness h (mm).
        imperfection (Imperfection; default None): Imperfection: `{apex_force: F/F_c, dimple: depth/h,
            width: /sqrt(R h)}` (default none).
        integration (Integration; default None): Gauss rule of the elements: `full` (3 x 3, default) or
            `reduced` (2 x 2, ANSYS PLANE183's).
        material (MaterialLaw; default None): Hyperelastic law: `neo_hookean` (default),
            `saint_venant_kirchhoff` or `hencky`.
        n_meridian (integer or null; default None, 4..=20000): Elements along the meridian (default: 1.5
            (R + h) / g0, so that the elements at the contact rim resolve the Lennard-Jones range g0;
            `fem::mesh::meridian_elements`) and through the thickness (default 2: quadratic elements
            carry the bending exactly).
        n_thickness (integer; default 2, 1..=16):
        nu (number; default 0.45, (-1, 0.5)): Poisson's ratio, default 0.45.

    Columns:
        r [mm]: node radius (`fem.mesh`)
        z [mm]: node height (`fem.mesh`)
        axis [boolean]: the node lies on the axis
        base [boolean]: the node lies on the clamped base
        outer [boolean]: the node lies on the outer surface
    """

@overload
def point(
    kind: Literal["fem.profile"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    cycle: Any = ...,
    points: Any = ...,
) -> Dict[str, Any]:
    """Chapter 3: deformed meridian (outer and inner surface) and contact pressure at chosen plate
    displacements

    Parameters:
        cycle (IndentParams; required): The cycle, as the parameters of `fem.indent` (only its loading
            leg is computed, to the largest `points` delta if that is smaller than delta_max).
        points (array; required): The states to draw.

    Columns:
        label [text]: the named plate displacement of a profile (`fem.profile`)
        point [count]: the point's index along the surface
        surface_id [0, 1]: outer (0) or inner (1) surface
        delta_over_R [R]: plate displacement δ/R
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        z_over_R [R]: height of a surface point
        p_over_E [E]: contact pressure at a surface point
        contact [0 or 1]: the point touches the plate
        inverted [boolean]: the state is on the inverted branch
        F_bar [F_c]: net plate force (contact minus adhesion), the force the figures draw
        F_contact_bar [F_c]: the compressive contact force alone
        F_error_bar [F_c]: the mesh's share of its error
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def point(
    kind: Literal["figure"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    height: int = ...,
    layers: Any = ...,
    legend: Any = ...,
    log_x: bool = ...,
    log_y: bool = ...,
    title: str = ...,
    width: int = ...,
    x_label: str = ...,
    x_range: Optional[Any] = ...,
    y_label: str = ...,
    y_range: Optional[Any] = ...,
) -> Dict[str, Any]:
    """An x-y figure (SVG) of columns of the needed stages, with its data as a long table

    Parameters:
        height (integer; default 560, >= 0):
        layers (array; required):
        legend (LegendPosition; default 'auto'):
        log_x (boolean; default False):
        log_y (boolean; default False):
        title (string; required):
        width (integer; default 800, >= 0):
        x_label (string; required): Axis label, with units or the dimensionless symbol.
        x_range (array or null; default None): Axis ranges (data units); default: the data's extent.
            `x_range` is also the range this figure shows of each data layer's `x` column: a sweep of
            that parameter may sample it (`{shown: n}`) and is checked against it.
        y_label (string; required):
        y_range (array or null; default None):

    Columns:
        series [text]: the curve's legend label
        x [`x_unit`]: the plotted abscissa
        y [`y_unit`]: the plotted ordinate
        x_name [text]: the table column plotted as x
        y_name [text]: the table column plotted as y (`guide` for guide lines)
        x_unit [text]: the unit of `x`: that of the column plotted (this file), the axis' for guide and
            fit lines
        y_unit [text]: the unit of `y`, likewise
        group_by [text]: the table column a layer groups its rows by (empty for an ungrouped series; the
            columns appear where some layer groups)
        group [text]: the point's group value as shown in the legend (empty for an ungrouped series)
        group_value [units of the group column]: the group value as a number, for filtering (0 for text
            groups and ungrouped series)
        group_unit [text]: the unit of the group column (docs/outputs.md; empty for ungrouped series and
            undocumented columns)
        y_error [units of y]: the error bar's half-height (0 without one)
    """

@overload
def point(
    kind: Literal["fit.powerlaw"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    expected_slope: Optional[float] = ...,
    from_: str = ...,
    group_by: Optional[str] = ...,
    x: str = ...,
    x_max: float = ...,
    x_min: float = ...,
    y: str = ...,
) -> Dict[str, Any]:
    """Power law y = c x^s fitted over an x range (log-log least squares), with standard errors

    Parameters:
        expected_slope (number or null; default None): A reference slope (e.g. 5/4), reported beside the
            fitted one.
        from_ (string; required): The stage whose table is fitted (must be in `needs`).
        group_by (string or null; default None): One fit per distinct value of this (numeric) column.
        x (string; required):
        x_max (number; required):
        x_min (number; required, > 0): Only points with x in [x_min, x_max] are fitted.
        y (string; required):

    Columns:
        slope [1]: fitted exponent
        slope_std_error [1]: its standard error
        prefactor [units of y]: fitted prefactor
        prefactor_std_error [units of y]: its standard error
        r_squared [1]: coefficient of determination in log-log
        n_points [count]: points fitted
        x_min [units of x]: the fitted range's lower end
        x_max [units of x]: the fitted range's upper end
        expected_slope [1]: the thesis' slope, for comparison
    """

@overload
def point(
    kind: Literal["pb.calibrate"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    from_: str = ...,
    linear_range: Optional[Any] = ...,
    min_points: int = ...,
    slope_tolerance: float = ...,
    sqrt_range: Optional[Any] = ...,
    y: str = ...,
) -> Dict[str, Any]:
    """Persson-Brener prefactor alpha (Eq. 5.18) fitted to F_T*(V0) curves: linear (Eq. 5.20) and square-
    root (Eq. 5.21) regimes

    Parameters:
        from_ (string; required): A `bem.sweep` stage (in `needs`): columns lambda, W, k, V0, converged
            and `y` (and s, for a power-law material: one curve per s; the laws are the SLS ones, so
            alpha is then an effective prefactor).
        linear_range (array or null; default None): Fixed V0 ranges instead of the detected regimes.
        min_points (integer; default 3, >= 3): The fewest points a regime may have (default 3).
        slope_tolerance (number; default 0.1, (0, 0.25)): A regime is the longest run of points whose
            local slopes d ln F / d ln V0 lie within this of the law's slope (1 or 1/2); default 0.1.
        sqrt_range (array or null; default None):
        y (string; default 'F_T'): The friction column (default F_T = mu* |W|, Eq. 5.6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        regime [text]: `linear` (Eq. 5.20) or `sqrt` (Eq. 5.21)
        alpha [1]: Persson-Brener prefactor α (Eq. 5.18), geometric mean over the regime's points
        alpha_std_error [1]: its standard error
        alpha_spread [1]: the standard deviation of ln α over the regime's points
        n_points [count]: points fitted
        x_min [units of x]: the fitted range's lower end
        x_max [units of x]: the fitted range's upper end
        slope [1]: fitted exponent
        slope_std_error [1]: its standard error
        prefactor [units of y]: fitted prefactor
        fitted_slope [1]: the free log-log slope over the regime
        fitted_slope_std_error [1]: its standard error
    """

@overload
def point(
    kind: Literal["theory.adhesionless_friction_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    W_range: Any = ...,
    from_: str = ...,
) -> Dict[str, Any]:
    """Persson's adhesionless maximum of mu* over V0 (Appendix A) for each k of a needed stage, across a
    load range

    Parameters:
        W_range (array; required): The load range the line spans, [from, to], 0 < from < to (the column
            `W`).
        from_ (string; required): The stage whose distinct modulus ratios are bounded (must be in
            `needs`; its table has the column `k`).

    Columns:
        k [1]: modulus ratio E0/E∞
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        mu_star_max_adhesionless [1]: Persson's adhesionless maximum of μ* over V0 for the row's k
            (Appendix A), which the maxima approach at large loads
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def point(
    kind: Literal["theory.hertz_jkr_pressure"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    P_bar: float = ...,
    n: int = ...,
) -> Dict[str, Any]:
    """Hertz and JKR pressure p/p0_Hertz vs r/a_Hertz at the same load (Fig. 2.4)

    Parameters:
        P_bar (number; default 1.0, > 0): Load in Maugis' units, P = F / (pi w R); must exceed the JKR
            pull-off -3/2.
        n (integer; default 200, 10..=1000000): Number of radial points per model.

    Columns:
        model [text]: which closed form a row belongs to (`hertz`, `jkr`, `dmt`)
        P_bar [F/(π w R)]: load (positive: compressive)
        r_over_aH [a_Hertz]: radius in the Hertz contact radius (Fig. 2.4)
        p_over_p0H [p0_Hertz]: pressure in the Hertz peak pressure (Fig. 2.4)
    """

@overload
def point(
    kind: Literal["theory.jkr_friction_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    from_: str = ...,
    lambda_range: Any = ...,
) -> Dict[str, Any]:
    """The JKR limit of the friction mu* = pi^(1/2) / (2 W^(3/2) k) for each (W, k) of a needed stage,
    across a lambda range

    Parameters:
        from_ (string; required): The stage whose distinct (W, k) pairs are bounded (must be in `needs`;
            its table has the columns `W` and `k`).
        lambda_range (array; required): The lambda range the line spans, [from, to], 0 < from < to.

    Columns:
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        mu_star_jkr [1]: the JKR limit of the friction, π^(1/2) / (2 |W|^(3/2) k) (the equation after
            Fig. 4.6), which max μ* approaches as λ grows
    """

@overload
def point(
    kind: Literal["theory.lennard_jones"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    n: int = ...,
    z_max: float = ...,
    z_min: float = ...,
) -> Dict[str, Any]:
    """The Lennard-Jones 3-9 law of the solvers: energy/dgamma and pressure/sigma0 vs separation h/eps
    (Fig. 2.3)

    Parameters:
        n (integer; default 200, 2..=1000000):
        z_max (number; default 4.0):
        z_min (number; default 0.85, > 0): Separations h/eps from `z_min` to `z_max` (eps the
            equilibrium separation), `n` points.

    Columns:
        h_over_eps [ε]: separation over the equilibrium separation (Fig. 2.3)
        energy_over_dgamma [Δγ]: Lennard-Jones 3-9 energy per unit area
        pressure_over_sigma0 [σ0]: its disjoining pressure, compression positive
    """

@overload
def point(
    kind: Literal["theory.line_pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    lambda_: float = ...,
) -> Dict[str, Any]:
    """2D line-contact pull-off W: Maugis-Dugdale, JKR -3(pi/16)^(1/3), rigid Lennard-Jones -2.434
    sqrt(lambda)

    Parameters:
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter (sweepable).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W_md [W (Eq. 4.6)]: pull-off load of the Maugis-Dugdale line contact
        A_md [β]: its contact half-width (0: reached as the contact closes)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        W_jkr [W]: the 2D JKR pull-off -3(π/16)^(1/3)
        W_rigid_lj [W]: the rigid Lennard-Jones limit -2.434 √λ
    """

@overload
def point(
    kind: Literal["theory.maugis_dugdale"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    A_max: float = ...,
    A_min: float = ...,
    lambda_: float = ...,
    n: int = ...,
) -> Dict[str, Any]:
    """Maugis-Dugdale sphere contact: load P_bar and approach vs contact radius A_bar (thesis 2.4.2.4)

    Parameters:
        A_max (number; default 2.5): Largest dimensionless contact radius A.
        A_min (number; default 0.02, > 0): Smallest dimensionless contact radius A.
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter lambda = 2 sigma0 (R /
            (pi w K^2))^(1/3) (sweepable).
        n (integer; default 200, 2..=1000000): Number of radii (log-spaced).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        A_bar [Maugis' A]: contact radius
        P_bar [F/(π w R)]: load (positive: compressive)
        approach_bar [Maugis' δ]: approach
        m [1]: Maugis-Dugdale ratio c/a of the cohesive zone's outer radius to the contact radius
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def point(
    kind: Literal["theory.maugis_pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    lambda_: float = ...,
) -> Dict[str, Any]:
    """Maugis-Dugdale pull-off load (minimum of P_bar over A_bar); JKR -3/2, DMT -2

    Parameters:
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter (sweepable).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        P_bar_pulloff [F/(π w R)]: pull-off load under load control
        A_bar_pulloff [Maugis' A]: contact radius at pull-off
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        P_bar_jkr [F/(π w R)]: JKR pull-off, -3/2
        P_bar_dmt [F/(π w R)]: DMT pull-off, -2
    """

@overload
def point(
    kind: Literal["theory.persson"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V0: float = ...,
    inv_k: float = ...,
    rel_tol: float = ...,
) -> Dict[str, Any]:
    """Persson's adhesionless friction mu* = mu R/a0 vs V0 = v tau/a0 for a standard linear solid (Eqs.
    7.1-7.2)

    Parameters:
        V0 (number; required, (0, 1e100], sweepable): V0 = v tau / a0 (sweepable), in (0, 1e100]: beyond
            1e100 mu* (about 1/V0 there) underflows the quadrature's relative tolerance.
        inv_k (number; required, > 1, sweepable): 1/k = E_inf / E0 (sweepable), > 1.
        rel_tol (number; default 1e-08, [1e-14, 0.01)): Relative tolerance of the quadrature, in [1e-14,
            0.01): below 1e-14 double precision cannot meet it (at 1e-16 the quadrature refines for a
            minute and returns the same digits).

    Columns:
        inv_k [1]: E∞/E0 = 1/k
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def point(
    kind: Literal["theory.persson_brener"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    V_PB: float = ...,
    k: float = ...,
    per_decade: Optional[int] = ...,
    prony: Optional[Any] = ...,
    s: Optional[float] = ...,
    tau_ratio: Optional[float] = ...,
) -> Dict[str, Any]:
    """Persson-Brener G_trail/dgamma (Eq. 5.12, or Eq. 5.27 for a spectrum) and f_T/dgamma = G - 1/G (Eq.
    5.13) vs v/v0

    Parameters:
        V_PB (number; required, > 0, sweepable): V_PB = v / v0, v0 = c0 / (2 pi tau) (sweepable).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0 / E_inf in (0, 1) (sweepable).
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        k [1]: modulus ratio E0/E∞
        V_PB [v/v0]: Persson-Brener speed
        G_trail_over_dgamma [Δγ]: energy release rate at the trailing edge (Eq. 5.12)
        F_T_PB [Δγ]: Persson-Brener friction f_T/Δγ = G - 1/G (Eq. 5.13)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        tau_ratio [1]: τ1/τ2, the power-law spectrum's shortest retardation time over its longest
        n_eq_5_28 [1]: the power-law exponent (1-s)/(2-s) of Eq. 5.28
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
    """

@overload
def point(
    kind: Literal["theory.persson_max"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    inv_k: float = ...,
    rel_tol: float = ...,
) -> Dict[str, Any]:
    """Maximum over V0 of Persson's adhesionless mu*, and where it occurs

    Parameters:
        inv_k (number; required, > 1, sweepable): 1/k = E_inf / E0 (sweepable), > 1.
        rel_tol (number; default 1e-08, [1e-14, 0.01)):

    Columns:
        inv_k [1]: E∞/E0 = 1/k
        k [1]: modulus ratio E0/E∞
        mu_star_max [1]: maximum of μ* over V0
        V0_at_max [1]: the V0 of that maximum
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def point(
    kind: Literal["theory.sphere_limits"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    A_max: float = ...,
    A_min: float = ...,
    n: int = ...,
) -> Dict[str, Any]:
    """Hertz (P = A^3), JKR (A^3 - sqrt(6 A^3)) and DMT (A^3 - 2) curves in Maugis' units

    Parameters:
        A_max (number; default 2.5):
        A_min (number; default 0.02, > 0):
        n (integer; default 200, 2..=1000000):

    Columns:
        model [text]: which closed form a row belongs to (`hertz`, `jkr`, `dmt`)
        A_bar [Maugis' A]: contact radius
        P_bar [F/(π w R)]: load (positive: compressive)
    """

@overload
def point(
    kind: Literal["util.fail"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    message: str = ...,
    panic: bool = ...,
    x: float = ...,
) -> Dict[str, Any]:
    """Fails with `message` when x <= 0 (for testing the orchestrator)

    Parameters:
        message (string; required): The error message.
        panic (boolean; default False): Also panic instead of returning an error.
        x (number; default 0.0, sweepable): Positive: output this value instead of failing; the failure
            happens when `x <= 0`.

    Columns:
        x [`x_unit`]: the plotted abscissa
    """

@overload
def point(
    kind: Literal["util.sleep"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    raise_on_unconverged: bool = False,
    ms: int = ...,
    round: Optional[int] = ...,
    x: float = ...,
) -> Dict[str, Any]:
    """Waits `ms` milliseconds and returns `x` (for testing the orchestrator)

    Parameters:
        ms (integer; default 0, >= 0): Milliseconds to wait before returning (a checkpoint of the time
            limit every 10 ms).
        round (integer or null; default None): Output `x` rounded to this many decimals (lets tests
            produce identical outputs from different parameters).
        x (number; required, sweepable): Value echoed into the output table (sweepable).

    Columns:
        x [`x_unit`]: the plotted abscissa
        upstream_rows []: (see docs/outputs.md)
        upstream_x []: (see docs/outputs.md)
    """

@overload
def point(kind: str, params: Optional[Mapping[str, Any]] = None, /, *, raise_on_unconverged: bool = False, **kw: Any) -> Dict[str, Any]: ...

@overload
def sweep(
    kind: Literal["bem.maxima"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V0_range: Any = ...,
    W: Sweep = ...,
    grid: int = ...,
    half_length: Optional[float] = ...,
    k: Sweep = ...,
    lambda_: Sweep = ...,
    log_tol: float = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    rel_tol: Optional[float] = ...,
) -> Any:
    """Chapter 4 BEM: maximum over V0 of mu* for one (lambda, W, k), by bracketing and golden-section
    search

    Parameters:
        V0_range (array; default [0.001, 1000.0]): Speeds searched, [from, to].
        W (number; required, sweepable): Dimensionless load (sweepable).
        grid (integer; default 13, 3..=1000): Log-spaced bracketing points over the range.
        half_length (number or null; default None, > 0):
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter (sweepable).
        log_tol (number; default 0.01, (0, 1)): Golden-section tolerance in log10 V0.
        n (integer or null; default None, 16..=32000): Mesh rules of each solve, as in `bem.sweep`.
        n_max (integer or null; default None, 16..=32000):
        rel_tol (number or null; default None, (0, 1)):

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        mu_star_max [1]: maximum of μ* over V0
        V0_at_max [1]: the V0 of that maximum
        mu_adh [1]: the adhesive part of μ*
        mu_comp [1]: the compressive part of μ*
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        evaluations [count]: solves made by a search (maximum, pull-off)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["bem.profile"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V0: Sweep = ...,
    W: Sweep = ...,
    half_length: Optional[float] = ...,
    k: Sweep = ...,
    lambda_: Sweep = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    newton_tol: Optional[float] = ...,
    per_decade: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    prony: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
    s: Sweep = ...,
    start: Optional[str] = ...,
    tau_ratio: Optional[float] = ...,
) -> Any:
    """Chapter 4 BEM: pressure P(X), displacement U(X), gap H(X) and friction integrand P dU/dX of one
    point

    Parameters:
        V0 (number; required, >= 0, sweepable): Dimensionless speed V0 = v tau / a0 (Eq. 4.18; a0 the
            Hertz half-width of |W|), >= 0 (sweepable).
        W (number; required, sweepable): Dimensionless load W (Eq. 4.6), nonzero (sweepable). Negative:
            a tensile load (the cylinder beneath the substrate, Chapter 5), reached on the stable branch
            by walking down from |W| by pseudo-arclength continuation; beyond the pull-off the point is
            reported as not converged.
        half_length (number or null; default None, > 0): Half-length of the domain in units of beta;
            default: chosen from lambda, W and rel_tol (`bem::solver::domain_half_length`).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (the error is then
            estimated against n/2); default: the mesh is chosen from `rel_tol`.
        n_max (integer or null; default None, 16..=32000): The largest mesh of the refinement (default
            16000).
        newton_tol (number or null; default None, (0, 1)): Newton's tolerance on the max-norm residual
            in units of H (default 1e-9, `bem::solver::TOLERANCE`); for the accuracy-cost bench.
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh: `linear`
            between the element centres (the default: second order at every speed) or `uniform` on each
            element (the thesis' strips, Eq. 4.12: first order where the elements are longer than the
            creep length, as at low speed; docs/bem.md, "Discretisation").
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of mu* (default
            1e-3): starting from `bem::solver::starting_mesh`, the number of elements is doubled until
            the Richardson error estimate meets it, up to `n_max`.
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        start (string or null; default None): A stage of `needs` whose rows hold converged states (a
            `bem.profile`'s: `X`, `H`, `approach`), best read row by row (`needs: [{stage: S, match:
            [lambda, W, k]}]`): the refinement's first mesh starts by Newton from the state, among those
            of this lambda, W, k and material, at the speed nearest V0 (in log V0), instead of the
            continuation from the relaxed state (the continuation if that fails). mu* changes within
            Newton's tolerance only; without such rows the point is solved from scratch. Not with a
            fixed `n`.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
        X [β]: position along the interface
        P [σ0]: interface pressure P(X), compression positive
        U [β²/R]: surface displacement U(X)
        H [β²/R]: gap H(X) = (h - ε) R/β² (Eq. 4.7)
        P_dU_dX [σ0]: the friction integrand P dU/dX
        mu_integrand [1 per β]: the local contribution to μ* (Fig. 4.4's quantity)
        surface [β²/R]: the deformed surface, -U
        indenter [β²/R]: the indenter's profile X²/2 - approach
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        approach [β²/R]: approach Δ of the cylinder (Eq. 4.7)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["bem.pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V: Sweep = ...,
    k: Sweep = ...,
    lambda_: Sweep = ...,
    n: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
) -> Any:
    """Chapters 4-5 BEM: pull-off load (minimum W on the equilibrium branch, walked by pseudo-arclength in
    approach and load) at speed V

    Parameters:
        V (number; required, >= 0, sweepable): Speed V = v tau/beta >= 0 (sweepable): independent of the
            load, which is the unknown here; the table also gives V0 = V/a0 with a0 the Hertz half-width
            of the pull-off load.
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (default: from
            `bem::solver::starting_mesh`, doubled until the Richardson estimate of the pull-off load
            meets rel_tol).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh, as in
            `bem.sweep` (default `linear`).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of the pull-off load
            (default 1e-3).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        k [1]: modulus ratio E0/E∞
        V [1]: speed in the relaxation time of the pull-off stages
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        W_pulloff [W]: pull-off load at speed V
        A [β]: contact half-width at pull-off (gap below the separation of peak tension)
        two_A [β]: contact width 2A at pull-off (Fig. 5.8)
        x_lead [β]: leading edge of the contact
        x_trail [β]: trailing edge of the contact
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        F_T [1]: rolling friction force F_T* = μ* |W| (Eq. 5.6)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        evaluations [count]: solves made by a search (maximum, pull-off)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        half_length [β (BEM length unit)]: half-length of the BEM domain
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["bem.sweep"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V0: Sweep = ...,
    W: Sweep = ...,
    half_length: Optional[float] = ...,
    k: Sweep = ...,
    lambda_: Sweep = ...,
    n: Optional[int] = ...,
    n_max: Optional[int] = ...,
    newton_tol: Optional[float] = ...,
    per_decade: Optional[int] = ...,
    pressure: Optional[Any] = ...,
    prony: Optional[Any] = ...,
    rel_tol: Optional[float] = ...,
    s: Sweep = ...,
    start: Optional[str] = ...,
    tau_ratio: Optional[float] = ...,
) -> Any:
    """Chapter 4 BEM: friction mu* (Eq. 4.16) of a cylinder sliding on an adhesive SLS half-plane, one
    point per task

    Parameters:
        V0 (number; required, >= 0, sweepable): Dimensionless speed V0 = v tau / a0 (Eq. 4.18; a0 the
            Hertz half-width of |W|), >= 0 (sweepable).
        W (number; required, sweepable): Dimensionless load W (Eq. 4.6), nonzero (sweepable). Negative:
            a tensile load (the cylinder beneath the substrate, Chapter 5), reached on the stable branch
            by walking down from |W| by pseudo-arclength continuation; beyond the pull-off the point is
            reported as not converged.
        half_length (number or null; default None, > 0): Half-length of the domain in units of beta;
            default: chosen from lambda, W and rel_tol (`bem::solver::domain_half_length`).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0/E_inf in (0, 1) (sweepable).
        lambda_ (number; required, > 0, sweepable): Maugis-Tabor parameter lambda (Eq. 4.9), > 0
            (sweepable).
        n (integer or null; default None, 16..=32000): A fixed number of elements (the error is then
            estimated against n/2); default: the mesh is chosen from `rel_tol`.
        n_max (integer or null; default None, 16..=32000): The largest mesh of the refinement (default
            16000).
        newton_tol (number or null; default None, (0, 1)): Newton's tolerance on the max-norm residual
            in units of H (default 1e-9, `bem::solver::TOLERANCE`); for the accuracy-cost bench.
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        pressure (PressureParam or null; default None): How the pressure varies over the mesh: `linear`
            between the element centres (the default: second order at every speed) or `uniform` on each
            element (the thesis' strips, Eq. 4.12: first order where the elements are longer than the
            creep length, as at low speed; docs/bem.md, "Discretisation").
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        rel_tol (number or null; default None, (0, 1)): Requested relative accuracy of mu* (default
            1e-3): starting from `bem::solver::starting_mesh`, the number of elements is doubled until
            the Richardson error estimate meets it, up to `n_max`.
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        start (string or null; default None): A stage of `needs` whose rows hold converged states (a
            `bem.profile`'s: `X`, `H`, `approach`), best read row by row (`needs: [{stage: S, match:
            [lambda, W, k]}]`): the refinement's first mesh starts by Newton from the state, among those
            of this lambda, W, k and material, at the speed nearest V0 (in log V0), instead of the
            continuation from the relaxed state (the continuation if that fails). mu* changes within
            Newton's tolerance only; without such rows the point is solved from scratch. Not with a
            fixed `n`.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        mu_adh [1]: the adhesive part of μ*
        mu_comp [1]: the compressive part of μ*
        F_T [1]: rolling friction force F_T* = μ* |W| (Eq. 5.6)
        x_lead [β]: leading edge of the contact
        x_trail [β]: trailing edge of the contact
        approach [β²/R]: approach Δ of the cylinder (Eq. 4.7)
        p_max_bar [σ0]: largest compressive pressure
        p_min_bar [σ0]: largest tension
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        termination [text]: why the solver stopped. `bem.sweep`: `converged`, `iteration_limit`,
            `stalled` (line searches cut the step to 1/16 several times in a row), `step_too_small` (no
            step lowered the residual), `diverged` (non-finite residual or direction), `off_branch` (a
            tensile state left the stable branch), `beyond_pull_off` (no stable state at that tensile
            load), `non_finite_friction`. `fem.indent` (per state): `converged`, `iteration_limit`,
            `no_step` (every trial step inverted an element), `no_descent` (the energy descent found no
            shift that lowers the potential), `unstable` (an equilibrium at a tangent that is not
            positive definite), `inverted` (the state could not be evaluated), `not_solved` (the
            reference state taken as the start when no adhering state was found)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        residual [units of the solved equation]: the final residual's max-norm
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        n [count]: elements of the final BEM mesh
        half_length [β (BEM length unit)]: half-length of the BEM domain
        zone_elements [count]: BEM elements per cohesive zone π/(8 λ²): below 1 the crack front is not
            resolved
        start_V0 [v τ/a0]: with `start`: the speed of the state the point's first mesh started from (-1:
            no row matched, solved from scratch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["bench.pareto"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    candidates: Any = ...,
    default: str = ...,
    error: Optional[str] = ...,
    error_resolution: float = ...,
    match: Any = ...,
    reference: str = ...,
    time_resolution: float = ...,
    tolerance: float = ...,
    value: str = ...,
) -> Any:
    """Run time against error: per solver configuration, max relative error vs a reference, wall time,
    Pareto front

    Parameters:
        candidates (array; required): The configurations: stages with one row per physical point (each
            must be in `needs`).
        default (string; required): The candidate that the thesis pipeline uses (its defaults).
        error (string or null; default None): The candidates' column holding the error estimate of
            `value` (absolute, in its units), if any: each candidate is then checked against the
            reference, with the columns `estimate_covers` (the fraction of its points whose actual error
            is within the estimate) and `error_over_estimate` (the largest actual error over estimate).
        error_resolution (number; default 0.0): Relative errors within this fraction of each other count
            as equal (default 0: compared exactly).
        match (array; required): Columns that identify a physical point (matched between candidates and
            reference).
        reference (string; required): The converged reference: a stage with the same physical points.
        time_resolution (number; default 0.0): Wall times within this fraction of each other count as
            equal (default 0).
        tolerance (number; required, > 0): The declared tolerance on the relative error (e.g. 0.005).
        value (string; required): The quantity whose relative error is measured (e.g. `mu_star`,
            `F_buckling_bar`).

    Columns:
        config [text]: the configuration's parameters
        rel_error [1]: the largest relative error against the reference
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
        points [count]: points compared
        configs [count]: the configurations a `bench.pareto` table compares (every row the same)
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        on_front [boolean]: on the Pareto front of error against time
        on_front_resolved [boolean]: on the front at the error resolution
        is_default [boolean]: the configuration the thesis pipeline uses
        meets_tolerance [boolean]: within it
        tolerance [1]: the declared tolerance
        value [units of the column]: the quantity measured (1/0 for increasing, decreasing)
    """

@overload
def sweep(
    kind: Literal["bench.summary"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    stages: Any = ...,
) -> Any:
    """Summary of a stress grid: per stage points, converged, max iterations, worst residual

    Parameters:
        stages (array; required): The stages summarised (each must be in `needs`), one row each.

    Columns:
        stage [text]: the stage whose table it reads
        points [count]: points compared
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        not_converged [count]: points that did not converge
        max_iterations [count]: the largest Newton iteration count over the task's solves
        worst_residual [units of the solved equation]: the largest final residual
    """

@overload
def sweep(
    kind: Literal["claim"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    docs: str = ...,
    expect: Any = ...,
    id: str = ...,
    independent: Optional[Any] = ...,
    quantity: Any = ...,
    reason: str = ...,
    source: str = ...,
    statement: str = ...,
    thesis: Any = ...,
) -> Any:
    """A statement of the thesis checked against a published table: the quantity, the thesis' value, the
    verdict

    Parameters:
        docs (string; default None): The docs section that explains it, e.g. `docs/shell.md#claims`.
        expect (Verdict; required): The verdict recorded at the last review: a claim recorded as
            reproduced that no longer is, is a regression.
        id (string; required): A short identifier, e.g. `ch2.jkr_pulloff`.
        independent (Independent or null; default None):
        quantity (Quantity; required): The measured quantity.
        reason (string; default None): Why the reproduction differs (required with `expect: differs`).
        source (string; required): Where the thesis states it: section, equation or figure.
        statement (string; required): The statement, in a few words.
        thesis (Expected; required): The thesis' value with the tolerance its text implies, or its
            bound.

    Columns:
        id [text]: the claim's identifier, e.g. `ch2.md_jkr_limit`
        source [text]: where the thesis states it
        statement [text]: the statement
        stage [text]: the stage whose table it reads
        column [text]: the column reduced
        aggregate [text]: how (value, max, slope, increasing, ...)
        value [units of the column]: the quantity measured (1/0 for increasing, decreasing)
        thesis [text]: the thesis' condition in words (`-1.5 ± 0.1 %`, `< 280.25`)
        thesis_value [units of the column]: its value, or a bound
        has_independent [boolean]: an independent value is given
        independent_value [units of the column]: the independent value (0 without one)
        independent_source [text]: what it is
        verdict [text]: `reproduced` or `differs`
        expected [text]: the verdict recorded at the last review
        regression [boolean]: recorded as reproduced and now differing
        reason [text]: why it differs
        docs [text]: the docs section that explains it
    """

@overload
def sweep(
    kind: Literal["claims"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    claims: Any = ...,
) -> Any:
    """The verdicts of claim stages in one table, and the run's verdict line

    Parameters:
        claims (array; required): The `claim` stages gathered (each must be in `needs`).

    Columns:
        id [text]: the claim's identifier, e.g. `ch2.md_jkr_limit`
        verdict [text]: `reproduced` or `differs`
        expected [text]: the verdict recorded at the last review
    """

@overload
def sweep(
    kind: Literal["fem.buckling"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    apex_force: Sweep = ...,
    dimple: Sweep = ...,
    dissipation: bool = ...,
    gamma_over_Eh: Sweep = ...,
    h_over_R: Sweep = ...,
    mesh_study: bool = ...,
    model: Any = ...,
    mu: Sweep = ...,
) -> Any:
    """Chapter 3: F_buckling, delta at it and the dissipated energy W at one (h/R, gamma/(E h), mu)

    Parameters:
        apex_force (number or null; default None, sweepable): The apex force of the imperfection in
            units of F_c = E h^3 / R (sweepable; default: `model.imperfection.apex_force`).
        dimple (number or null; default None, sweepable): The dimple depth of the imperfection in units
            of h (sweepable; default: `model.imperfection.dimple`).
        dissipation (boolean; default True): Also unload, for the dissipated energy W (default true;
            false stops at the snap).
        gamma_over_Eh (number; default 0.0, >= 0, sweepable): Work of adhesion gamma/(E h) (sweepable;
            default 0).
        h_over_R (number; required, (0, 0.5), sweepable): Thickness over radius h/R (sweepable).
        mesh_study (boolean; default False): Estimate the mesh's share of the errors of F_buckling and W
            at this point by a second cycle on twice the meridian elements, run alongside (`MeshStudy`;
            default false: the declared errors of the default mesh, none on other meshes). Three to four
            times the CPU time.
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).

    Columns:
        h_over_R [1]: thickness over inner radius
        gamma_over_Eh [1]: work of adhesion over E h
        mu [1]: Coulomb friction coefficient
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        buckled [boolean]: the shell snapped through on loading
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        F_contact_buckling_bar [F_c]: contact force at the snap
        F_adhesive_buckling_bar [F_c]: adhesive pull at the snap
        F_buckling_error_bar [F_c]: its error estimate (bisection bracket and mesh)
        F_buckling_mesh_error_bar [F_c]: the mesh's share
        delta_buckling_over_R [R]: plate displacement at the snap
        delta_buckling_error_over_R [R]: its error estimate
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        delta_landing_over_R [R]: where the snap lands on the inverted branch
        W_bar [E h³ (F_c R)]: dissipated energy W = ∮ F dδ of the cycle
        W_Nmm [N mm]: the dissipated energy W in N mm
        W_error_bar [E h³]: its error estimate
        W_error_Nmm [N mm]: W's error estimate in N mm
        W_mesh_error_Nmm [N mm]: the mesh's share of W's error, in N mm
        W_friction_Nmm [N mm]: the part of W dissipated by friction, in N mm
        n_meridian [count]: elements along the meridian
        mesh_error_source [text]: where the mesh error comes from (`study`: a cycle on a mesh twice as
            fine along the meridian; `declared`: the default mesh's measured errors,
            `fem::mesh::default_mesh_rel_error` and `default_mesh_w_rel_error`; `none`)
        mesh_study_agrees [boolean]: both meshes agree on whether the shell snaps
        complete [boolean]: the cycle (or probe) reached its end
        max_iterations [count]: the largest Newton iteration count over the task's solves
        max_residual [E h^2 (shell), H (BEM)]: the largest final residual over the task's solves
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["fem.buckling_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    gamma_over_Eh: Sweep = ...,
    h_hi: float = ...,
    h_lo: float = ...,
    model: Any = ...,
    mu: Sweep = ...,
    tol: float = ...,
) -> Any:
    """Chapter 3: the h/R above which the shell does not snap through before delta_max, by bisection

    Parameters:
        gamma_over_Eh (number; default 0.0, >= 0, sweepable): Work of adhesion gamma/(E h) (default 0).
        h_hi (number; default 0.4, (0, 0.5)):
        h_lo (number; default 0.1, (0, 0.5)): The search interval of h/R (default [0.1, 0.4]) and its
            tolerance (default 0.005).
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).
        tol (number; default 0.005, > 0):

    Columns:
        mu [1]: Coulomb friction coefficient
        gamma_over_Eh [1]: work of adhesion over E h
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        h_limit_over_R [1]: thickness above which the shell does not snap before δ_max
        h_lo_over_R [1]: the bisection's snapping end
        h_hi_over_R [1]: its non-snapping end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        buckles_at_h_lo [boolean]: the shell snaps at h_lo
        buckles_at_h_hi [boolean]: the shell snaps at h_hi
        probes [count]: loading runs made by the bracketing
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["fem.gamma_c"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    apex_force: Sweep = ...,
    dimple: Sweep = ...,
    g0: Sweep = ...,
    gamma_max: float = ...,
    growth: float = ...,
    guess: float = ...,
    h_over_R: Sweep = ...,
    model: Any = ...,
    mu: Sweep = ...,
    rel_tol: float = ...,
) -> Any:
    """Chapter 3: critical adhesion gamma_c/(E h) above which the shell does not snap, by bracketing, with
    Eq. 3.7

    Parameters:
        apex_force (number or null; default None, >= 0, sweepable): The apex force of the imperfection
            in units of F_c = E h^3 / R (sweepable; default: `model.imperfection.apex_force`).
        dimple (number or null; default None, sweepable): The dimple depth of the imperfection in units
            of h (sweepable; default: `model.imperfection.dimple`).
        g0 (number or null; default None, > 0, sweepable): The Lennard-Jones range g0 in mm (sweepable;
            default: `model.g0`; the default mesh follows it), for studies of gamma_c's limit as the
            regularisation goes.
        gamma_max (number; default 0.1, > 0):
        growth (number; default 2.0, > 1):
        guess (number; default 0.02, > 0): The first gamma/(E h) tried per unit of the adhesionless
            snap's distance from delta_max: the first trial is guess (1 - delta_snap(0) / delta_max)
            (default 2e-2; `fem::critical::bracket`), the factor of the steps taken without a secant
            estimate (default 2), the largest gamma/(E h) tried (default 0.1).
        h_over_R (number; required, (0, 0.5), sweepable): Thickness over radius h/R (sweepable).
        model (MapModel; default {'E': 1.3, 'R': 15.0, 'bisections': 5, 'delta_max': 0.35, 'g0': 0.1,
            'grading': 3.0, 'hold': 'free', 'lift_threshold': 0.02, 'n_meridian': None, 'n_thickness':
            2, 'nu': 0.45, 'penalty': 1000.0, 'steps': 35}): The shell (clamped base), its mesh, the
            interface and the loading shared by the points of a map. Every field has a default (the
            thesis' R = 15 mm, E = 1.3 N/mm^2, nu = 0.45, g0 = 0.1 mm).
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (sweepable; default 0).
        rel_tol (number; default 0.1, (0, 10)): Bracketing tolerance: the search stops when gamma_hi /
            gamma_lo - 1 < rel_tol.

    Columns:
        h_over_R [1]: thickness over inner radius
        mu [1]: Coulomb friction coefficient
        g0 [mm]: equilibrium distance (range) g0 of the Lennard-Jones law (Eqs. 3.3-3.4); the default
            mesh resolves it
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        gamma_max_over_Eh [1]: the largest γ/(E h) the bracket tries: where the shell snaps up to it,
            γ_c is only bounded below (0 on the map's rows of the buckling limit)
        n_meridian [count]: elements along the meridian
        gamma_c_over_Eh [1]: critical adhesion γ_c/(E h): above it no snap before δ_max (geometric mid
            of the bracket)
        gamma_lo_over_Eh [1]: the bracket's buckling end
        gamma_hi_over_Eh [1]: the bracket's non-buckling end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        rel_tol [1]: the requested relative accuracy
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        reliable [boolean]: both bracket ends rest on converged probes
        buckles_without_adhesion [boolean]: the shell snaps at γ = 0
        gamma_c_N_per_mm [N/mm]: γ_c in N/mm
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        eq3_7_over_Eh [1]: Eq. 3.7's estimate (r/R)⁴
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        probes [count]: loading runs made by the bracketing
        unconverged_probes [count]: those that did not converge
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["fem.gamma_c_map"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    gamma_c: str = ...,
    limit: Optional[str] = ...,
) -> Any:
    """Chapter 3: the buckling map gamma_c/(E h) vs h/R per mu (Fig. 3.9), from fem.gamma_c points

    Parameters:
        gamma_c (string; required): The `fem.gamma_c` stage swept over h_over_R and mu.
        limit (string or null; default None): The `fem.buckling_limit` stage swept over mu (optional):
            each mu's boundary is closed at gamma_c = 0 there.

    Columns:
        mu [1]: Coulomb friction coefficient
        h_over_R [1]: thickness over inner radius
        gamma_c_over_Eh [1]: critical adhesion γ_c/(E h): above it no snap before δ_max (geometric mid
            of the bracket)
        gamma_lo_over_Eh [1]: the bracket's buckling end
        gamma_hi_over_Eh [1]: the bracket's non-buckling end
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        h_error_over_R [1]: error of the map's h/R (the bisection's half-width; 0 for given points)
        eq3_7_over_Eh [1]: Eq. 3.7's estimate (r/R)⁴
        found [boolean]: the bracket closed (false: the threshold lies beyond the searched range; the
            value is a bound)
        reliable [boolean]: both bracket ends rest on converged probes
        delta_max_over_R [R]: where the loading leg ends, δ_max/R: a snap counts only before it
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        gamma_max_over_Eh [1]: the largest γ/(E h) the bracket tries: where the shell snaps up to it,
            γ_c is only bounded below (0 on the map's rows of the buckling limit)
    """

@overload
def sweep(
    kind: Literal["fem.indent"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    base: Any = ...,
    bisections: int = ...,
    delta_max: float = ...,
    g0: float = ...,
    gamma: Sweep = ...,
    hold: Any = ...,
    lift_threshold: float = ...,
    mesh_study: bool = ...,
    mu: Sweep = ...,
    penalty: float = ...,
    shell: Any = ...,
    snap: Any = ...,
    stability: Any = ...,
    steps: int = ...,
) -> Any:
    """Chapter 3: load-unload cycle of a shell pressed by a rigid plate (snap-through, snap-back, unstable
    branch)

    Parameters:
        base (Support; default 'clamped'): Base support: `clamped` (default, as the experiments) or
            `roller`.
        bisections (integer; default 6, >= 0): Bisections locating the snap-through in delta (default 6:
            to steps/64).
        delta_max (number; required, (0, 1)): Largest plate displacement delta/R.
        g0 (number; default 0.1, > 0): Equilibrium distance g0 of the Lennard-Jones law (mm; default 0.1
            as the thesis).
        gamma (number; default 0.0, >= 0, sweepable): Work of adhesion dgamma of the Lennard-Jones law,
            Eq. 3.3 (N/mm; default 0).
        hold (Hold; default 'free'): What holds touching points of an adhesive contact in the stability
            test: `free` (default) or `lennard_jones` (16 dgamma / g0^2).
        lift_threshold (number; default 0.02, (0, 1)): With `stability: lift_threshold`: contact nodes
            pressed above this fraction of the peak pressure are held against lifting off, the others
            are free to (default 0.02).
        mesh_study (boolean; default False): Estimate the mesh's share of the errors of every state's
            force, F_buckling and W by a second cycle on twice the meridian elements, run alongside
            (`Cycles`; default false: the declared errors of the default mesh, none on other meshes).
            Three to four times the CPU time.
        mu (number; default 0.0, >= 0, sweepable): Coulomb friction coefficient (default 0).
        penalty (number; default 1000.0, > 0): Contact penalty in units of E/h: the penetration is about
            p h/(penalty E).
        shell (ShellParams; required): The shell and its mesh, as for `fem.mesh`.
        snap (SnapCriterion; default None): What counts as the snap-through: `instability` (default, the
            stability test), `energy` (the inverted state stores less total potential energy; the whole
            cycle, `fem::cycle::energy`) or the thesis' staggered procedure, `{thesis: {passes: n,
            first_pass: ...}}` (`map::SnapCriterion`), which runs the loading leg only (W is then 0: no
            loop).
        stability (Stability; default None): Stability test: `lift_threshold` (default) or `tangent`
            (`shell::Stability`).
        steps (integer; required, 1..=100000): Equal load steps to delta_max (and back).

    Columns:
        leg [text]: `loading`, `unloading` or `unstable` (the unstable branch traced by arc length)
        leg_id [0, 1, 2]: the leg as a number (loading 0, unloading 1, unstable 2)
        state [text]: `flattened` or `inverted` branch
        R_mm [mm]: the shell's inner radius R
        h_mm [mm]: the shell's thickness h
        h_over_R [1]: thickness over inner radius
        gamma [N/mm]: work of adhesion Δγ
        mu [1]: Coulomb friction coefficient
        apex_force [F_c]: imperfection: the point force at the inner apex, away from the plate
        dimple [h]: imperfection: the depth of the apex dimple
        criterion [text]: what counts as the snap-through (`model.snap`): `local` (the stability test
            gives the flattened state up; `instability`), `landing`, `energy` (the inverted state lies
            lower by the friction work of the way there; `energy_friction`, the published one), `energy
            (no friction work)` (`energy`), `staggered (the thesis' procedure)` (`thesis`)
        delta_over_R [R]: plate displacement δ/R
        F_bar [F_c]: net plate force (contact minus adhesion), the force the figures draw
        F_error_bar [F_c]: the mesh's share of its error
        F_contact_bar [F_c]: the compressive contact force alone
        F_adhesive_bar [F_c]: the adhesive pull (negative); F_bar = F_contact_bar + F_adhesive_bar
        slip_fraction [1]: fraction of the contact nodes that slip
        p_max_over_E [E]: peak contact pressure
        p_apex_over_E [E]: contact pressure at the apex (0 once the contact is a ring)
        A_bar [Maugis' A]: contact radius
        contact_radius_over_R [R]: outermost contact radius
        max_penetration_over_h [h]: largest penetration of the penalty contact
        stable [boolean]: the state is stable under prescribed δ
        held [boolean]: a flattened state past the stability test with no inverted state reachable: the
            shell stays there
        converged [boolean]: the solver met its tolerance; a false row is recorded, not dropped
        termination [text]: why the solver stopped. `bem.sweep`: `converged`, `iteration_limit`,
            `stalled` (line searches cut the step to 1/16 several times in a row), `step_too_small` (no
            step lowered the residual), `diverged` (non-finite residual or direction), `off_branch` (a
            tensile state left the stable branch), `beyond_pull_off` (no stable state at that tensile
            load), `non_finite_friction`. `fem.indent` (per state): `converged`, `iteration_limit`,
            `no_step` (every trial step inverted an element), `no_descent` (the energy descent found no
            shift that lowers the potential), `unstable` (an equilibrium at a tangent that is not
            positive definite), `inverted` (the state could not be evaluated), `not_solved` (the
            reference state taken as the start when no adhering state was found)
        iterations [count]: Newton iterations (of a search such as `bem.maxima`: summed over its solves)
        residual [units of the solved equation]: the final residual's max-norm
        buckled [boolean]: the shell snapped through on loading
        F_buckling_bar [F_c]: net plate force at the snap (the last stable state)
        F_buckling_error_bar [F_c]: its error estimate (bisection bracket and mesh)
        F_buckling_mesh_error_bar [F_c]: the mesh's share
        delta_buckling_over_R [R]: plate displacement at the snap
        delta_landing_over_R [R]: where the snap lands on the inverted branch
        delta_snap_back_over_R [R]: where the shell snaps back on unloading
        W_bar [E h³ (F_c R)]: dissipated energy W = ∮ F dδ of the cycle
        W_error_bar [E h³]: its error estimate
        W_mesh_error_bar [E h³]: the mesh's share
        W_friction_bar [E h³]: the part of W dissipated by friction
        n_meridian [count]: elements along the meridian
        mesh_error_source [text]: where the mesh error comes from (`study`: a cycle on a mesh twice as
            fine along the meridian; `declared`: the default mesh's measured errors,
            `fem::mesh::default_mesh_rel_error` and `default_mesh_w_rel_error`; `none`)
        mesh_study_agrees [boolean]: both meshes agree on whether the shell snaps
        complete [boolean]: the cycle (or probe) reached its end
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["fem.mesh"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    E: float = ...,
    R: float = ...,
    grading: float = ...,
    h: float = ...,
    imperfection: Any = ...,
    integration: Any = ...,
    material: Any = ...,
    n_meridian: Optional[int] = ...,
    n_thickness: int = ...,
    nu: float = ...,
) -> Any:
    """Chapter 3: the meridian mesh of a hemispherical shell (8-node elements), one row per node

    Parameters:
        E (number; default 1.3, > 0): Young's modulus E (N/mm^2), default 1.3.
        R (number; required, > 0): Inner radius R (mm).
        grading (number; default 3.0, > 0): Ratio of the last to the first element size along the
            meridian (default 3: fine enough at the apex for the first contact, and at r ~ 0.6 R for the
            inverted state's ring).
        h (number; required, > 0): Thickness h (mm).
        imperfection (Imperfection; default None): Imperfection: `{apex_force: F/F_c, dimple: depth/h,
            width: /sqrt(R h)}` (default none).
        integration (Integration; default None): Gauss rule of the elements: `full` (3 x 3, default) or
            `reduced` (2 x 2, ANSYS PLANE183's).
        material (MaterialLaw; default None): Hyperelastic law: `neo_hookean` (default),
            `saint_venant_kirchhoff` or `hencky`.
        n_meridian (integer or null; default None, 4..=20000): Elements along the meridian (default: 1.5
            (R + h) / g0, so that the elements at the contact rim resolve the Lennard-Jones range g0;
            `fem::mesh::meridian_elements`) and through the thickness (default 2: quadratic elements
            carry the bending exactly).
        n_thickness (integer; default 2, 1..=16):
        nu (number; default 0.45, (-1, 0.5)): Poisson's ratio, default 0.45.

    Columns:
        r [mm]: node radius (`fem.mesh`)
        z [mm]: node height (`fem.mesh`)
        axis [boolean]: the node lies on the axis
        base [boolean]: the node lies on the clamped base
        outer [boolean]: the node lies on the outer surface
    """

@overload
def sweep(
    kind: Literal["fem.profile"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    cycle: Any = ...,
    points: Any = ...,
) -> Any:
    """Chapter 3: deformed meridian (outer and inner surface) and contact pressure at chosen plate
    displacements

    Parameters:
        cycle (IndentParams; required): The cycle, as the parameters of `fem.indent` (only its loading
            leg is computed, to the largest `points` delta if that is smaller than delta_max).
        points (array; required): The states to draw.

    Columns:
        label [text]: the named plate displacement of a profile (`fem.profile`)
        point [count]: the point's index along the surface
        surface_id [0, 1]: outer (0) or inner (1) surface
        delta_over_R [R]: plate displacement δ/R
        r_over_R [R]: contact radius at the snap (Eq. 3.7's r); in profiles, the radius of a surface
            point
        z_over_R [R]: height of a surface point
        p_over_E [E]: contact pressure at a surface point
        contact [0 or 1]: the point touches the plate
        inverted [boolean]: the state is on the inverted branch
        F_bar [F_c]: net plate force (contact minus adhesion), the force the figures draw
        F_contact_bar [F_c]: the compressive contact force alone
        F_error_bar [F_c]: the mesh's share of its error
        lu_factorizations [count]: LU factorisations of the shell's tangent over the whole task
            (`fem.buckling`, `fem.gamma_c`, `fem.buckling_limit`, `fem.indent` and `fem.profile` with
            their mesh study, on every row): one per Newton step or predictor whose tangent is not
            symmetric positive definite (friction, adhesion's softening, the unstable branch), failed
            runs included; the others are factored by Cholesky and not counted (0 on a frictionless
            loading that never leaves the stable branch)
        wall_time_s [s]: wall time of the row's task (the kind's own measurement, else the executor's);
            repeated on each row of a task: sum one per `task_key`
    """

@overload
def sweep(
    kind: Literal["figure"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    height: int = ...,
    layers: Any = ...,
    legend: Any = ...,
    log_x: bool = ...,
    log_y: bool = ...,
    title: str = ...,
    width: int = ...,
    x_label: str = ...,
    x_range: Optional[Any] = ...,
    y_label: str = ...,
    y_range: Optional[Any] = ...,
) -> Any:
    """An x-y figure (SVG) of columns of the needed stages, with its data as a long table

    Parameters:
        height (integer; default 560, >= 0):
        layers (array; required):
        legend (LegendPosition; default 'auto'):
        log_x (boolean; default False):
        log_y (boolean; default False):
        title (string; required):
        width (integer; default 800, >= 0):
        x_label (string; required): Axis label, with units or the dimensionless symbol.
        x_range (array or null; default None): Axis ranges (data units); default: the data's extent.
            `x_range` is also the range this figure shows of each data layer's `x` column: a sweep of
            that parameter may sample it (`{shown: n}`) and is checked against it.
        y_label (string; required):
        y_range (array or null; default None):

    Columns:
        series [text]: the curve's legend label
        x [`x_unit`]: the plotted abscissa
        y [`y_unit`]: the plotted ordinate
        x_name [text]: the table column plotted as x
        y_name [text]: the table column plotted as y (`guide` for guide lines)
        x_unit [text]: the unit of `x`: that of the column plotted (this file), the axis' for guide and
            fit lines
        y_unit [text]: the unit of `y`, likewise
        group_by [text]: the table column a layer groups its rows by (empty for an ungrouped series; the
            columns appear where some layer groups)
        group [text]: the point's group value as shown in the legend (empty for an ungrouped series)
        group_value [units of the group column]: the group value as a number, for filtering (0 for text
            groups and ungrouped series)
        group_unit [text]: the unit of the group column (docs/outputs.md; empty for ungrouped series and
            undocumented columns)
        y_error [units of y]: the error bar's half-height (0 without one)
    """

@overload
def sweep(
    kind: Literal["fit.powerlaw"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    expected_slope: Optional[float] = ...,
    from_: str = ...,
    group_by: Optional[str] = ...,
    x: str = ...,
    x_max: float = ...,
    x_min: float = ...,
    y: str = ...,
) -> Any:
    """Power law y = c x^s fitted over an x range (log-log least squares), with standard errors

    Parameters:
        expected_slope (number or null; default None): A reference slope (e.g. 5/4), reported beside the
            fitted one.
        from_ (string; required): The stage whose table is fitted (must be in `needs`).
        group_by (string or null; default None): One fit per distinct value of this (numeric) column.
        x (string; required):
        x_max (number; required):
        x_min (number; required, > 0): Only points with x in [x_min, x_max] are fitted.
        y (string; required):

    Columns:
        slope [1]: fitted exponent
        slope_std_error [1]: its standard error
        prefactor [units of y]: fitted prefactor
        prefactor_std_error [units of y]: its standard error
        r_squared [1]: coefficient of determination in log-log
        n_points [count]: points fitted
        x_min [units of x]: the fitted range's lower end
        x_max [units of x]: the fitted range's upper end
        expected_slope [1]: the thesis' slope, for comparison
    """

@overload
def sweep(
    kind: Literal["pb.calibrate"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    from_: str = ...,
    linear_range: Optional[Any] = ...,
    min_points: int = ...,
    slope_tolerance: float = ...,
    sqrt_range: Optional[Any] = ...,
    y: str = ...,
) -> Any:
    """Persson-Brener prefactor alpha (Eq. 5.18) fitted to F_T*(V0) curves: linear (Eq. 5.20) and square-
    root (Eq. 5.21) regimes

    Parameters:
        from_ (string; required): A `bem.sweep` stage (in `needs`): columns lambda, W, k, V0, converged
            and `y` (and s, for a power-law material: one curve per s; the laws are the SLS ones, so
            alpha is then an effective prefactor).
        linear_range (array or null; default None): Fixed V0 ranges instead of the detected regimes.
        min_points (integer; default 3, >= 3): The fewest points a regime may have (default 3).
        slope_tolerance (number; default 0.1, (0, 0.25)): A regime is the longest run of points whose
            local slopes d ln F / d ln V0 lie within this of the law's slope (1 or 1/2); default 0.1.
        sqrt_range (array or null; default None):
        y (string; default 'F_T'): The friction column (default F_T = mu* |W|, Eq. 5.6).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        regime [text]: `linear` (Eq. 5.20) or `sqrt` (Eq. 5.21)
        alpha [1]: Persson-Brener prefactor α (Eq. 5.18), geometric mean over the regime's points
        alpha_std_error [1]: its standard error
        alpha_spread [1]: the standard deviation of ln α over the regime's points
        n_points [count]: points fitted
        x_min [units of x]: the fitted range's lower end
        x_max [units of x]: the fitted range's upper end
        slope [1]: fitted exponent
        slope_std_error [1]: its standard error
        prefactor [units of y]: fitted prefactor
        fitted_slope [1]: the free log-log slope over the regime
        fitted_slope_std_error [1]: its standard error
    """

@overload
def sweep(
    kind: Literal["theory.adhesionless_friction_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    W_range: Any = ...,
    from_: str = ...,
) -> Any:
    """Persson's adhesionless maximum of mu* over V0 (Appendix A) for each k of a needed stage, across a
    load range

    Parameters:
        W_range (array; required): The load range the line spans, [from, to], 0 < from < to (the column
            `W`).
        from_ (string; required): The stage whose distinct modulus ratios are bounded (must be in
            `needs`; its table has the column `k`).

    Columns:
        k [1]: modulus ratio E0/E∞
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        mu_star_max_adhesionless [1]: Persson's adhesionless maximum of μ* over V0 for the row's k
            (Appendix A), which the maxima approach at large loads
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def sweep(
    kind: Literal["theory.hertz_jkr_pressure"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    P_bar: float = ...,
    n: int = ...,
) -> Any:
    """Hertz and JKR pressure p/p0_Hertz vs r/a_Hertz at the same load (Fig. 2.4)

    Parameters:
        P_bar (number; default 1.0, > 0): Load in Maugis' units, P = F / (pi w R); must exceed the JKR
            pull-off -3/2.
        n (integer; default 200, 10..=1000000): Number of radial points per model.

    Columns:
        model [text]: which closed form a row belongs to (`hertz`, `jkr`, `dmt`)
        P_bar [F/(π w R)]: load (positive: compressive)
        r_over_aH [a_Hertz]: radius in the Hertz contact radius (Fig. 2.4)
        p_over_p0H [p0_Hertz]: pressure in the Hertz peak pressure (Fig. 2.4)
    """

@overload
def sweep(
    kind: Literal["theory.jkr_friction_limit"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    from_: str = ...,
    lambda_range: Any = ...,
) -> Any:
    """The JKR limit of the friction mu* = pi^(1/2) / (2 W^(3/2) k) for each (W, k) of a needed stage,
    across a lambda range

    Parameters:
        from_ (string; required): The stage whose distinct (W, k) pairs are bounded (must be in `needs`;
            its table has the columns `W` and `k`).
        lambda_range (array; required): The lambda range the line spans, [from, to], 0 < from < to.

    Columns:
        W [W (Eq. 4.6)]: dimensionless load per unit length (negative: tensile, the cylinder beneath the
            substrate)
        k [1]: modulus ratio E0/E∞
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        mu_star_jkr [1]: the JKR limit of the friction, π^(1/2) / (2 |W|^(3/2) k) (the equation after
            Fig. 4.6), which max μ* approaches as λ grows
    """

@overload
def sweep(
    kind: Literal["theory.lennard_jones"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    n: int = ...,
    z_max: float = ...,
    z_min: float = ...,
) -> Any:
    """The Lennard-Jones 3-9 law of the solvers: energy/dgamma and pressure/sigma0 vs separation h/eps
    (Fig. 2.3)

    Parameters:
        n (integer; default 200, 2..=1000000):
        z_max (number; default 4.0):
        z_min (number; default 0.85, > 0): Separations h/eps from `z_min` to `z_max` (eps the
            equilibrium separation), `n` points.

    Columns:
        h_over_eps [ε]: separation over the equilibrium separation (Fig. 2.3)
        energy_over_dgamma [Δγ]: Lennard-Jones 3-9 energy per unit area
        pressure_over_sigma0 [σ0]: its disjoining pressure, compression positive
    """

@overload
def sweep(
    kind: Literal["theory.line_pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    lambda_: Sweep = ...,
) -> Any:
    """2D line-contact pull-off W: Maugis-Dugdale, JKR -3(pi/16)^(1/3), rigid Lennard-Jones -2.434
    sqrt(lambda)

    Parameters:
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter (sweepable).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        W_md [W (Eq. 4.6)]: pull-off load of the Maugis-Dugdale line contact
        A_md [β]: its contact half-width (0: reached as the contact closes)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        W_jkr [W]: the 2D JKR pull-off -3(π/16)^(1/3)
        W_rigid_lj [W]: the rigid Lennard-Jones limit -2.434 √λ
    """

@overload
def sweep(
    kind: Literal["theory.maugis_dugdale"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    A_max: float = ...,
    A_min: float = ...,
    lambda_: Sweep = ...,
    n: int = ...,
) -> Any:
    """Maugis-Dugdale sphere contact: load P_bar and approach vs contact radius A_bar (thesis 2.4.2.4)

    Parameters:
        A_max (number; default 2.5): Largest dimensionless contact radius A.
        A_min (number; default 0.02, > 0): Smallest dimensionless contact radius A.
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter lambda = 2 sigma0 (R /
            (pi w K^2))^(1/3) (sweepable).
        n (integer; default 200, 2..=1000000): Number of radii (log-spaced).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        A_bar [Maugis' A]: contact radius
        P_bar [F/(π w R)]: load (positive: compressive)
        approach_bar [Maugis' δ]: approach
        m [1]: Maugis-Dugdale ratio c/a of the cohesive zone's outer radius to the contact radius
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def sweep(
    kind: Literal["theory.maugis_pulloff"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    lambda_: Sweep = ...,
) -> Any:
    """Maugis-Dugdale pull-off load (minimum of P_bar over A_bar); JKR -3/2, DMT -2

    Parameters:
        lambda_ (number; required, > 0, sweepable): Maugis' transition parameter (sweepable).

    Columns:
        lambda [1]: Maugis(-Tabor) parameter: Maugis' λ in Chapter 2 stages, λ of Eq. 4.9 in Chapters
            4-5
        P_bar_pulloff [F/(π w R)]: pull-off load under load control
        A_bar_pulloff [Maugis' A]: contact radius at pull-off
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        P_bar_jkr [F/(π w R)]: JKR pull-off, -3/2
        P_bar_dmt [F/(π w R)]: DMT pull-off, -2
    """

@overload
def sweep(
    kind: Literal["theory.persson"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V0: Sweep = ...,
    inv_k: Sweep = ...,
    rel_tol: float = ...,
) -> Any:
    """Persson's adhesionless friction mu* = mu R/a0 vs V0 = v tau/a0 for a standard linear solid (Eqs.
    7.1-7.2)

    Parameters:
        V0 (number; required, (0, 1e100], sweepable): V0 = v tau / a0 (sweepable), in (0, 1e100]: beyond
            1e100 mu* (about 1/V0 there) underflows the quadrature's relative tolerance.
        inv_k (number; required, > 1, sweepable): 1/k = E_inf / E0 (sweepable), > 1.
        rel_tol (number; default 1e-08, [1e-14, 0.01)): Relative tolerance of the quadrature, in [1e-14,
            0.01): below 1e-14 double precision cannot meet it (at 1e-16 the quadrature refines for a
            minute and returns the same digits).

    Columns:
        inv_k [1]: E∞/E0 = 1/k
        k [1]: modulus ratio E0/E∞
        V0 [1]: speed v τ / a0 (Eq. 4.18; a0 the Hertz half-width of |W|)
        mu_star [1]: friction μ* = μ R/a0 (Eq. 4.16; Appendix A: Persson's adhesionless)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def sweep(
    kind: Literal["theory.persson_brener"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    V_PB: Sweep = ...,
    k: Sweep = ...,
    per_decade: Optional[int] = ...,
    prony: Optional[Any] = ...,
    s: Sweep = ...,
    tau_ratio: Optional[float] = ...,
) -> Any:
    """Persson-Brener G_trail/dgamma (Eq. 5.12, or Eq. 5.27 for a spectrum) and f_T/dgamma = G - 1/G (Eq.
    5.13) vs v/v0

    Parameters:
        V_PB (number; required, > 0, sweepable): V_PB = v / v0, v0 = c0 / (2 pi tau) (sweepable).
        k (number; required, (0, 1), sweepable): Modulus ratio k = E0 / E_inf in (0, 1) (sweepable).
        per_decade (integer or null; default None, 1..=64): Power-law spectrum: bins per decade of its
            discretisation (default 8).
        prony (array or null; default None): Material: a Maxwell-Wiechert relaxation Prony series,
            [[weight, relaxation time / tau], ...] (weights normalised; with k it fixes the creep
            function, Eq. 2.27).
        s (number or null; default None, [0, 1), sweepable): Material: the exponent s in [0, 1) of the
            power-law retardation spectrum S(tau) ~ tau^-s on (tau1, tau2) (Eq. 5.24), sweepable; then
            tau = tau2 (in V0 or v0). Default: the standard linear solid.
        tau_ratio (number or null; default None, (0, 1)): Power-law spectrum: tau1/tau2 (default 1e-6).

    Columns:
        k [1]: modulus ratio E0/E∞
        V_PB [v/v0]: Persson-Brener speed
        G_trail_over_dgamma [Δγ]: energy release rate at the trailing edge (Eq. 5.12)
        F_T_PB [Δγ]: Persson-Brener friction f_T/Δγ = G - 1/G (Eq. 5.13)
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
        s [1]: exponent of the power-law retardation spectrum (Eq. 5.24)
        tau_ratio [1]: τ1/τ2, the power-law spectrum's shortest retardation time over its longest
        n_eq_5_28 [1]: the power-law exponent (1-s)/(2-s) of Eq. 5.28
        material [text]: the viscoelastic material (`SLS k = ...`, a Prony series, a power law)
    """

@overload
def sweep(
    kind: Literal["theory.persson_max"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    inv_k: Sweep = ...,
    rel_tol: float = ...,
) -> Any:
    """Maximum over V0 of Persson's adhesionless mu*, and where it occurs

    Parameters:
        inv_k (number; required, > 1, sweepable): 1/k = E_inf / E0 (sweepable), > 1.
        rel_tol (number; default 1e-08, [1e-14, 0.01)):

    Columns:
        inv_k [1]: E∞/E0 = 1/k
        k [1]: modulus ratio E0/E∞
        mu_star_max [1]: maximum of μ* over V0
        V0_at_max [1]: the V0 of that maximum
        error_estimate [units of the main result]: a bound on the error of the row's main result
            (Richardson share, quadrature or bracket; docs/performance.md)
    """

@overload
def sweep(
    kind: Literal["theory.sphere_limits"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    A_max: float = ...,
    A_min: float = ...,
    n: int = ...,
) -> Any:
    """Hertz (P = A^3), JKR (A^3 - sqrt(6 A^3)) and DMT (A^3 - 2) curves in Maugis' units

    Parameters:
        A_max (number; default 2.5):
        A_min (number; default 0.02, > 0):
        n (integer; default 200, 2..=1000000):

    Columns:
        model [text]: which closed form a row belongs to (`hertz`, `jkr`, `dmt`)
        A_bar [Maugis' A]: contact radius
        P_bar [F/(π w R)]: load (positive: compressive)
    """

@overload
def sweep(
    kind: Literal["util.fail"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    message: str = ...,
    panic: bool = ...,
    x: Sweep = ...,
) -> Any:
    """Fails with `message` when x <= 0 (for testing the orchestrator)

    Parameters:
        message (string; required): The error message.
        panic (boolean; default False): Also panic instead of returning an error.
        x (number; default 0.0, sweepable): Positive: output this value instead of failing; the failure
            happens when `x <= 0`.

    Columns:
        x [`x_unit`]: the plotted abscissa
    """

@overload
def sweep(
    kind: Literal["util.sleep"],
    params: Optional[Mapping[str, Any]] = None,
    /,
    *,
    cache: Optional[Path] = None,
    jobs: Optional[int] = None,
    progress: Optional[bool] = None,
    backend: str = 'pandas',
    raise_on_unconverged: bool = False,
    wait: bool = True,
    ms: int = ...,
    round: Optional[int] = ...,
    x: Sweep = ...,
) -> Any:
    """Waits `ms` milliseconds and returns `x` (for testing the orchestrator)

    Parameters:
        ms (integer; default 0, >= 0): Milliseconds to wait before returning (a checkpoint of the time
            limit every 10 ms).
        round (integer or null; default None): Output `x` rounded to this many decimals (lets tests
            produce identical outputs from different parameters).
        x (number; required, sweepable): Value echoed into the output table (sweepable).

    Columns:
        x [`x_unit`]: the plotted abscissa
        upstream_rows []: (see docs/outputs.md)
        upstream_x []: (see docs/outputs.md)
    """

@overload
def sweep(kind: str, params: Optional[Mapping[str, Any]] = None, /, *, cache: Optional[Path] = None, jobs: Optional[int] = None, progress: Optional[bool] = None, backend: str = 'pandas', raise_on_unconverged: bool = False, wait: bool = True, **kw: Any) -> Any: ...
