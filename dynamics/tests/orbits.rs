//! Periodic orbits of the boundary map: a hand-derived orbit found exactly, the exact return
//! map against the f64 one, Newton's quadratic convergence.

use collision_core::{Exact, Scalar, State2};
use noslip_dynamics::orbits::section::{return_map, Section};
use noslip_dynamics::orbits::{exact, newton, scene::table, Verdict};
use noslip_dynamics::table::{Boundary, Table};
use noslip_dynamics::Law;
use noslip_scene::Scene;

fn q(n: i64, d: i64) -> Exact {
    Exact::from_ratio(n, d)
}

fn walls() -> Table<Exact, 2> {
    let scene = Scene::from_toml(
        include_str!("../../scenes/disk_between_walls.toml"),
        "walls",
    )
    .unwrap();
    table::<2, 1>(&scene, Some(Law::NoSlip))
        .unwrap()
        .exact
        .unwrap()
}

/// The period-2 orbit of a disk bouncing between the walls `y = 0` and `y = 4` (radius 1/2,
/// uniform: g = gamma^2 = 1/2), `u = (0, v)`, no spin. By hand: at the bottom wall the no-slip
/// map acts on `(u_x, R s)` (`s = U_01`) as `[[a, b], [c, -a]]`, at the top as
/// `[[a, -b], [-c, -a]]`, with `a = (1 - g)/(1 + g)`, `b = 2g/(1 + g)`, `c = 2/(1 + g)`; `u_y`
/// flips twice and the flight time `h/v` (`h = 3`) only shears `x` by `u_x`. On the section
/// (`dx, du_x, du_y, R ds`; `dy = 0`) the return map is block triangular: `dx -> dx + ...`
/// (eigenvalue 1), `du_y -> du_y` (1), and the product `[[a^2 - bc, -2ab], [2ac, a^2 - bc]]`
/// with determinant 1 and trace `2 (a^2 - bc) = 2 ((1 - g)^2 - 4g) / (1 + g)^2 = -14/9`:
/// `p(l) = (l - 1)^2 (l^2 + 14/9 l + 1) = l^4 - 4/9 l^3 - 10/9 l^2 - 4/9 l + 1`, elliptic
/// (`l = -7/9 +- i sqrt(32)/9`).
#[test]
fn bouncing_orbit_has_the_hand_derived_characteristic_polynomial() {
    let t = walls();
    let z = Section {
        x: [q(1, 1), q(1, 2)],
        state: State2::from_scalar_spin(q(0, 1), [q(0, 1), q(1, 1)]),
    };
    let r = exact::<2, 1>(&t, &z, 2).unwrap();
    assert!(r.periodic);
    assert_eq!(r.boundaries, vec![1, 0]);
    assert_eq!(r.coefficients, ["1", "-4/9", "-10/9", "-4/9", "1"]);
    assert_eq!(r.charpoly, "l^4 - 4/9 l^3 - 10/9 l^2 - 4/9 l + 1");
    // Newton in f64 from a start with slip and spin finds it, with the same eigenvalues.
    let f = t.map(|x| x.to_f64());
    let orbit = newton::<2, 1>(&f, &[3.0, 0.5, 0.2, 1.0, 0.3], 2).unwrap();
    assert_eq!(orbit.verdict, Verdict::Elliptic);
    assert!(
        orbit.start[2].abs() < 1e-12 && orbit.start[4].abs() < 1e-12,
        "{:?}",
        orbit.start
    );
    let want = [
        (-7.0 / 9.0, 32f64.sqrt() / 9.0),
        (-7.0 / 9.0, -(32f64.sqrt()) / 9.0),
        (1.0, 0.0),
        (1.0, 0.0),
    ];
    for (re, im) in want {
        assert!(
            orbit
                .eigenvalues
                .iter()
                .any(|e| (e.0 - re).abs() < 1e-7 && (e.1 - im).abs() < 1e-7),
            "{:?}",
            orbit.eigenvalues
        );
    }
}

/// A 3-4-5 right triangle (walls with unit rational normals, one tilted): ten steps of the
/// return map from a rational start in exact rationals, against the same steps in f64: states
/// within 1e-12 and derivatives within 1e-9 relative (ten contacts amplify rounding by at
/// most the norm of the derivative, printed by the failure).
#[test]
fn exact_return_map_equals_the_f64_one_to_rounding() {
    let ball = collision_core::Ball {
        inv_mass: q(1, 1),
        radius: q(1, 4),
        gamma2: q(1, 2),
    };
    let t = Table {
        boundaries: vec![
            Boundary::Wall {
                point: [q(0, 1), q(0, 1)],
                normal: [q(0, 1), q(1, 1)],
            },
            Boundary::Wall {
                point: [q(0, 1), q(0, 1)],
                normal: [q(1, 1), q(0, 1)],
            },
            Boundary::Wall {
                point: [q(4, 1), q(0, 1)],
                normal: [q(-3, 5), q(-4, 5)],
            },
        ],
        period: [None, None],
        ball,
        laws: vec![Law::NoSlip; 3],
    };
    let z = Section {
        x: [q(1, 1), q(1, 4)],
        state: State2::from_scalar_spin(q(1, 3), [q(2, 7), q(1, 1)]),
    };
    let e = return_map(&t, &z, 10).unwrap();
    let f = return_map(
        &t.map(|x| x.to_f64()),
        &Section::from_slice(&z.to_vec().iter().map(Scalar::to_f64).collect::<Vec<_>>()),
        10,
    )
    .unwrap();
    assert_eq!(e.boundaries, f.boundaries);
    for (a, b) in e.states.iter().zip(&f.states) {
        for (x, y) in a.to_vec().iter().zip(b.to_vec()) {
            assert!(
                (x.to_f64() - y).abs() < 1e-12 * (1.0 + y.abs()),
                "{x} vs {y}"
            );
        }
    }
    let big = f
        .columns
        .iter()
        .flatten()
        .fold(1.0f64, |m, x| m.max(x.abs()));
    for (a, b) in e.columns.iter().zip(&f.columns) {
        for (x, y) in a.iter().zip(b) {
            assert!(
                (x.to_f64() - y).abs() < 1e-9 * big,
                "{x} vs {y} (max {big})"
            );
        }
    }
}

/// Newton's method on the Sinai table (curved: the return map is nonlinear) converges
/// quadratically: each residual is at most 10 times the square of the one before, until
/// rounding (1e-12) is reached.
#[test]
fn newton_converges_quadratically_on_the_sinai_table() {
    let scene = Scene::from_toml(include_str!("../../scenes/sinai.toml"), "sinai").unwrap();
    let t = table::<2, 1>(&scene, Some(Law::NoSlip)).unwrap().float;
    // Near the horizontal period-2 orbit through the periodic face: contacts at x = 0.85 and
    // (the obstacle's image) x = 0.15, y = 1/2.
    let orbit = newton::<2, 1>(&t, &[0.85, 0.51, 1.0, 0.02, 0.05], 2).unwrap();
    let r = &orbit.residuals;
    assert!(r.len() >= 3, "{r:?}");
    for w in r.windows(2) {
        if w[0] > 1e-6 {
            continue;
        }
        assert!(w[1] <= 10.0 * w[0] * w[0] + 1e-13, "{r:?}");
    }
    println!("{orbit:?}");
}

/// The classical control: in the smooth Sinai table the horizontal period-2 orbit through the
/// periodic face bounces between the obstacle and its image at normal incidence; a flight of
/// `l = 1 - 2 R_eff = 3/10` between circles of radius `R_eff = 7/20` gives per bounce the
/// matrix `[[1, l], [2/R, 1 + 2l/R]]` of trace `2 + 2l/R = 26/7`, so over the period
/// `lambda + 1/lambda = (26/7)^2 - 2 = 578/49` (hyperbolic); with the scaling and the
/// (conserved) spin: `p(l) = (l - 1)^2 (l^2 - 578/49 l + 1)`, exactly. Newton finds it in
/// f64 from a start 1e-3 off, with the same eigenvalues.
#[test]
fn smooth_sinai_bouncing_orbit_is_the_classical_hyperbolic_one() {
    let scene = Scene::from_toml(include_str!("../../scenes/sinai.toml"), "sinai").unwrap();
    let t = table::<2, 1>(&scene, Some(Law::Smooth))
        .unwrap()
        .exact
        .unwrap();
    let z = Section {
        x: [q(17, 20), q(1, 2)],
        state: State2::from_scalar_spin(q(0, 1), [q(1, 1), q(0, 1)]),
    };
    let r = exact::<2, 1>(&t, &z, 2).unwrap();
    assert!(r.periodic);
    // (l^2 - 2 l + 1)(l^2 - 578/49 l + 1)
    let (a, b) = (q(-578, 49), q(-2, 1));
    let want = [
        q(1, 1),
        a.clone() + b.clone(),
        q(2, 1) + a.clone() * b.clone(),
        a + b,
        q(1, 1),
    ];
    assert_eq!(
        r.coefficients,
        want.iter().map(|c| c.to_string()).collect::<Vec<_>>()
    );
    let orbit = newton::<2, 1>(&t.map(|x| x.to_f64()), &[0.85, 0.501, 1.0, 0.001, 0.0], 2).unwrap();
    assert_eq!(orbit.verdict, Verdict::Hyperbolic);
    let top = orbit.eigenvalues[0];
    assert!(
        (top.0 + 1.0 / top.0 - 578.0 / 49.0).abs() < 1e-9 && top.1 == 0.0,
        "{:?}",
        orbit.eigenvalues
    );
}

/// Cox, Feres and Zhang (Stability of periodic orbits in no-slip billiards, 2017): a no-slip
/// billiard with a corner of inner angle below `pi` has linearly stable period-2 orbits
/// bouncing between the corner's two sides. A period-2 orbit runs back and forth along one
/// chord, so each contact reverses the velocity (and the spin): the no-slip map has such
/// states (the `-1` eigenvectors of its tangential part), smooth contacts only at normal
/// incidence.
///
/// What holds in the shipped equilateral triangle (no-slip, as shipped): the grid search finds
/// period-2 orbits, each between two different sides, each with its velocity reversed at the
/// contacts, and none hyperbolic: every eigenvalue of the section map is on the unit circle
/// (to 1e-6, the verdict's tolerance). They come in families (the chord moved along the
/// sides), so their eigenvalues are `+-1` and the verdict is "parabolic" (not "elliptic" in
/// this program's sense, which needs a non-real eigenvalue: docs/dynamics.md).
///
/// The classical control: with smooth (specular) contacts the velocity reverses only at normal
/// incidence, so a period-2 orbit would run along a common perpendicular of two sides; two
/// sides of a triangle are not parallel and have none, so the same search finds no period-2
/// orbit at all.
#[test]
fn triangle_has_stable_period_two_orbits_no_slip_and_none_smooth() {
    use noslip_dynamics::orbits::search::{search, Search, DEFAULT_MAX_CONTACTS};
    let scene = Scene::from_toml(include_str!("../../scenes/triangle.toml"), "triangle").unwrap();
    let ask = |law| Search {
        period: 2,
        from: Vec::new(),
        grid: Some(6),
        law,
        max_contacts: DEFAULT_MAX_CONTACTS,
    };
    let no_slip = search::<2, 1>(&scene, &ask(None)).unwrap();
    assert!(!no_slip.orbits.is_empty(), "{no_slip:?}");
    for o in &no_slip.orbits {
        assert_ne!(o.boundaries[0], o.boundaries[1], "{o:?}");
        assert_ne!(o.verdict, Verdict::Hyperbolic, "{o:?}");
        for (re, im) in &o.eigenvalues {
            assert!((re.hypot(*im) - 1.0).abs() < 1e-6, "{o:?}");
        }
        // u at the second contact is -u at the first (relative 1e-9: Newton's residual).
        let [a, b] = [&o.states[0], &o.states[1]];
        for k in 2..4 {
            assert!((a[k] + b[k]).abs() < 1e-9 * (1.0 + a[k].abs()), "{o:?}");
        }
    }
    let smooth = search::<2, 1>(&scene, &ask(Some(Law::Smooth))).unwrap();
    assert!(smooth.orbits.is_empty(), "{smooth:?}");
    assert_eq!(smooth.misses, smooth.starts);
}

/// Cox, Feres and Zhang's corner theorem in its own setting: the shipped wedge of 20 degrees
/// (two flat walls, no-slip as shipped). The grid search finds period-2 orbits between the
/// two walls that are elliptic: a non-real pair of eigenvalues on the unit circle (to 1e-6).
/// With smooth contacts none: the two walls have no common perpendicular.
#[test]
fn wedge_of_twenty_degrees_has_elliptic_period_two_orbits() {
    use noslip_dynamics::orbits::search::{search, Search, DEFAULT_MAX_CONTACTS};
    let scene = Scene::from_toml(include_str!("../../scenes/wedge.toml"), "wedge").unwrap();
    let ask = |law| Search {
        period: 2,
        from: Vec::new(),
        grid: Some(3),
        law,
        max_contacts: DEFAULT_MAX_CONTACTS,
    };
    let no_slip = search::<2, 1>(&scene, &ask(None)).unwrap();
    let elliptic: Vec<_> = no_slip
        .orbits
        .iter()
        .filter(|o| o.verdict == Verdict::Elliptic)
        .collect();
    assert!(!elliptic.is_empty(), "{no_slip:?}");
    for o in elliptic {
        assert_ne!(o.boundaries[0], o.boundaries[1], "{o:?}");
        assert!(o.eigenvalues.iter().any(|(_, im)| im.abs() > 1e-6), "{o:?}");
        for (re, im) in &o.eigenvalues {
            assert!((re.hypot(*im) - 1.0).abs() < 1e-6, "{o:?}");
        }
    }
    let smooth = search::<2, 1>(&scene, &ask(Some(Law::Smooth))).unwrap();
    assert!(smooth.orbits.is_empty(), "{smooth:?}");
}

/// `noslip orbits scenes/triangle.toml --period 4 --grid 1` never returned: the return maps
/// of its period-4 orbits have the eigenvalue 1 four times (three of them in a block equal to
/// the identity up to a few ulps), on which nalgebra's eigenvalue iteration, uncapped, looped
/// forever. With the bounded attempts of `poly::eigenvalues` the three starts give three
/// orbits, each with its eigenvalues (on the unit circle: 1 or a pair near -1) and a verdict.
#[test]
fn the_triangle_period_four_search_returns_with_its_eigenvalues() {
    use noslip_dynamics::orbits::search::{search, Search, DEFAULT_MAX_CONTACTS};
    let scene = Scene::from_toml(include_str!("../../scenes/triangle.toml"), "triangle").unwrap();
    let ask = Search {
        period: 4,
        from: Vec::new(),
        grid: Some(1),
        law: None,
        max_contacts: DEFAULT_MAX_CONTACTS,
    };
    let r = search::<2, 1>(&scene, &ask).unwrap();
    assert_eq!((r.starts, r.tried, r.orbits.len()), (3, 3, 3), "{r:?}");
    assert_eq!(r.stopped, None);
    for o in &r.orbits {
        assert_ne!(o.verdict, Verdict::Undetermined, "{o:?}");
        assert_eq!(o.eigenvalues.len(), 4, "{o:?}");
    }
}

/// A search shares one budget of contacts among its starts: with a bound of 2000 the
/// sector's period-4 grid (64 starts, about 10^4 contacts in all) stops part way, having
/// followed at most 2000 contacts, and says how many starts it tried; with the default bound
/// it tries them all.
#[test]
fn a_search_stops_at_its_bound_of_contacts() {
    use noslip_dynamics::orbits::search::{search, Search, DEFAULT_MAX_CONTACTS};
    let scene = Scene::from_toml(include_str!("../../scenes/sector.toml"), "sector").unwrap();
    let ask = |max_contacts| Search {
        period: 4,
        from: Vec::new(),
        grid: Some(4),
        law: None,
        max_contacts,
    };
    let cut = search::<2, 1>(&scene, &ask(2000)).unwrap();
    assert!(
        cut.contacts <= 2000 && cut.contacts > 1000,
        "{}",
        cut.contacts
    );
    assert!(
        0 < cut.tried && cut.tried < cut.starts,
        "{} {}",
        cut.tried,
        cut.starts
    );
    let why = cut.stopped.as_deref().unwrap();
    assert!(
        why.contains(&format!("{} of 64 starts were tried", cut.tried)),
        "{why}"
    );
    let all = search::<2, 1>(&scene, &ask(DEFAULT_MAX_CONTACTS)).unwrap();
    assert_eq!((all.starts, all.tried, all.stopped), (64, 64, None));
    assert!(all.contacts > 2000 && all.orbits.len() >= cut.orbits.len());
}
