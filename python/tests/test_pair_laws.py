"""A ball-ball contact law per pair of species (``[[contact.pair]]``, issue 27) in Python:
``Scene(text)`` and ``Scene.from_dict`` read it, ``Scene.ball_laws`` shows every pair's law,
a bad pair raises ``InputError`` naming the field, and the shipped mixture simulates."""

from fractions import Fraction

import numpy as np
import pytest

import noslip

GAS = {
    "dim": 2,
    "box": {"size": [20, 20], "boundary": ["periodic", "periodic"]},
    "species": [
        {"name": "grain", "mass": 1, "radius": "1/2", "count": 20},
        {"name": "tracer", "mass": 4, "radius": 1, "count": 4},
    ],
    "contact": {
        "balls": {"e": "0.9", "beta": "0.5"},
        "pair": [
            {"species": ["tracer", "grain"], "law": {"e": "0.8", "beta": "-1/5"}},
            {"species": [1, 1], "law": "smooth"},
        ],
    },
}

TEXT = """dim = 2
[box]
size = [20, 20]
boundary = ["periodic", "periodic"]
[[species]]
name = "grain"
mass = 1
radius = "1/2"
count = 20
[[species]]
name = "tracer"
mass = 4
radius = 1
count = 4
[contact]
balls = { e = "0.9", beta = "0.5" }
[[contact.pair]]
species = ["tracer", "grain"]
law = { e = "0.8", beta = "-1/5" }
[[contact.pair]]
species = [1, 1]
law = "smooth"
"""


def test_pairs_are_read_from_text_and_dict_and_shown_by_ball_laws():
    expected = {
        ("grain", "grain"): {"e": Fraction(9, 10), "beta": Fraction(1, 2)},
        ("grain", "tracer"): {"e": Fraction(4, 5), "beta": Fraction(-1, 5)},
        ("tracer", "tracer"): "smooth",
    }
    for scene in (noslip.Scene(TEXT), noslip.Scene.from_dict(GAS)):
        assert scene.ball_laws == expected
    # Without pairs every pair has contact.balls; a Walton law keeps its three numbers.
    plain = noslip.Scene.from_dict({**GAS, "contact": {"balls": "no-slip"}})
    assert set(plain.ball_laws.values()) == {"no-slip"}
    walton = {"e": Fraction(7, 10), "mu": Fraction(3, 10), "beta0": Fraction(3, 5)}
    scene = noslip.Scene.from_dict(
        {**GAS, "contact": {"pair": [{"species": ["grain", "tracer"], "law": walton}]}}
    )
    assert scene.ball_laws[("grain", "tracer")] == walton
    assert scene.ball_laws[("grain", "grain")] == "no-slip"


def test_the_shipped_mixture_simulates(root):
    scene = noslip.Scene.from_file(root / "scenes" / "mixture2d.toml")
    laws = scene.ball_laws
    assert laws[("grain", "tracer")] == {"e": Fraction(4, 5), "beta": Fraction(-1, 5)}
    result = noslip.simulate(scene, events=300)
    assert result.summary["events"] == 300


def pair_dict(species, law):
    contact = {"pair": [{"species": ["grain", "tracer"], "law": "smooth"},
                        {"species": species, "law": law}]}
    return {**GAS, "contact": contact}


@pytest.mark.parametrize(
    "species, law, place, says",
    [
        (["grain", "dust"], "smooth", r"contact\.pair\[1\]\.species\[1\]",
         'no species named "dust"'),
        ([0, 5], "smooth", r"contact\.pair\[1\]\.species\[1\]", "no species 5"),
        (["grain"], "smooth", r"contact\.pair\[1\]\.species", "lists 1 species, expected two"),
        (["tracer", "grain"], "no-slip", r"contact\.pair\[1\]\.species",
         r"the pair \(\"grain\", \"tracer\"\) is listed twice"),
        (["tracer", "tracer"], {"e": "1.5", "beta": 0}, r"contact\.pair\[1\]\.law\.e",
         r"must be in \[0, 1\], got 3/2"),
        (["tracer", "tracer"], {"e": 0.5, "beta": float("nan")}, r"contact\.pair\[1\]\.law\.beta",
         "must be finite, got NaN"),
        (["tracer", "tracer"], "rough", r"contact\.pair\[1\]\.law", "unknown contact kind"),
    ],
)
def test_a_bad_pair_raises_input_error_naming_the_field(species, law, place, says):
    with pytest.raises(noslip.InputError, match=rf"^<dict>: {place}: {says}"):
        noslip.Scene.from_dict(pair_dict(species, law))


def test_a_bad_pair_in_text_names_the_field():
    bad = TEXT.replace('law = { e = "0.8", beta = "-1/5" }', 'law = { e = "0.8", beta = 2 }')
    with pytest.raises(noslip.InputError,
                       match=r"^<string>: contact\.pair\[0\]\.law\.beta: must be in \[-1, 1\]"):
        noslip.Scene(bad)
    twice = TEXT.replace("species = [1, 1]", 'species = ["grain", 1]')
    with pytest.raises(noslip.InputError,
                       match=r"^<string>: contact\.pair\[1\]\.species: the pair .* listed twice"):
        noslip.Scene(twice)


def test_the_losses_per_pair_of_species(root):
    """The shipped mixture's observables split ``lost_ball_ball`` by pair of species
    (``docs/granular.md``): ``lost_ball_ball_A-B`` and ``contacts_A-B`` named by the species,
    after the other columns; each pair's contacts are its contacts in the event log, to the
    count; each pair's loss is the sum of its contacts' losses recomputed from the log's pre-
    and post-contact states (``1/2 m (|u|^2 + 2 lambda |U|^2)``, ``lambda = gamma^2 R^2 / 2``);
    and the pairs add up to ``lost_ball_ball``.

    Tolerances: each loss is a difference of four ball energies, each within ``8 eps`` of at
    most the start's energy ``E_0`` whichever way it is evaluated (a few products and sums), so
    the two computations of a loss differ by at most ``64 eps E_0``; the two running sums of
    ``C`` nonnegative losses (their total below ``E_0``) each err by at most ``C eps E_0 / 2``:
    ``|ours - column| <= 65 C eps E_0``. The pairs' sum against the total: two orders of
    summation of the same ``C`` losses and two more additions, ``(C + 2) eps E_0``. (To the
    bit, against the engine's own per-contact losses: ``sim/tests/pair_laws.rs``.)"""
    scene = noslip.Scene.from_file(root / "scenes" / "mixture2d.toml")
    run = noslip.simulate(scene, events=2000, log=True, observables=0.5)
    obs, ev = run.observables, run.events
    pairs = ["grain-grain", "grain-tracer", "tracer-tracer"]
    names = list(obs)
    assert names[-6:] == [f"lost_ball_ball_{p}" for p in pairs] + [f"contacts_{p}" for p in pairs]
    assert names[: names.index("msd_cm_1") + 1] == [
        "time", "contacts", "T_tr", "T_rot", "energy", "collision_frequency",
        "lost_ball_ball", "lost_ball_wall", "lost_ball_obstacle", "lost_ball_boundary",
        "injected", "pressure", "a2", "msd", "msd_cm",
        "T_tr_0", "T_rot_0", "T_tr_1", "T_rot_1", "msd_cm_0", "msd_cm_1",
    ]
    for p in pairs:
        assert obs[f"contacts_{p}"].dtype == np.int64
        assert obs[f"lost_ball_ball_{p}"].dtype == np.float64
    # Balls in species order: 150 grains (mass 1, R = 1/2), then 20 tracers (mass 4, R = 1);
    # gamma^2 = 1/2 for both.
    species = np.array([0] * 150 + [1] * 20)
    mass = np.array([1.0, 4.0])[species]
    lam = 0.5 * 0.5 * np.array([0.25, 1.0])[species]
    balls = ev["balls"]
    assert (balls >= 0).all(), "a periodic gas: ball-ball contacts only"
    pair = species[balls[:, 0]] + species[balls[:, 1]]  # 0, 1, 2 in the pairs' order

    def energy(velocity: np.ndarray, spin: np.ndarray) -> np.ndarray:
        m, l = mass[balls], lam[balls]
        return (0.5 * m * ((velocity**2).sum(-1) + 2 * l * (spin**2).sum(-1))).sum(-1)

    loss = energy(ev["pre_velocity"], ev["pre_spin"]) - energy(ev["post_velocity"], ev["post_spin"])
    eps = np.finfo(float).eps
    e0 = obs["energy"][0]
    for k, p in enumerate(pairs):
        mine = np.where(pair == k, 1, 0)
        counted = np.concatenate([[0], np.cumsum(mine)])[obs["contacts"]]
        assert np.array_equal(obs[f"contacts_{p}"], counted), p
        lost = np.concatenate([[0.0], np.cumsum(np.where(pair == k, loss, 0.0))])[obs["contacts"]]
        bound = 65 * obs["contacts"] * eps * e0
        assert (np.abs(obs[f"lost_ball_ball_{p}"] - lost) <= bound).all(), p
        assert obs[f"lost_ball_ball_{p}"][-1] > 0 and obs[f"contacts_{p}"][-1] > 0, p
    total = sum(obs[f"lost_ball_ball_{p}"] for p in pairs)
    assert (np.abs(total - obs["lost_ball_ball"]) <= (obs["contacts"] + 2) * eps * e0).all()
    assert sum(obs[f"contacts_{p}"][-1] for p in pairs) == obs["contacts"][-1]
