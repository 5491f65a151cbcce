"""noslip.verify and noslip.report return the reports of the Rust crates as Python objects."""

import pytest

import noslip


def test_verify_passes_and_reports_every_check():
    out = noslip.verify(dims=[2, 3], points=2)
    assert out["passed"] is True
    assert {r["dim"] for r in out["results"]} == {2, 3}
    assert all(r["passed"] for r in out["results"]) and len(out["results"]) > 20


def test_report_measures_the_no_slip_kernels_and_the_rough_family():
    out = noslip.report(dims=[2], samples=20)
    (dim,) = out["dims"]
    assert dim["dim"] == 2 and len(dim["regimes"]) == 9
    family = {r["regime"]: r for r in dim["family"]}
    assert set(family) == {
        "rough", "rough_ends", "rough_near_ends", "rough_immovable", "rough_grazing",
        "walton", "walton_switch",
    }
    for r in family.values():
        f64 = next(v for v in r["variants"] if v["variant"] == "f64")
        # Every sampled case ran, none gave a NaN or an infinity.
        assert f64["evaluated"] == 20 and f64["non_finite"] == 0, r["name"]
        assert r["stability"]["over_conditioning"] == 0, r["name"]
    assert family["walton"]["kernel"] == "walton" and family["rough"]["kernel"] == "rough"
    # The static bound over each regime's box holds for every sampled case in the box.
    typical = next(r for r in dim["regimes"] if r["regime"] == "typical")
    for name in ("f64", "f64_fma", "f32"):
        s = next(v for v in typical["variants"] if v["variant"] == name)["static_bound"]
        assert s["in_box"] > 0 and s["broken"] == 0, name
        assert 0 < s["measured_eps"] < s["bound_eps"] < float("inf"), name


def test_bad_dims_are_input_errors():
    with pytest.raises(noslip.InputError, match=r"^dims: 7 has no generated kernels"):
        noslip.verify(dims=[7])
    with pytest.raises(noslip.InputError, match=r"^samples: must be in 1\.\.=100000, got 0$"):
        noslip.report(dims=[2], samples=0)


def test_negative_and_huge_ints_are_named():
    """Not PyO3's bare `OverflowError: can't convert negative int to unsigned`."""
    cases = [
        (lambda: noslip.verify(points=-1), r"^points: must be an integer in 1\.\.=\d+, got -1$"),
        (lambda: noslip.verify(dims=[2, -2]),
         r"^dims\[1\]: must be an integer in 0\.\.=\d+, got -2$"),
        (lambda: noslip.report(samples=-5), r"^samples: must be an integer in 1\.\.=\d+, got -5$"),
        (lambda: noslip.report(seed=10**30),
         r"^seed: must be an integer in 0\.\.=\d+, got 10{30}$"),
    ]
    for call, message in cases:
        with pytest.raises(noslip.InputError, match=message):
            call()


def test_counts_past_their_cap_are_named():
    """The caps of `noslip verify --points` and `noslip report --samples` (a huge count ran for
    ever, or grew memory without limit)."""
    with pytest.raises(noslip.InputError, match=r"^points: must be in 1\.\.=1024, got 1025$"):
        noslip.verify(dims=[2], points=1025)
    with pytest.raises(noslip.InputError, match=r"^samples: must be in 1\.\.=100000, got 100001$"):
        noslip.report(dims=[2], samples=100001)
