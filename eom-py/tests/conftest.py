"""Paths shared by the tests: the repository root (reference data, the `eom` binary)."""

import os
import shutil
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def eom_binary():
    """The `eom` CLI of this checkout (target/release), else one on the PATH."""
    exe = ROOT / "target" / "release" / "eom"
    if exe.exists():
        return str(exe)
    found = shutil.which("eom")
    if found is None:
        if os.environ.get("EOM_REQUIRE_CLI"):
            pytest.fail("EOM_REQUIRE_CLI is set but no eom binary (cargo build --release)")
        pytest.skip("no eom binary (cargo build --release -p eom-cli)")
    return found
