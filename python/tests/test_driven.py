"""A driven granular gas (``[thermostat]``, ``docs/granular.md``): ``noslip.simulate`` runs a
scene with a white-noise thermostat, its kicks counted and their energy in the summary,
``observables=`` sampled; bad thermostats refused naming the field (scene and Python)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import noslip
from noslip.granular import driven_gas, driven_ratio, two_temperature_ratio


def test_a_driven_gas_is_kicked_and_keeps_its_temperature() -> None:
    # 300 spheres at phi = 0.02, e = beta = 0.9; kicks every 0.05 up to t = 10: 200 kicks.
    # strength 0.185 holds T_tr near 1: n (N - 1) m xi^2 / N = omega_1 T^(3/2) (a - b c / d),
    # omega_1 = 4 sqrt(pi) rho chi = 0.284, a - b c / d = 0.359 (sim/tests/driven.rs).
    scene = driven_gas(0.9, 0.9, strength=0.185, interval=0.05, balls=300)
    assert "[thermostat]" in scene.toml and "driven rough gas" in scene.description
    run = noslip.simulate(scene, time=10.0, observables=0.5)
    s = run.summary
    assert s["kicks"] == 200
    # The kicks inject n (N - 1) m xi^2 dt / 2 = 3 * 299 * 0.034225 * 0.05 / 2 = 0.7675 each
    # on average, 153.5 in all; the random cross term sum m u . dv has standard deviation
    # sqrt(2 E_tr xi^2 dt) = 1.24 per kick at T_tr = 1 (E_tr = 450), 17.6 over 200 kicks:
    # within six of those.
    assert abs(s["energy_injected"] - 153.5) < 6 * 17.6, s
    obs = run.observables
    # A row at the start and at the first contact after each of t = 0.5, 1, ..., 9.5 (the
    # first after 10 is past the run's end).
    assert len(obs["time"]) == 20
    # T_tr stays near 1: a single run's temperature wanders by the kicks' random energy (17.6
    # of 450, 4 %) and its own fluctuations (sqrt(2 / 897) = 5 % a row); the late rows' mean
    # within 20 % (the theory itself is within a few per cent at beta = 0.9).
    late = obs["T_tr"][10:]
    assert 0.8 < float(np.mean(late)) < 1.2, obs["T_tr"]
    # The energy the contacts took is positive and at most what was there and came in.
    lost = obs["lost_ball_ball"][-1]
    assert 0 < lost < s["energy_start"] + s["energy_injected"]
    # The kicks' energy, row by row, balances the energy with the contacts' losses: an
    # identity up to rounding, bounded as sim/tests/driven_observables.rs derives it, with
    # C contacts and K kicks in an interval, 300 balls, E_max twice the largest energy and W
    # the largest running total: (64 C + (16 + 600) K + 40 * 300) eps E_max + (C + K + 10) eps W.
    kinds = ("ball_ball", "ball_wall", "ball_obstacle", "ball_boundary")
    lost_all = sum(obs[f"lost_{k}"] for k in kinds)
    balance = np.diff(obs["energy"]) - (np.diff(obs["injected"]) - np.diff(lost_all))
    c = np.diff(obs["contacts"]).astype(float)
    k = np.diff(np.floor(obs["time"] / 0.05))
    eps = np.finfo(float).eps
    e_max = 2 * obs["energy"].max()
    w = max(obs["injected"][-1], *(obs[f"lost_{k}"][-1] for k in kinds))
    bound = (64 * c + 616 * k + 12000) * eps * e_max + (c + k + 10) * eps * w
    assert (np.abs(balance) <= bound).all(), (balance, bound)
    assert obs["injected"][-1] <= s["energy_injected"] and obs["injected"][0] == 0
    # The kicks end the flights of the displacements: msd is known (and grows) when driven.
    assert np.isfinite(obs["msd"]).all() and np.isfinite(obs["msd_cm"]).all()
    assert obs["msd"][0] == 0 and obs["msd"][-1] > obs["msd"][1] > 0
    # The same scene runs bit for bit again (seeded kicks).
    again = noslip.simulate(scene, time=10.0, observables=0.5)
    assert np.array_equal(again.observables["T_tr"], obs["T_tr"])


def test_the_driven_ratio_is_the_rotational_balance() -> None:
    # c / d = eta / (1 - eta / k): 0.8444 for solid spheres and 0.8636 for disks at
    # beta = 0.9 (sim/tests/driven.rs); independent of e; below the cooling state's ratio.
    assert round(driven_ratio(3, 0.9, 0.9), 4) == 0.8444
    assert round(driven_ratio(2, 0.9, 0.9), 4) == 0.8636
    assert driven_ratio(3, 0.7, 0.9) == driven_ratio(3, 0.9, 0.9)
    assert driven_ratio(3, 0.9, 0.9) < two_temperature_ratio(3, 0.9, 0.9)
    # Elastic perfectly rough balls: equipartition.
    assert driven_ratio(3, 1.0, 1.0) == pytest.approx(1.0, abs=1e-12)
    assert math.isnan(driven_ratio(3, 0.9, -1.0))


@pytest.mark.parametrize("field", ["strength", "interval"])
@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf])
def test_bad_thermostats_are_named(field: str, value: float) -> None:
    args = {"strength": 1.0, "interval": 0.1, field: value}
    with pytest.raises(ValueError, match=f"^{field}:"):
        driven_gas(0.9, 0.9, **args)


def test_a_bad_thermostat_in_a_scene_is_named() -> None:
    base = {
        "dim": 2,
        "box": {"size": [10, 10], "boundary": ["periodic", "periodic"]},
        "species": [{"mass": 1, "radius": "1/2", "count": 4}],
    }
    for thermostat, says in [
        ({"kind": "white-noise", "strength": 0, "interval": 1},
         "thermostat.strength: must be positive, got 0"),
        ({"kind": "white-noise", "strength": 1, "interval": "-1/2"},
         "thermostat.interval: must be positive, got -1/2"),
        ({"kind": "shaker", "strength": 1, "interval": 1},
         'thermostat.kind: must be "white-noise", got "shaker"'),
    ]:
        with pytest.raises(noslip.InputError, match="thermostat"):
            noslip.Scene.from_dict({**base, "thermostat": thermostat})
        try:
            noslip.simulate({**base, "thermostat": thermostat}, time=1.0)
        except noslip.InputError as e:
            assert says in str(e), str(e)
        else:
            raise AssertionError("accepted")


def test_a_driven_log_keeps_the_contacts_as_its_events() -> None:
    # The kick lines of the events log (docs/granular.md) are not contacts: `events` holds
    # one row per contact, as many as the summary counts, in time order.
    scene = driven_gas(0.9, 0.9, strength=0.185, interval=0.05, balls=100)
    run = noslip.simulate(scene, time=2.0, log=True)
    assert run.summary["kicks"] == 40
    assert len(run.events["time"]) == run.summary["events"] > 0
    assert (np.diff(run.events["time"]) >= 0).all()
    # The kicks have arrays of their own (the log's kick lines): numbered from 1, every 0.05,
    # every ball's velocity after each.
    ev = run.events
    assert ev["kick"].tolist() == list(range(1, 41))
    assert np.allclose(ev["kick_time"], 0.05 * ev["kick"], rtol=1e-12, atol=0)
    assert ev["kick_velocities"].shape == (40, 100, 3)
    assert ev["kick_energy_injected"].shape == (40,)
    # Their energies add up to the summary's, in the same order (the same bits).
    total = 0.0
    for e in ev["kick_energy_injected"]:
        total += float(e)
    assert total == run.summary["energy_injected"]
    # The total momentum (equal masses: the velocities' sum) is the same after every kick:
    # the contacts and the kicks keep it, to rounding.
    p = ev["kick_velocities"].sum(axis=1)
    scale = np.abs(ev["kick_velocities"]).sum(axis=1).max()
    assert np.abs(p - p[0]).max() <= 1e-12 * scale
    # Without a thermostat, no kicks.
    cooling = Path(__file__).resolve().parents[2] / "scenes" / "granular3d.toml"
    calm = noslip.simulate(cooling, events=100, log=True).events
    assert calm["kick"].shape == (0,) and calm["kick_velocities"].shape[0] == 0
