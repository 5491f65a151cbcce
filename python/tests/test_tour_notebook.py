"""The notebook tour, ``examples/tour.ipynb``, executed as a reader would run it (nbclient,
an ipykernel in this venv, from ``examples/``): every cell runs without error, and what its
cells check comes out as it should (energy conserved exactly, the animation shown, the
sweep read back from its store)."""

from __future__ import annotations

import time
from pathlib import Path
from typing import Any

import pytest

ROOT = Path(__file__).resolve().parents[2]
TOUR = ROOT / "examples" / "tour.ipynb"


def text_of(cell: dict[str, Any]) -> str:
    """A code cell's printed and displayed text."""
    parts = []
    for out in cell.get("outputs", []):
        if out.get("output_type") == "stream":
            parts.append("".join(out["text"]))
        data = out.get("data", {})
        for kind in ("text/plain", "text/html"):
            if kind in data:
                parts.append("".join(data[kind]))
    return "\n".join(parts)


def test_the_tour_runs(tmp_path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(str(TOUR), as_version=4)
    begun = time.monotonic()
    client = nbclient.NotebookClient(
        notebook,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(ROOT / "examples")}},
    )
    client.execute()
    seconds = time.monotonic() - begun
    # nbclient raised on any cell's error; now what the cells check. Cells: imports, one
    # collision, exact, batch, portrait, animation, sweep, the sweep again.
    code = [c for c in notebook.cells if c.cell_type == "code"]
    outputs = [text_of(c) for c in code]
    assert len(code) == 8
    assert outputs[2].strip().splitlines()[-1].endswith(" True"), outputs[2]
    assert "max relative energy change" in outputs[3]
    assert any("image/png" in out.get("data", {}) for out in code[4].outputs)
    assert "<iframe srcdoc=" in outputs[5] and "noslip-data" in outputs[5]
    assert outputs[7].startswith("the same frame from the store: True"), outputs[7]
    print(f"tour: {seconds:.1f} s")
