"""Writes the package's type stubs (``__init__.pyi``) from the kinds' declarations: an
overload of ``point`` and ``sweep`` per kind, whose keywords are its parameters (typed,
``lambda`` spelled ``lambda_``) and whose docstring gives their meanings, ranges and units
and the kind's output columns. An editor then completes parameters and shows their units.

Regenerate after a kind's parameters change: ``python3 -m repro._stubs >
crates/python/python/repro/__init__.pyi`` (a test checks the committed file is current).
"""

import dataclasses
import inspect
import keyword
import textwrap
import typing

import repro

HEAD = '''"""Type stubs of repro, generated from the stage kinds' declarations by
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

{dataclasses}
{api}
Sweep = Union[float, Sequence[float], np.ndarray, Mapping[str, Any]]
Path = Union[str, os.PathLike]
'''

def annotation(t) -> str:
    """A field's type as the stub writes it: `str`, `Any`, `List[Param]`."""
    if isinstance(t, type):
        return t.__name__
    return str(t).replace("typing.", "").replace("repro.", "")


def dataclass_stubs() -> str:
    """The stub of each dataclass of the API, from its fields and public methods."""
    out = []
    for cls in (repro.Param, repro.Column, repro.KindDescription):
        lines = ["@dataclass(frozen=True)", f"class {cls.__name__}:"]
        lines += [f"    {f.name}: {annotation(f.type)}" for f in dataclasses.fields(cls)]
        for name, fn in vars(cls).items():
            if callable(fn) and not name.startswith("_"):
                hints = typing.get_type_hints(fn)
                args = ", ".join(f"{a}: {annotation(hints[a])}" for a in list(fn.__code__.co_varnames)[1 : fn.__code__.co_argcount])
                lines.append(f"    def {name}(self, {args}) -> {annotation(hints['return'])}: ...")
        out.append("\n".join(lines) + "\n")
    return "\n".join(out)


def signature(fn) -> str:
    """A function's signature as the stub writes it, from the function itself."""
    return str(inspect.signature(fn)).replace("repro.", "").replace("NoneType", "None")


def api_stubs() -> str:
    """The stub of `Run` (its annotated attributes, properties and methods) and of the
    functions without a per-kind overload, from the objects themselves."""
    lines = ["class Run:"]
    lines += [f"    {name}: {annotation(t)}" for name, t in typing.get_type_hints(repro.Run).items()]
    for name, member in vars(repro.Run).items():
        if name.startswith("_"):
            continue
        if isinstance(member, property):
            lines += ["    @property", f"    def {name}(self) -> {annotation(typing.get_type_hints(member.fget)['return'])}: ..."]
        elif callable(member):
            lines.append(f"    def {name}{signature(member)}: ...")
    lines.append("")
    lines += [f"def {fn.__name__}{signature(fn)}: ..." for fn in (repro.kinds, repro.describe, repro.run)]
    return "\n".join(lines) + "\n"


TYPES = {"number": "float", "integer": "int", "boolean": "bool", "string": "str"}


def py_type(t: str, sweepable: bool, sweep: bool) -> str:
    if sweep and sweepable:
        return "Sweep"
    alts = [a.strip() for a in t.split(" or ")]
    names = [TYPES.get(a, "Any") for a in alts if a != "null"]
    base = names[0] if len(set(names)) == 1 else "Any"
    return f"Optional[{base}]" if "null" in alts else base


def keyword_name(name: str) -> str:
    return f"{name}_" if keyword.iskeyword(name) else name


def docstring(d) -> str:
    lines = [d.doc, "", "Parameters:"]
    for p in d.params:
        state = "required" if p.required else f"default {p.default!r}"
        rng = f", {p.range}" if p.range else ""
        sweep = ", sweepable" if p.sweepable else ""
        lines.append(f"    {keyword_name(p.name)} ({p.type}; {state}{rng}{sweep}): {p.meaning}")
    if d.columns:
        lines += ["", "Columns:"]
        lines += [f"    {c.name} [{c.unit}]: {c.meaning}" for c in d.columns]
    def wrap(line):
        indent = "        " if line.startswith("    ") else ""
        return textwrap.fill(line, 100, subsequent_indent=indent) if line else ""

    body = "\n".join(wrap(line) for line in lines)
    return textwrap.indent('"""' + body.replace('"""', "'''") + '\n"""', "    ")


def overload(d, fn: str) -> str:
    extra = (
        ["raise_on_unconverged: bool = False"]
        if fn == "point"
        else [
            "cache: Optional[Path] = None",
            "jobs: Optional[int] = None",
            "progress: Optional[bool] = None",
            "backend: str = 'pandas'",
            "raise_on_unconverged: bool = False",
            "wait: bool = True",
        ]
    )
    params = [f"{keyword_name(p.name)}: {py_type(p.type, p.sweepable, fn == 'sweep')} = ..." for p in d.params]
    ret = "Dict[str, Any]" if fn == "point" else "Any"
    args = ",\n    ".join(
        [f'kind: Literal["{d.name}"]', "params: Optional[Mapping[str, Any]] = None", "/", "*", *extra, *params]
    )
    return f"@overload\ndef {fn}(\n    {args},\n) -> {ret}:\n{docstring(d)}\n"


def render() -> str:
    out = [HEAD.replace("{dataclasses}", dataclass_stubs()).replace("{api}", api_stubs())]
    for fn in ("point", "sweep"):
        for name in repro.kinds():
            out.append(overload(repro.describe(name), fn))
        generic = (
            "raise_on_unconverged: bool = False, **kw: Any) -> Dict[str, Any]: ..."
            if fn == "point"
            else "cache: Optional[Path] = None, jobs: Optional[int] = None, progress: Optional[bool] = None, "
            "backend: str = 'pandas', raise_on_unconverged: bool = False, wait: bool = True, **kw: Any) -> Any: ..."
        )
        out.append(f"@overload\ndef {fn}(kind: str, params: Optional[Mapping[str, Any]] = None, /, *, {generic}\n")
    return "\n".join(out)


if __name__ == "__main__":
    print(render(), end="")
