//! Rough-ball contact laws, the TC model's `tc` and Maxwellian starts in scene files: read
//! exactly, elastic members named, bad values refused with the key named.

use noslip_scene::{ContactKind, Scene};
use num_rational::BigRational;

const BASE: &str = r#"
dim = 2
[box]
size = [10, 10]
boundary = ["wall", "wall"]
[[species]]
mass = 1
radius = "1/2"
count = 3
"#;

fn scene(extra: &str) -> Result<Scene, String> {
    Scene::from_toml(&format!("{BASE}{extra}"), "t.toml").map_err(|e| e.to_string())
}

fn q(text: &str) -> BigRational {
    noslip_scene::parse_exact(text).unwrap()
}

#[test]
fn rough_laws_are_read_exactly_everywhere() {
    let s = scene(
        "[contact]\nballs = { e = \"0.9\", beta = \"-1/3\" }\ntc = \"1e-6\"\n\
         [[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = { e = 0.5, beta = 0 }\n\
         [[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = { e = 1, beta = 1 }\n",
    );
    // A box with walls and a [[wall]]: walls need no periodic axis, which BASE has not.
    let s = s.unwrap();
    assert_eq!(
        s.ball_contact,
        ContactKind::Rough {
            e: q("9/10"),
            beta: q("-1/3")
        }
    );
    assert_eq!(s.tc, Some(q("1/1000000")));
    assert_eq!(
        s.obstacles[0].contact,
        ContactKind::Rough {
            e: q("1/2"),
            beta: q("0")
        }
    );
    // (1, 1) is the no-slip law by name, so it runs the no-slip path.
    assert_eq!(s.boundaries[0].contact, ContactKind::NoSlip);
    let smooth = scene("[contact]\nballs = { e = 1, beta = -1 }\n").unwrap();
    assert_eq!(smooth.ball_contact, ContactKind::Smooth);
    assert_eq!(smooth.tc, None);
    // The defaults are unchanged.
    assert_eq!(scene("").unwrap().ball_contact, ContactKind::NoSlip);
}

/// A container at `e = 0` would lose a ball at its first slanted contact (it leaves along
/// the wall's tangent: `noslip_sim::left_table`): refused naming `e`, in both law forms and
/// under the TC model; `e > 0` on a container and `e = 0` on a flat wall or an obstacle are
/// read.
#[test]
fn a_container_at_e_0_is_refused_naming_e() {
    let container =
        |law: &str| format!("[[container]]\ncentre = [5, 5]\nradius = 20\ncontact = {law}\n");
    for law in [
        "{ e = 0, beta = \"-1\" }",
        "{ e = 0, beta = \"0.5\" }",
        "{ e = 0, mu = \"0.2\", beta0 = \"0.5\" }",
        // Positive, but 0 in f64, as the engine takes it.
        "{ e = \"1e-400\", beta = \"-1\" }",
    ] {
        for tc in ["", "[contact]\ntc = \"1e-3\"\n"] {
            let e = scene(&(container(law) + tc)).unwrap_err();
            assert!(
                e.starts_with("t.toml: container[0].contact.e: must be > 0 on a container"),
                "{law} {tc}: {e}"
            );
        }
    }
    assert!(scene(&container("{ e = \"1e-9\", beta = \"-1\" }")).is_ok());
    let wall = "[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = { e = 0, beta = 0 }\n";
    let obstacle = "[[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = { e = 0, beta = 0 }\n";
    assert!(scene(wall).is_ok());
    assert!(scene(obstacle).is_ok());
}

#[test]
fn bad_laws_are_refused_naming_the_key() {
    let cases = [
        (
            "[contact]\nballs = { e = 1.5, beta = 0 }\n",
            "contact.balls.e",
        ),
        (
            "[contact]\nballs = { e = 0.5, beta = \"-3/2\" }\n",
            "contact.balls.beta",
        ),
        (
            "[[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = { e = -0.1, beta = 0 }\n",
            "obstacle[0].contact.e",
        ),
        (
            "[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = { e = 0.5, beta = 2 }\n",
            "wall[0].contact.beta",
        ),
        (
            "[[container]]\ncentre = [5, 5]\nradius = 20\ncontact = { e = 2, beta = 0 }\n",
            "container[0].contact.e",
        ),
        ("[contact]\ntc = 0\n", "contact.tc"),
        ("[contact]\ntc = -1\n", "contact.tc"),
        // Below the normal f64 range (1e-400 rounds to 0: no TC model at all).
        ("[contact]\ntc = \"1e-400\"\n", "contact.tc"),
        ("[contact]\ntc = \"1e-310\"\n", "contact.tc"),
    ];
    for (extra, place) in cases {
        let e = scene(extra).unwrap_err();
        assert!(e.starts_with(&format!("t.toml: {place}: ")), "{extra}: {e}");
    }
    // NaN, a non-number, a missing or an unknown key, an unknown name: refused at parsing,
    // with the line and what was expected (and the key path where the parser points at a
    // value or a key).
    for (extra, says) in [
        (
            "[contact]\nballs = { e = nan, beta = 0 }\n",
            "contact.balls.e: must be finite",
        ),
        ("[contact]\nballs = { e = \"x\", beta = 0 }\n", "\"x\""),
        (
            "[contact]\nballs = { e = 0.5 }\n",
            "a contact table is { e = ..., beta = ... } (rough) or",
        ),
        (
            "[contact]\nballs = { e = 0.5, beta = 0, mu = 1 }\n",
            "a contact table is { e = ..., beta = ... } (rough) or",
        ),
        (
            "[contact]\nballs = { e = 0.5, beta = 0, nu = 1 }\n",
            "unknown field `nu`",
        ),
        (
            "[contact]\nballs = \"rough\"\n",
            "unknown contact kind \"rough\"",
        ),
        (
            "[contact]\nballs = 1\n",
            "\"no-slip\", \"smooth\", a table { e = ..., beta = ... } or",
        ),
    ] {
        let e = scene(extra).unwrap_err();
        assert!(
            e.starts_with("t.toml: line ") && e.contains(says),
            "{extra}: {e}"
        );
    }
}

#[test]
fn point_masses_are_refused_under_laws_with_a_tangential_part() {
    let points = "[[species]]\nmass = 1\nradius = \"1/2\"\nlambda = 0\ncount = 2\n";
    let e = scene(&format!(
        "{points}[contact]\nballs = {{ e = 0.5, beta = 0 }}\n"
    ))
    .unwrap_err();
    assert!(e.contains("t.toml: species: two point masses"), "{e}");
    assert!(scene(&format!(
        "{points}[contact]\nballs = {{ e = 0.5, beta = -1 }}\n"
    ))
    .is_ok());
}

#[test]
fn maxwellian_starts_take_a_temperature() {
    let s = scene("[random]\nvelocities = \"maxwellian\"\ntemperature = \"2/3\"\n").unwrap();
    assert_eq!(s.random.temperature, Some(q("2/3")));
    let s = scene("[random]\nvelocities = \"maxwellian\"\n").unwrap();
    assert_eq!(s.random.temperature, Some(q("1")));
    assert_eq!(scene("").unwrap().random.temperature, None);
    for (extra, place) in [
        ("[random]\ntemperature = 1\n", "random.temperature"),
        (
            "[random]\nvelocities = \"maxwellian\"\ntemperature = 0\n",
            "random.temperature",
        ),
        (
            "[random]\nvelocities = \"maxwellian\"\nspeed = 1\n",
            "random.speed",
        ),
        (
            "[random]\nvelocities = \"maxwellian\"\nspin = 1\n",
            "random.spin",
        ),
        ("[random]\nvelocities = \"gauss\"\n", "random.velocities"),
    ] {
        let e = scene(extra).unwrap_err();
        assert!(e.starts_with(&format!("t.toml: {place}: ")), "{extra}: {e}");
    }
}

#[test]
fn walton_laws_are_read_exactly_and_bad_ones_refused_naming_the_key() {
    let s = scene("[contact]\nballs = { e = \"0.9\", mu = \"1/4\", beta0 = \"0.5\" }\n").unwrap();
    assert_eq!(
        s.ball_contact,
        ContactKind::Walton {
            e: q("9/10"),
            mu: q("1/4"),
            beta0: q("1/2")
        }
    );
    // Without friction the tangential restitution is -1 at every contact: the rough law.
    let frictionless = scene("[contact]\nballs = { e = \"0.9\", mu = 0, beta0 = \"0.5\" }\n");
    assert_eq!(
        frictionless.unwrap().ball_contact,
        ContactKind::Rough {
            e: q("9/10"),
            beta: q("-1")
        }
    );
    let err = |extra: &str| scene(extra).unwrap_err();
    let e = err("[contact]\nballs = { e = \"0.9\", mu = \"-0.1\", beta0 = \"0.5\" }\n");
    assert!(e.contains("contact.balls.mu") && e.contains(">= 0"), "{e}");
    let e = err("[contact]\nballs = { e = \"0.9\", mu = \"0.1\", beta0 = 2 }\n");
    assert!(e.contains("contact.balls.beta0"), "{e}");
    // Half of each form is neither.
    let e = err("[contact]\nballs = { e = \"0.9\", mu = \"0.1\" }\n");
    assert!(e.contains("mu = ..., beta0 = ..."), "{e}");
    let e = err("[contact]\nballs = { e = \"0.9\", beta = \"0.1\", mu = \"0.1\" }\n");
    assert!(e.contains("mu = ..., beta0 = ..."), "{e}");
}

/// `[box] contact`: the box walls' law, read exactly (no-slip by default and without a box),
/// bad values refused naming `box.contact`; box walls with a rough or Walton law have their
/// `fixed` kernels with the law folded in, smooth walls none (`Scene::pairs`).
#[test]
fn the_box_takes_a_contact_law() {
    let boxed = |contact: &str| {
        Scene::from_toml(
            &BASE.replace(
                "boundary = [\"wall\", \"wall\"]\n",
                &format!("boundary = [\"wall\", \"wall\"]\ncontact = {contact}\n"),
            ),
            "t.toml",
        )
        .map_err(|e| e.to_string())
    };
    assert_eq!(scene("").unwrap().box_contact, ContactKind::NoSlip);
    assert!(!scene("").unwrap().pairs().ball_wall.is_empty());
    let rough = boxed("{ e = \"0.9\", beta = \"1/2\" }").unwrap();
    assert_eq!(
        rough.box_contact,
        ContactKind::Rough {
            e: q("9/10"),
            beta: q("1/2")
        }
    );
    assert_eq!(rough.pairs().ball_wall.len(), 4);
    assert_eq!(rough.pairs().laws.wall, rough.box_contact);
    let smooth = boxed("\"smooth\"").unwrap();
    assert_eq!(smooth.box_contact, ContactKind::Smooth);
    assert!(smooth.pairs().ball_wall.is_empty());
    let walton = boxed("{ e = 1, mu = \"0.2\", beta0 = 1 }").unwrap();
    assert!(matches!(walton.box_contact, ContactKind::Walton { .. }));
    assert_eq!(walton.pairs().ball_wall.len(), 4);
    assert_eq!(walton.pairs().laws.wall, walton.box_contact);
    for (contact, place) in [
        ("{ e = 2, beta = 0 }", "box.contact.e"),
        ("{ e = 0.5, mu = -1, beta0 = 0 }", "box.contact.mu"),
    ] {
        let e = boxed(contact).unwrap_err();
        assert!(
            e.starts_with(&format!("t.toml: {place}: ")),
            "{contact}: {e}"
        );
    }
}

/// The laws `Scene::pairs` folds into each kind of kernel: the balls' and the box's own law
/// when no-slip, rough or Walton (smooth contacts have no kernels in the set); the fixed
/// bodies' no-slip law if any is no-slip, else their one rough or Walton law, else none.
#[test]
fn pairs_fold_rough_and_walton_laws() {
    let rough = |e: &str, beta: &str| ContactKind::Rough {
        e: q(e),
        beta: q(beta),
    };
    let s = scene("[contact]\nballs = { e = \"0.9\", beta = \"1/2\" }\n").unwrap();
    let p = s.pairs();
    assert_eq!(p.ball_ball, [(0, 0)]);
    assert_eq!(p.laws.ball, rough("9/10", "1/2"));
    assert_eq!(p.laws.wall, ContactKind::NoSlip);
    let walton = scene("[contact]\nballs = { e = 1, mu = \"0.2\", beta0 = 1 }\n").unwrap();
    assert_eq!(walton.pairs().ball_ball, [(0, 0)]);
    assert_eq!(walton.pairs().laws.ball, walton.ball_contact);
    assert!(matches!(walton.ball_contact, ContactKind::Walton { .. }));
    let obstacle = |contact: &str| {
        format!("[[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = {contact}\n")
    };
    let wall =
        |contact: &str| format!("[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = {contact}\n");
    let law_a = "{ e = 0.5, beta = 0 }";
    let law_b = "{ e = 0.5, beta = \"0.1\" }";
    // One rough law on every fixed body: folded.
    let p = scene(&(obstacle(law_a) + &wall(law_a))).unwrap().pairs();
    assert_eq!(
        (p.ball_obstacle.len(), &p.laws.fixed),
        (1, &rough("1/2", "0"))
    );
    // A no-slip one among them: the no-slip kernel, as before rough laws were folded.
    let p = scene(&(obstacle(law_a) + &wall("\"no-slip\"")))
        .unwrap()
        .pairs();
    assert_eq!(
        (p.ball_obstacle.len(), &p.laws.fixed),
        (1, &ContactKind::NoSlip)
    );
    // Two rough laws and no no-slip one: no ball-obstacle kernel.
    let p = scene(&(obstacle(law_a) + &wall(law_b))).unwrap().pairs();
    assert!(p.ball_obstacle.is_empty());
    // Smooth fixed bodies need none; beside them, one Walton law is folded like a rough one.
    let p = scene(&(obstacle("\"smooth\"") + &wall("\"smooth\"")))
        .unwrap()
        .pairs();
    assert!(p.ball_obstacle.is_empty());
    let walton = "{ e = 1, mu = 1, beta0 = 0 }";
    let s = scene(&(obstacle("\"smooth\"") + &wall(walton))).unwrap();
    let p = s.pairs();
    assert_eq!(p.ball_obstacle.len(), 1);
    assert!(matches!(p.laws.fixed, ContactKind::Walton { .. }));
}

/// A whole scene with the given law written at one place.
type WithLaw = Box<dyn Fn(&str) -> String>;

/// Every place a law can be written: the key path validation names it by, and the scene
/// with a law there.
fn law_places() -> Vec<(&'static str, WithLaw)> {
    let boxed =
        |extra: &'static str| move |law: &str| format!("{BASE}{}", extra.replace("{law}", law));
    vec![
        (
            "contact.balls",
            Box::new(boxed("[contact]\nballs = {law}\n")),
        ),
        (
            "box.contact",
            Box::new(|law: &str| {
                BASE.replace(
                    "boundary = [\"wall\", \"wall\"]\n",
                    &format!("boundary = [\"wall\", \"wall\"]\ncontact = {law}\n"),
                )
            }),
        ),
        (
            "obstacle[0].contact",
            Box::new(boxed(
                "[[obstacle]]\nposition = [5, 5]\nradius = 1\ncontact = {law}\n",
            )),
        ),
        (
            "wall[0].contact",
            Box::new(boxed(
                "[[wall]]\npoint = [0, 1]\nnormal = [0, 1]\ncontact = {law}\n",
            )),
        ),
        (
            "container[0].contact",
            Box::new(boxed(
                "[[container]]\ncentre = [5, 5]\nradius = 20\ncontact = {law}\n",
            )),
        ),
        (
            "polygon[0].contact",
            Box::new(boxed(
                "[[polygon]]\nvertices = [[4, 4], [6, 4], [5, 6]]\ncontact = {law}\n",
            )),
        ),
        (
            "table.contact",
            Box::new(|law: &str| {
                format!(
                    "dim = 2\n[table]\npolygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n\
                     contact = {law}\n[[species]]\nmass = 1\nradius = \"1/20\"\n\
                     [[ball]]\nspecies = 0\nposition = [\"1/2\", \"1/2\"]\n"
                )
            }),
        ),
    ]
}

/// Issue 27: a bad number in a contact law is refused naming the field, in every place a law
/// can be written: out of range (`e` outside `[0, 1]`, `beta` or `beta0` outside `[-1, 1]`,
/// `mu < 0`) by validation, with the key path as the place; NaN and infinities by the parser,
/// with the line, the column and the key path.
#[test]
fn bad_numbers_in_every_law_are_refused_naming_the_field() {
    let outside = [
        ("{ e = \"1.01\", beta = 0 }", "e", "in [0, 1], got 101/100"),
        ("{ e = -1e-9, beta = 0 }", "e", "in [0, 1]"),
        (
            "{ e = 0.5, beta = \"-1.5\" }",
            "beta",
            "in [-1, 1], got -3/2",
        ),
        ("{ e = 0.5, beta = 2 }", "beta", "in [-1, 1]"),
        ("{ e = 2, mu = 1, beta0 = 0 }", "e", "in [0, 1]"),
        (
            "{ e = 0.5, mu = \"-1/4\", beta0 = 0 }",
            "mu",
            ">= 0, got -1/4",
        ),
        (
            "{ e = 0.5, mu = 1, beta0 = \"3/2\" }",
            "beta0",
            "in [-1, 1]",
        ),
        ("{ e = 0.5, mu = 1, beta0 = -2 }", "beta0", "in [-1, 1]"),
    ];
    let not_finite = [
        ("{ e = nan, beta = 0 }", "e", "must be finite, got NaN"),
        (
            "{ e = 0.5, beta = -nan }",
            "beta",
            "must be finite, got NaN",
        ),
        ("{ e = inf, beta = 0 }", "e", "must be finite, got inf"),
        ("{ e = 0.5, mu = nan, beta0 = 0 }", "mu", "must be finite"),
        (
            "{ e = 0.5, mu = 1, beta0 = -inf }",
            "beta0",
            "must be finite, got -inf",
        ),
        ("{ e = nan, mu = 1, beta0 = 0 }", "e", "must be finite"),
    ];
    for (place, scene_with) in law_places() {
        // The place is right: a good law there is read.
        let good = Scene::from_toml(&scene_with("{ e = 0.5, beta = 0 }"), "t.toml");
        assert!(good.is_ok(), "{place}: {good:?}");
        for (law, key, says) in outside {
            let e = Scene::from_toml(&scene_with(law), "t.toml")
                .unwrap_err()
                .to_string();
            let named = format!("t.toml: {place}.{key}: must be {says}");
            assert!(e.starts_with(&named), "{place} = {law}: {e}");
        }
        for (law, key, says) in not_finite {
            let text = scene_with(law);
            let e = Scene::from_toml(&text, "t.toml").unwrap_err().to_string();
            // The line of the law, and the field's path after the column.
            let line = 1 + text[..text.find(law).unwrap()].matches('\n').count();
            let named = format!(": {place}.{key}: {says}");
            assert!(
                e.starts_with(&format!("t.toml: line {line}, column ")) && e.contains(&named),
                "{place} = {law}: {e}"
            );
        }
    }
}
