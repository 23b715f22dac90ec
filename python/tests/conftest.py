"""Shared fixtures: the `slambox` CLI built beside the module (SLAMBOX_BINARY, set by CTest)."""
import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs `slambox ARGS...`, returning the CompletedProcess (text)."""
    binary = os.environ.get("SLAMBOX_BINARY")
    if not binary or not os.path.exists(binary):
        pytest.skip("SLAMBOX_BINARY is not set to the slambox CLI (CTest sets it)")

    def run(*args, check=True):
        return subprocess.run([binary, *map(str, args)], capture_output=True, text=True, check=check)

    return run
