"""A ball-ball contact law per pair of species (``[[contact.pair]]``, issue 27) in Python:
``Scene(text)`` and ``Scene.from_dict`` read it, ``Scene.ball_laws`` shows every pair's law,
a bad pair raises ``InputError`` naming the field, and the shipped mixture simulates."""

from fractions import Fraction

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
