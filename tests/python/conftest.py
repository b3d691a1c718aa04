# Shared fixtures: the built CLI (DIFFRAY_CLI) and the repository's rooms (DIFFRAY_ROOMS), both set by CTest.
import os
import pathlib

import pytest


@pytest.fixture
def cli():
    path = os.environ.get("DIFFRAY_CLI")
    if not path:
        pytest.skip("DIFFRAY_CLI is not set (CTest sets it)")
    return path


@pytest.fixture
def rooms():
    return pathlib.Path(os.environ.get("DIFFRAY_ROOMS", pathlib.Path(__file__).parents[2] / "rooms"))
