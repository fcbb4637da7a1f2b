# SPDX-License-Identifier: GPL-3.0-or-later
"""Fixtures of the Python module's tests (run by ctest: tests/CMakeLists.txt sets the paths)."""
import os
import pathlib

import pytest


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(os.environ["ROIFEM_SOURCE_DIR"])


@pytest.fixture(scope="session")
def scenarios(source_dir):
    return source_dir / "scenarios"


@pytest.fixture(scope="session")
def cli():
    return os.environ["ROIFEM_CLI"]
