"""noslip.verify and noslip.report return the reports of the Rust crates as Python objects."""

import noslip


def test_verify_passes_and_reports_every_check():
    out = noslip.verify(dims=[2, 3], points=2)
    assert out["passed"] is True
    assert {r["dim"] for r in out["results"]} == {2, 3}
    assert all(r["passed"] for r in out["results"]) and len(out["results"]) > 20


def test_bad_dims_are_input_errors():
    import pytest

    with pytest.raises(noslip.InputError, match=r"^dims: 7 has no generated kernels"):
        noslip.verify(dims=[7])
    with pytest.raises(noslip.InputError, match=r"^samples: must be at least 1"):
        noslip.report(dims=[2], samples=0)
