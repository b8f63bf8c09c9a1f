"""Shared fixtures of the Python module's tests. CTest runs them with PYTHONPATH pointing at the
built package (build/python) and SINEW_CLI at the built command-line tool."""
import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root():
    return ROOT


@pytest.fixture(scope="session")
def examples():
    return ROOT / "examples"


@pytest.fixture(scope="session")
def cli():
    path = os.environ.get("SINEW_CLI") or shutil.which("sinew") or str(ROOT / "build" / "sinew")
    if not pathlib.Path(path).exists():
        pytest.skip("the sinew CLI is not built")
    return path
