"""Paths shared by the tests: the repository root (reference data, the `eom` binary)."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
