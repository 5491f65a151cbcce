//! The simulator's contact geometry and time reversal, on every shipped scene.
//!
//! - At every contact the logged normal is the unit line of centres of the two touching
//!   bodies, taken with the minimum image on periodic axes, and the centres are at contact
//!   distance `R_i + R_j` (a wall: the centre at `R` from it, `nu = +-e_k`).
//! - Time reversal: the no-slip map is reversible (`(u, U) -> (u', U')` implies
//!   `(-u', -U') -> (-u, -U)`) and so is free flight; `k` contacts forward, all velocities and
//!   spins negated, `k` contacts back return to the start up to rounding.

use collision_core::{Generated, Kernel};
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use noslip_sim::table::Shape;
use noslip_sim::{Body, Event, GenericKernels, Setup, Simulation, Step};
use std::path::Path;

fn scene(path: &Path) -> Scene {
    Scene::from_file(path).expect("shipped scene is valid")
}

fn simulation<const N: usize, const S: usize>(
    setup: Setup<N, S>,
) -> Simulation<N, S, GenericKernels<f64>>
where
    Generated: Kernel<f64, N, S>,
{
    let species = setup.species.clone();
    Simulation::new(setup, GenericKernels { species }).expect("a valid setup")
}

/// The next contact, with no time limit.
fn next<const N: usize, const S: usize>(
    sim: &mut Simulation<N, S, GenericKernels<f64>>,
) -> Option<Event<N, S>>
where
    Generated: Kernel<f64, N, S>,
{
    loop {
        match sim.step(f64::INFINITY) {
            Step::Contact(e) => return Some(e),
            Step::Quiet { .. } => {}
            _ => return None,
        }
    }
}

/// `b - a` reduced to the minimum image on periodic axes: `d_k - L_k round(d_k / L_k)`.
fn min_image<const N: usize>(
    a: &[f64; N],
    b: &[f64; N],
    size: &[f64; N],
    periodic: &[bool; N],
) -> [f64; N] {
    std::array::from_fn(|k| {
        let d = b[k] - a[k];
        if periodic[k] {
            d - size[k] * (d / size[k]).round()
        } else {
            d
        }
    })
}

fn norm<const N: usize>(x: &[f64; N]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// The largest geometry errors over a run, and the contacts beyond tolerance.
#[derive(Debug, Default)]
struct Geometry {
    contacts: u64,
    distance: f64,
    normal: f64,
    bad: u64,
}

/// Run `contacts` contacts of `setup` and measure each contact's geometry against the
/// tolerances of [`tolerances`].
fn geometry<const N: usize, const S: usize>(setup: Setup<N, S>, contacts: u64) -> Geometry
where
    Generated: Kernel<f64, N, S>,
{
    let (size, periodic) = (setup.size, setup.periodic);
    let radius: Vec<f64> = setup.species.iter().map(|s| s.radius).collect();
    let obstacles = setup.obstacles.clone();
    let mut sim = simulation(setup);
    let mut g = Geometry::default();
    while g.contacts < contacts {
        let Some(e) = next(&mut sim) else { break };
        g.contacts += 1;
        let r_i = radius[sim.species_of(match e.contact {
            noslip_sim::Contact::Ball { i, .. }
            | noslip_sim::Contact::Wall { i, .. }
            | noslip_sim::Contact::Obstacle { i, .. }
            | noslip_sim::Contact::Boundary { i, .. } => i,
        })];
        // The centre line from body 1 to body 2 and the contact distance.
        let (d, sigma) = match e.contact {
            noslip_sim::Contact::Ball { j, .. } => (
                min_image(&e.position[0], &e.position[1], &size, &periodic),
                r_i + radius[sim.species_of(j)],
            ),
            noslip_sim::Contact::Obstacle { obstacle, .. } => {
                let o = &obstacles[obstacle];
                (
                    min_image(&o.position, &e.position[0], &size, &periodic),
                    r_i + o.radius,
                )
            }
            noslip_sim::Contact::Wall { axis, upper, .. } => {
                // The centre's offset from the wall, along the wall's normal.
                let x = e.position[0][axis];
                let gap = if upper { size[axis] - x } else { x };
                let mut d = [0.0; N];
                d[axis] = if upper { -gap } else { gap };
                (d, r_i)
            }
            noslip_sim::Contact::Boundary { boundary, .. } => {
                // The line from the nearest point of the boundary (or a sphere's centre) to
                // the ball's centre, and its length at contact.
                let a = e.position[0];
                let sub = |x: &[f64; N], y: &[f64; N]| -> [f64; N] {
                    std::array::from_fn(|k| x[k] - y[k])
                };
                let dot = |x: &[f64; N], y: &[f64; N]| (0..N).map(|k| x[k] * y[k]).sum::<f64>();
                match &sim.table().boundaries[boundary].shape {
                    Shape::Wall { point, normal } => {
                        let h = dot(&sub(&a, point), normal);
                        (normal.map(|x| h * x), r_i)
                    }
                    Shape::Edge { from, to, .. } => {
                        let edge = sub(to, from);
                        let s = dot(&sub(&a, from), &edge) / dot(&edge, &edge);
                        let foot: [f64; N] = std::array::from_fn(|k| from[k] + s * edge[k]);
                        (sub(&a, &foot), r_i)
                    }
                    Shape::Sphere { centre, radius } => (sub(&a, centre), r_i + radius),
                    Shape::Container { centre, radius } => (sub(centre, &a), radius - r_i),
                }
            }
        };
        let length = norm(&d);
        let distance_error = (length - sigma).abs() / sigma;
        let normal_error = (0..N)
            .map(|k| (e.nu[k] - d[k] / length).abs())
            .fold(0.0, f64::max);
        g.distance = g.distance.max(distance_error);
        g.normal = g.normal.max(normal_error);
        if distance_error.max(normal_error) > tolerance(&size, sigma) {
            g.bad += 1;
        }
    }
    g
}

/// The tolerance of the contact geometry, relative to the contact distance `sigma`:
/// `64 eps (L_max / sigma + 1)`. Centres are coordinates in `[0, L_k]`, each the result of a
/// few roundings of size `eps L_k` (free flight `a + u dt` from the record, the fold into the
/// box, the image `b + k L`); the local clock's rounding moves a ball by `eps` times its
/// flight since the last re-basing; the contact time is solved from the closest approach
/// (`predict::contact_time`), whose roundings are of the size of the centres' offset, not its
/// square. So `|d|` is within `64 eps (L_max + sigma)` of `sigma`, and the engine's `nu` (from
/// the same centres, through the stored image) within `64 eps (L_max / sigma + 1)` of the
/// test's unit minimum-image line. A contact with the wrong image is off by O(1) in `nu`; the
/// clock's rounding at absolute times `t` (before the local clock) moved centres by
/// `eps t |u|`, and the form of the root through `|d|^2 - sigma^2` by `eps |d|^2 / sigma`
/// after a long flight (5e-12 on the Sinai table with canonical contact times).
fn tolerance<const N: usize>(size: &[f64; N], sigma: f64) -> f64 {
    let side = size.iter().copied().fold(0.0, f64::max);
    64.0 * f64::EPSILON * (side / sigma + 1.0)
}

fn scene_geometry<const N: usize, const S: usize>(scene: &Scene, contacts: u64) -> Geometry
where
    Generated: Kernel<f64, N, S>,
{
    geometry(setup::<N, S>(scene).expect("placement succeeds"), contacts)
}

#[test]
fn every_shipped_scene_contacts_at_the_minimum_image_line_of_centres() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    let mut dims = Vec::new();
    let mut failures = Vec::new();
    for path in &paths {
        let scene = scene(path);
        dims.push(scene.dim);
        let g = collision_core::with_dim!(
            scene.dim,
            |N, S| scene_geometry::<N, S>(&scene, 3000),
            unreachable!("dim {}", scene.dim)
        );
        eprintln!("{}: {g:?}", path.display());
        if g.bad > 0 {
            failures.push(format!("{}: {g:?}", path.display()));
        }
    }
    dims.sort();
    dims.dedup();
    assert_eq!(dims, [2, 3, 4, 5, 6], "the shipped scenes cover n = 2..6");
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Two disks (R = 1/2) in a periodic box of side 10.5: disk 1 is 0.07 from the face x = L,
/// moving at (1, 0); disk 0 rests at x = 1.04, so the pair meets across the face at
/// t = 0.07 + 1.04 - sqrt(3)/2, after disk 1 has wrapped (at t = 0.07). Disk 0's entry for that
/// contact was made before the wrap.
#[test]
fn a_contact_across_a_periodic_face_after_the_partner_wrapped() {
    let disk = collision_core::Ball {
        inv_mass: 1.0,
        radius: 0.5,
        gamma2: 0.5,
    };
    let body = |position: [f64; 2], velocity: [f64; 2], spin: f64| Body {
        species: 0,
        position,
        state: collision_core::BodyState {
            spin: [spin],
            velocity,
        },
    };
    let setup = Setup {
        size: [10.5, 10.5],
        periodic: [true, true],
        species: vec![disk],
        obstacles: vec![],
        bodies: vec![
            body([1.04, 5.0], [0.0, 0.0], 0.0),
            body([10.43, 5.5], [1.0, 0.0], 1.0),
        ],
        orientation: false,
        table: noslip_sim::Table::boxed(),
    };
    let mut sim = simulation(setup);
    let e = next(&mut sim).expect("the disks meet");
    // Body 1 is either disk (nu points from it to the other).
    let sign = match e.contact {
        noslip_sim::Contact::Ball { i: 0, j: 1 } => 1.0,
        noslip_sim::Contact::Ball { i: 1, j: 0 } => -1.0,
        c => panic!("{c:?}"),
    };
    let moving = if sign > 0.0 { 1 } else { 0 };
    let want_time = 0.07 + 1.04 - 0.75f64.sqrt();
    assert!((e.time - want_time).abs() < 1e-14, "{}", e.time);
    // Disk 1 has wrapped: it is at x = 0.17 (the wrap at t = 0.07).
    assert!(e.position[moving][0] < 0.5, "{:?}", e.position);
    let d = min_image(&e.position[0], &e.position[1], &[10.5; 2], &[true; 2]);
    let tol = tolerance(&[10.5; 2], 1.0);
    assert!((norm(&d) - 1.0).abs() <= tol, "{d:?}");
    // The minimum-image line of centres is (-sqrt(3)/2, 1/2); the stale image gave
    // (-0.99903, 0.04395), with disk 1 a box length away.
    for k in 0..2 {
        assert!((e.nu[k] - d[k] / norm(&d)).abs() <= tol, "{:?}", e.nu);
    }
    let want = [-0.75f64.sqrt() * sign, 0.5 * sign];
    assert!(
        (0..2).all(|k| (e.nu[k] - want[k]).abs() < 1e-12),
        "{:?}",
        e.nu
    );
}

/// The state of a run after `k` contacts (and, if `until` is given, after running on to the
/// absolute time `until`, with no more contacts), and that time.
fn after<const N: usize, const S: usize>(
    setup: Setup<N, S>,
    k: u64,
    until: Option<f64>,
) -> (Setup<N, S>, f64)
where
    Generated: Kernel<f64, N, S>,
{
    let (size, periodic) = (setup.size, setup.periodic);
    let mut end = setup.clone();
    let mut sim = simulation(setup);
    for n in 0..k {
        assert!(next(&mut sim).is_some(), "contact {n} of {k}");
    }
    if let Some(t) = until {
        assert_eq!(sim.step(t), Step::Until, "no contact after {k}, up to {t}");
    }
    // Centres put back into the box against rounding.
    end.bodies = (0..sim.len())
        .map(|i| {
            let p = sim.position(i);
            Body {
                species: sim.species_of(i),
                position: std::array::from_fn(|a| {
                    if periodic[a] {
                        p[a].rem_euclid(size[a])
                    } else {
                        p[a].clamp(0.0, size[a])
                    }
                }),
                state: sim.state(i).clone(),
            }
        })
        .collect();
    (end, sim.now())
}

/// Every velocity and spin negated.
fn reversed<const N: usize, const S: usize>(mut setup: Setup<N, S>) -> Setup<N, S> {
    for b in &mut setup.bodies {
        b.state.velocity = b.state.velocity.map(|x| -x);
        b.state.spin = b.state.spin.map(|x| -x);
    }
    setup
}

/// The largest differences between two states of the same balls: centres (minimum image),
/// velocities, spins; in units of the box side, the largest speed and the largest spin of `a`.
fn difference<const N: usize, const S: usize>(a: &Setup<N, S>, b: &Setup<N, S>) -> f64 {
    let side = a.size.iter().copied().fold(0.0, f64::max);
    let speed = a
        .bodies
        .iter()
        .map(|b| norm(&b.state.velocity))
        .fold(0.0, f64::max);
    let spin = a
        .bodies
        .iter()
        .flat_map(|b| b.state.spin.iter().map(|x| x.abs()))
        .fold(0.0, f64::max);
    let mut err = 0.0f64;
    for (x, y) in a.bodies.iter().zip(&b.bodies) {
        let d = min_image(&x.position, &y.position, &a.size, &a.periodic);
        err = err.max(norm(&d) / side);
        for k in 0..N {
            err = err.max((x.state.velocity[k] - y.state.velocity[k]).abs() / speed);
        }
        for k in 0..S {
            err = err.max((x.state.spin[k] - y.state.spin[k]).abs() / spin);
        }
    }
    err
}

/// `k` contacts forward to time `T`, every velocity and spin negated, `k` contacts back and
/// on to time `T` (the backward run starts its clock at 0), negated again: the difference from the start. Also the difference after
/// `k` contacts between the run and a twin whose centres started `2^-30` box sides away
/// (alternately along `+-e_0`): how much the gas amplifies a small error over `k` contacts.
fn reversal<const N: usize, const S: usize>(start: Setup<N, S>, k: u64) -> (f64, f64)
where
    Generated: Kernel<f64, N, S>,
{
    let (there, t) = after(start.clone(), k, None);
    let (back, _) = after(reversed(there.clone()), k, Some(t));
    let error = difference(&start, &reversed(back));
    let mut twin = start.clone();
    for (i, b) in twin.bodies.iter_mut().enumerate() {
        let delta = (2.0f64).powi(-30) * start.size[0];
        b.position[0] += if i % 2 == 0 { delta } else { -delta };
        b.position[0] = b.position[0].clamp(0.0, start.size[0]);
    }
    let (twin_there, _) = after(twin, k, None);
    (error, difference(&there, &twin_there))
}

fn shipped<const N: usize, const S: usize>(name: &str) -> Setup<N, S> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(name);
    setup::<N, S>(&scene(&path)).expect("placement succeeds")
}

/// Contacts forward, then back, in a walled gas (gas2d) and a periodic one (gas3d).
///
/// Tolerance: each contact rounds its pair's state in at most ~64 operations of relative
/// error `eps`, so the rounding of the whole run is like perturbing the state by at most
/// `64 k eps` along the way; the twin shows what the gas makes of a `2^-30` perturbation of
/// the start over the same `k` contacts (perturbations made later are amplified less). So
/// the reversal error must stay below the twin's divergence times `64 k eps / 2^-30`
/// (measured: about 10^4 below that bound). The twin's divergence must itself stay small
/// (`<= 1e-3`, the same sequence of events), so the bound is far below the O(1) error of one
/// contact taken with the wrong normal.
#[test]
fn time_reversal_returns_to_the_start() {
    let k = 1000;
    let scale = 64.0 * k as f64 * f64::EPSILON / 2f64.powi(-30);
    for (name, (error, twin)) in [
        ("gas2d", reversal::<2, 1>(shipped("gas2d.toml"), k)),
        ("gas3d", reversal::<3, 3>(shipped("gas3d.toml"), k)),
    ] {
        eprintln!("{name}: reversal error {error:.3e}, twin {twin:.3e}");
        assert!(twin <= 1e-3, "{name}: the twin diverged ({twin})");
        assert!(
            error <= scale * twin,
            "{name}: {k} contacts back return {error:.3e} from the start (bound {:.3e})",
            scale * twin
        );
    }
}

/// Velocities times `factor` (spins kept).
fn slowed<const N: usize, const S: usize>(mut setup: Setup<N, S>, factor: f64) -> Setup<N, S> {
    for b in &mut setup.bodies {
        b.state.velocity = b.state.velocity.map(|x| x * factor);
    }
    setup
}

/// issue 16: a gas started almost at rest (speed 1e-17, spin 1) reaches its first contacts at
/// t ~ 1e17, where the spin turns into O(1) velocities: with absolute times the centres were
/// off by `eps t |u|` ~ 1e-3 at contact.
#[test]
fn contacts_stay_at_contact_distance_after_a_start_almost_at_rest() {
    let g = geometry(slowed(shipped::<3, 3>("gas3d.toml"), 1e-17), 3000);
    eprintln!("{g:?}");
    assert_eq!((g.contacts, g.bad), (3000, 0), "{g:?}");
}

/// A long run of the Sinai billiard (one disk, 10^5 obstacle contacts, t ~ 5e4): with absolute
/// times the contact distance drifted by `eps t |u|`.
#[test]
fn contacts_stay_at_contact_distance_in_a_long_run() {
    let g = geometry(shipped::<2, 1>("sinai.toml"), 100_000);
    eprintln!("{g:?}");
    assert_eq!((g.contacts, g.bad), (100_000, 0), "{g:?}");
}

/// `(mean, standard error)` of `xs`.
fn mean_and_error(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// `(|nu|^2 - 1) / eps`, with `|nu|^2` summed exactly.
fn unit_offset<const N: usize>(nu: &[f64; N]) -> f64 {
    use num_rational::BigRational;
    use num_traits::{One, ToPrimitive};
    let q = |x: f64| BigRational::from_float(x).expect("finite");
    let sum: BigRational = nu.iter().map(|x| q(*x) * q(*x)).sum();
    (sum - BigRational::one()).to_f64().expect("small") / f64::EPSILON
}

/// Issue 11 item 3: a reflection at a normal with `|nu|^2 != 1` changes the energy by
/// `2 m (|nu|^2 - 1) (...)`, so a normal whose `|nu|^2 - 1` has a non-zero mean over the orbit
/// drifts the energy linearly. Along Sinai's orbit the plain `d / sqrt(sum d^2)` has such a
/// mean (+0.03 eps, many standard errors); the engine's normals, from an accurate `|d|`, must
/// have none (within 4 standard errors, computed exactly contact by contact).
#[test]
fn sinai_normals_are_unit_on_average() {
    let setup: Setup<2, 1> = shipped("sinai.toml");
    let centre = setup.obstacles[0].position;
    let (size, periodic) = (setup.size, setup.periodic);
    let mut sim = simulation(setup);
    let (mut engine, mut plain) = (Vec::new(), Vec::new());
    while engine.len() < 20_000 {
        let e = next(&mut sim).expect("Sinai never stops");
        // The obstacle's image nearest the ball, as the engine's image shifts place it.
        let d = min_image(&centre, &e.position[0], &size, &periodic);
        let r = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        engine.push(unit_offset(&e.nu));
        plain.push(unit_offset(&d.map(|x| x / r)));
    }
    let (mean, error) = mean_and_error(&engine);
    assert!(
        mean.abs() < 4.0 * error,
        "engine: mean |nu|^2 - 1 = {mean} eps, standard error {error}"
    );
    let (mean, error) = mean_and_error(&plain);
    assert!(
        mean.abs() > 4.0 * error,
        "plain: mean |nu|^2 - 1 = {mean} eps, standard error {error} (the test must tell the two apart)"
    );
}

/// `[box] contact` sets the law of the box's walls: a ball meeting a wall of a box with the
/// rough law `{ e = 1/2, beta = 1/4 }` leaves it with the rough kernel's state (bit for bit)
/// and with its normal velocity `-e` times what it was (first principles: spin moves only the
/// contact point's tangential velocity), and under `"smooth"` with its tangential velocity
/// and spin unchanged; the default is no-slip.
#[test]
fn the_box_walls_follow_their_contact_law() {
    use noslip_sim::rough::{fixed, RoughLaw};
    let text = |contact: &str| {
        format!(
            "dim = 2\n[box]\nsize = [10, 10]\nboundary = [\"wall\", \"wall\"]\n{contact}\n\
             [[species]]\nmass = 1\nradius = \"1/2\"\n\
             [[ball]]\nspecies = 0\nposition = [5, 5]\nvelocity = [1, \"3/10\"]\n\
             angular_velocity = 2\n"
        )
    };
    let first = |contact: &str| {
        let scene = Scene::from_toml(&text(contact), "box.toml").unwrap();
        let setup = setup::<2, 1>(&scene).unwrap();
        let ball = setup.species[0].clone();
        let mut sim = simulation(setup);
        let e = next(&mut sim).expect("a wall ahead");
        assert!(
            matches!(e.contact, noslip_sim::Contact::Wall { axis: 0, .. }),
            "{e:?}"
        );
        (e, ball)
    };
    let (e, ball) = first("contact = { e = \"1/2\", beta = \"1/4\" }");
    let law = RoughLaw::Constant(collision_core::Restitution { e: 0.5, beta: 0.25 });
    assert_eq!(e.post[0], fixed(&e.nu, &ball, &law, &e.pre[0]));
    let normal = |s: &collision_core::BodyState<f64, 2, 1>| s.velocity[0];
    assert!((normal(&e.post[0]) + 0.5 * normal(&e.pre[0])).abs() < 1e-15);
    let (e, _) = first("contact = \"smooth\"");
    assert_eq!(
        e.post[0].velocity,
        [-e.pre[0].velocity[0], e.pre[0].velocity[1]]
    );
    assert_eq!(e.post[0].spin, e.pre[0].spin);
    let (no_slip, _) = first("");
    let (named, _) = first("contact = \"no-slip\"");
    assert_eq!(no_slip, named);
    assert_ne!(no_slip.post[0].spin, no_slip.pre[0].spin);
}
