//! A ball-ball law per pair of species (`[[contact.pair]]`): read by name or index in either
//! order, the default `contact.balls` kept for the pairs not listed, the generator's pair
//! set folding each pair's law, and every bad pair refused naming its field.

use noslip_scene::{ContactKind, Pair, Scene};
use num_rational::BigRational;

/// Two species, `grain` (three balls) and unnamed `species1` (two balls), in a walled box.
const BASE: &str = r#"
dim = 2
[box]
size = [20, 20]
boundary = ["wall", "wall"]
[[species]]
name = "grain"
mass = 1
radius = "1/2"
count = 3
[[species]]
mass = 2
radius = 1
count = 2
"#;

fn scene(extra: &str) -> Result<Scene, String> {
    Scene::from_toml(&format!("{BASE}{extra}"), "t.toml").map_err(|e| e.to_string())
}

fn q(text: &str) -> BigRational {
    noslip_scene::parse_exact(text).unwrap()
}

fn rough(e: &str, beta: &str) -> ContactKind {
    ContactKind::Rough {
        e: q(e),
        beta: q(beta),
    }
}

#[test]
fn listed_pairs_take_their_law_and_the_rest_the_default() {
    let s = scene(
        "[contact]\nballs = { e = \"0.9\", beta = \"0.5\" }\n\
         [[contact.pair]]\nspecies = [\"species1\", \"grain\"]\nlaw = { e = \"0.8\", beta = \"-1/5\" }\n\
         [[contact.pair]]\nspecies = [1, 1]\nlaw = \"smooth\"\n",
    )
    .unwrap();
    assert_eq!(s.ball_contact, rough("9/10", "1/2"));
    assert_eq!(s.pair_contacts.len(), 2);
    // Stored with the lower index first, whatever the order written.
    assert_eq!(s.pair_contacts[0].species, [0, 1]);
    assert_eq!(s.ball_law(0, 0), &rough("9/10", "1/2"));
    assert_eq!(s.ball_law(0, 1), &rough("4/5", "-1/5"));
    assert_eq!(s.ball_law(1, 0), &rough("4/5", "-1/5"));
    assert_eq!(s.ball_law(1, 1), &ContactKind::Smooth);
    // The generator: a kernel per pair with its own law; the smooth pair has none.
    let set = s.pairs();
    assert_eq!(set.ball_ball, [(0, 0), (0, 1)]);
    assert_eq!(set.laws.of(Pair::BallBall(0, 0)), &rough("9/10", "1/2"));
    assert_eq!(set.laws.of(Pair::BallBall(0, 1)), &rough("4/5", "-1/5"));
    assert_eq!(set.laws.of(Pair::BallBall(1, 0)), &rough("4/5", "-1/5"));
    // The elastic members are named in a pair as in contact.balls; a Walton law is kept.
    let s = scene(
        "[[contact.pair]]\nspecies = [\"grain\", \"grain\"]\nlaw = { e = 1, beta = -1 }\n\
         [[contact.pair]]\nspecies = [\"grain\", 1]\nlaw = { e = \"0.7\", mu = \"0.3\", beta0 = \"0.6\" }\n",
    )
    .unwrap();
    assert_eq!(s.ball_contact, ContactKind::NoSlip);
    assert_eq!(s.ball_law(0, 0), &ContactKind::Smooth);
    assert!(matches!(s.ball_law(1, 0), ContactKind::Walton { .. }));
    assert_eq!(s.ball_law(1, 1), &ContactKind::NoSlip);
    let set = s.pairs();
    assert_eq!(set.ball_ball, [(0, 1), (1, 1)]);
    assert!(matches!(
        set.laws.of(Pair::BallBall(0, 1)),
        ContactKind::Walton { .. }
    ));
    assert_eq!(set.laws.of(Pair::BallBall(1, 1)), &ContactKind::NoSlip);
}

#[test]
fn a_scene_without_pairs_or_listing_the_default_has_the_pair_set_of_before() {
    let plain = scene("[contact]\nballs = { e = \"0.9\", beta = \"0.5\" }\n").unwrap();
    assert!(plain.pair_contacts.is_empty());
    let listed = scene(
        "[contact]\nballs = { e = \"0.9\", beta = \"0.5\" }\n\
         [[contact.pair]]\nspecies = [0, 0]\nlaw = { e = \"9/10\", beta = \"1/2\" }\n\
         [[contact.pair]]\nspecies = [0, 1]\nlaw = { e = \"0.9\", beta = \"0.5\" }\n\
         [[contact.pair]]\nspecies = [1, 1]\nlaw = { e = \"0.9\", beta = \"0.5\" }\n",
    )
    .unwrap();
    assert_eq!(listed.pair_contacts.len(), 3);
    // The same kernels, so the same generated module.
    assert_eq!(listed.pairs(), plain.pairs());
    assert!(plain.pairs().laws.pairs.is_empty());
}

#[test]
fn bad_pairs_are_refused_naming_the_field() {
    let pair = |species: &str, law: &str| {
        format!("[[contact.pair]]\nspecies = [0, 1]\nlaw = \"smooth\"\n[[contact.pair]]\nspecies = {species}\nlaw = {law}\n")
    };
    for (extra, place, says) in [
        (
            pair("[\"grain\", \"tracer\"]", "\"smooth\""),
            "contact.pair[1].species[1]",
            "no species named \"tracer\" (the scene has \"grain\", \"species1\")",
        ),
        (
            pair("[0, 2]", "\"smooth\""),
            "contact.pair[1].species[1]",
            "no species 2 (the scene has 2, numbered from 0)",
        ),
        (
            pair("[\"grain\"]", "\"smooth\""),
            "contact.pair[1].species",
            "lists 1 species, expected two (a species with itself: the name twice)",
        ),
        (
            pair("[\"species1\", \"grain\"]", "\"no-slip\""),
            "contact.pair[1].species",
            "the pair (\"grain\", \"species1\") is listed twice: also at contact.pair[0] (a pair is unordered)",
        ),
        (
            pair("[1, 1]", "{ e = \"1.5\", beta = 0 }"),
            "contact.pair[1].law.e",
            "must be in [0, 1], got 3/2",
        ),
        (
            pair("[1, 1]", "{ e = 1, beta = 2 }"),
            "contact.pair[1].law.beta",
            "must be in [-1, 1], got 2",
        ),
        (
            pair("[1, 1]", "{ e = 1, mu = -1, beta0 = 0 }"),
            "contact.pair[1].law.mu",
            "must be >= 0, got -1",
        ),
    ] {
        let e = scene(&extra).unwrap_err();
        assert_eq!(e, format!("t.toml: {place}: {says}"), "{extra}");
    }
    // Two species of one name: a name is ambiguous, an index is not.
    let twins = "[[species]]\nname = \"grain\"\nmass = 1\nradius = 1\n";
    let e = scene(&format!(
        "{twins}[[contact.pair]]\nspecies = [\"grain\", 1]\nlaw = \"smooth\"\n"
    ))
    .unwrap_err();
    assert!(
        e.starts_with("t.toml: contact.pair[0].species[0]: species[0] and species[2] are both named \"grain\""),
        "{e}"
    );
    assert!(scene(&format!(
        "{twins}[[contact.pair]]\nspecies = [2, 1]\nlaw = \"smooth\"\n"
    ))
    .is_ok());
    // What the parser refuses carries the line, the column and the key path.
    for (extra, says) in [
        (
            pair("[0, 1]", "{ e = nan, beta = 0 }"),
            "contact.pair[1].law.e: must be finite",
        ),
        (
            pair("[0, -1]", "\"smooth\""),
            "contact.pair[1].species[1]: a species index is >= 0, got -1",
        ),
        (
            pair("[0, 1]", "\"rough\""),
            "contact.pair[1].law: unknown contact kind \"rough\"",
        ),
        (
            "[[contact.pair]]\nspecies = [0, 1]\n".to_string(),
            "missing field `law`",
        ),
        (
            "[[contact.pair]]\nspecies = [0, 1]\nlaw = \"smooth\"\ne = 1\n".to_string(),
            "contact.pair[0].e: unknown field `e`",
        ),
    ] {
        let e = scene(&extra).unwrap_err();
        assert!(
            e.starts_with("t.toml: line ") && e.contains(says),
            "{extra}: {e}"
        );
    }
}

#[test]
fn point_masses_are_refused_by_the_law_of_their_pair() {
    let points =
        "[[species]]\nname = \"point\"\nmass = 1\nradius = \"1/2\"\nlambda = 0\ncount = 2\n";
    // Smooth by default, rough between the point masses: refused, naming the pair's law.
    let e = scene(&format!(
        "{points}[contact]\nballs = \"smooth\"\n\
         [[contact.pair]]\nspecies = [\"point\", \"point\"]\nlaw = {{ e = 0.5, beta = 0 }}\n"
    ))
    .unwrap_err();
    assert!(
        e.starts_with("t.toml: contact.pair[0].law: two point masses"),
        "{e}"
    );
    // Rough by default, smooth between the point masses (and the other pairs rough): fine.
    assert!(scene(&format!(
        "{points}[contact]\nballs = {{ e = 0.5, beta = 0 }}\n\
         [[contact.pair]]\nspecies = [\"point\", \"point\"]\nlaw = \"smooth\"\n"
    ))
    .is_ok());
}
