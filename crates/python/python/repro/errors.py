"""The exceptions of ``repro``: one base class, and one class per way a call can fail.

Each carries the message the command line prints for the same mistake.
"""

__all__ = [
    "ReproError",
    "InvalidParameter",
    "UnknownKind",
    "InvalidPipeline",
    "UsageError",
    "TaskFailed",
    "NotConverged",
    "CacheError",
    "CacheBusy",
]


class ReproError(Exception):
    """Every error ``repro`` raises (but ``KeyboardInterrupt``) is one of these."""


class InvalidParameter(ReproError, ValueError):
    """A parameter of a point or sweep is unknown, of the wrong type or out of its range."""


class UnknownKind(InvalidParameter, KeyError):
    """No stage kind has this name (``repro.kinds()`` lists them)."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""


class InvalidPipeline(ReproError, ValueError):
    """A pipeline file (or an override set over it) is invalid; nothing was run.

    ``diagnostics`` lists each error as ``(file, line, column, message)``; ``str(e)``
    prints them as ``repro run`` does (``file:line:column: error: message``)."""

    def __init__(self, message, diagnostics=()):
        super().__init__(message)
        self.diagnostics = [tuple(d) for d in diagnostics]


class UsageError(ReproError, ValueError):
    """An option names what the pipeline does not have (a target, a stage to force), or an
    override is not ``stage.param=value``."""


class TaskFailed(ReproError):
    """A task failed, panicked, timed out or ran out of memory; the others ran.

    ``failures`` lists them as ``"stage [point]: reason"``; for a run, ``run`` holds the
    :class:`repro.Run` with everything that completed."""

    def __init__(self, message, failures=(), run=None):
        super().__init__(message)
        self.failures = list(failures)
        self.run = run


class NotConverged(ReproError):
    """Rows whose solver did not meet its tolerance (``converged`` false), raised only when
    asked (``raise_on_unconverged=True``); ``rows`` holds them, with their ``termination``."""

    def __init__(self, message, rows=None):
        super().__init__(message)
        self.rows = rows


class CacheError(ReproError, OSError):
    """The cache or an output folder could not be read or written."""


class CacheBusy(CacheError):
    """Another process holds the cache."""
