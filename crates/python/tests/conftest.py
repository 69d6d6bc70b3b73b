"""Shared fixtures: the command line built from the same workspace (`cargo build`), to
compare the package with."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def repro_bin():
    path = pathlib.Path(os.environ.get("REPRO_BIN", ROOT / "target" / "debug" / "repro"))
    if not path.exists():
        subprocess.run(["cargo", "build", "--quiet"], cwd=ROOT, check=True)
    return str(path)


@pytest.fixture
def cli(repro_bin):
    def run(*args, check=True, cwd=None):
        p = subprocess.run([repro_bin, *map(str, args)], capture_output=True, text=True, cwd=cwd)
        if check and p.returncode != 0:
            raise AssertionError(f"repro {' '.join(map(str, args))} exited {p.returncode}:\n{p.stderr}")
        return p

    return run
