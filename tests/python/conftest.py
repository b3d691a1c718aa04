# Shared fixture: the built CLI (DIFFRAY_CLI, set by CTest), which the Python results are compared with.
import os

import pytest


@pytest.fixture
def cli():
    path = os.environ.get("DIFFRAY_CLI")
    if not path:
        pytest.skip("DIFFRAY_CLI is not set (CTest sets it)")
    return path

