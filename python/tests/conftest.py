"""Shared fixtures: the repository and the `noslip` command the Python results are
compared with."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli() -> Path:
    """The release `noslip` binary of this checkout (built if missing, as CI has it)."""
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    binary = target / "release" / "noslip"
    if not binary.exists():
        subprocess.run(
            ["cargo", "build", "--release", "-p", "noslip"], cwd=ROOT, check=True
        )
    return binary


def run_cli(cli: Path, *args: str, stdin: str | None = None) -> str:
    out = subprocess.run(
        [str(cli), *args], input=stdin, capture_output=True, text=True, check=False
    )
    assert out.returncode == 0, out.stderr
    return out.stdout
