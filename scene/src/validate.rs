//! Semantic checks of a parsed scene, in exact rationals. Each error names its key path.

use crate::ctx::Ctx;
use crate::number::show_q;
use crate::raw::{Distribution, RawBall, RawScene, RawSpecies, RawSpin};
use crate::table::{self, Shape};
use crate::ContactKind;
use crate::{
    BallSpec, Boundary, Obstacle, Placement, Random, RunDefaults, Scene, SceneError, Species,
    MAX_BALLS,
};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

type Q = BigRational;

fn q(n: i64) -> Q {
    Q::from_integer(n.into())
}

/// `gamma^2` from the species' inertia keys: `lambda` in `[0, R^2/n]` (`gamma^2 = 2 lambda /
/// R^2`), `gamma2` in `[0, 2/n]`, `distribution` uniform (`2/(n+2)`) or shell (`2/n`); none
/// means uniform. The bounds are those of `collision_core::Ball::new`, under the same rounding
/// allowance (`collision_core::allowance`) with the epsilon of `f64`, the arithmetic scenes
/// run in: a value within `8 eps` of its range (relative to the bound) is clamped to it
/// exactly, so an `f64` printed in full (`lambda = "8.333333333333334"` for `R = 5` in 3D)
/// is the shell `25/3` it stands for.
fn gamma2(ctx: &Ctx, at: &str, s: &RawSpecies, radius: &Q, n: usize) -> Result<Q, SceneError> {
    let nq = q(n as i64);
    let shell = q(2) / &nq;
    let given = [
        s.lambda.is_some(),
        s.gamma2.is_some(),
        s.distribution.is_some(),
    ];
    if given.iter().filter(|&&g| g).count() > 1 {
        return Err(ctx.err(at, "give at most one of lambda, gamma2 and distribution"));
    }
    let in_range = |x: &Q, bound: &Q, key: &str, what: &str| {
        allowance::within(x, &Q::zero(), bound, &f64_allowance(bound)).ok_or_else(|| {
            ctx.err(
                format!("{at}.{key}"),
                format!(
                    "must be in [0, {what}] = [0, {}], got {}",
                    show_q(bound),
                    show_q(x)
                ),
            )
        })
    };
    Ok(match (&s.lambda, &s.gamma2, s.distribution) {
        (Some(l), _, _) => {
            let r2 = radius * radius;
            let l = in_range(&l.0, &(&r2 / &nq), "lambda", "R^2/n")?;
            q(2) * l / r2
        }
        (_, Some(g), _) => in_range(&g.0, &shell, "gamma2", "2/n")?,
        (_, _, Some(Distribution::Shell)) => shell,
        _ => q(2) / (nq + q(2)),
    })
}

/// The rounding allowance of `f64` at scale `s`: `ULPS 2^-52 |s|`.
fn f64_allowance(s: &Q) -> Q {
    let eps = Q::new(BigInt::one(), BigInt::one() << 52);
    Q::from_integer(allowance::ULPS.into()) * eps * s.abs()
}

/// The rule of collision-core's checked `collide`, compiled here from its one source file
/// (collision-core builds with this crate, so this crate cannot depend on it). Its items are
/// `pub` for collision-core's API and unreachable from this private module.
#[path = "../../collision-core/src/allowance.rs"]
#[allow(unreachable_pub)]
mod allowance;

fn spin(ctx: &Ctx, at: &str, s: &Option<RawSpin>, n: usize) -> Result<Vec<Q>, SceneError> {
    let len = n * (n - 1) / 2;
    let Some(s) = s else {
        return Ok(vec![Q::zero(); len]);
    };
    let place = format!("{at}.angular_velocity");
    match s {
        RawSpin::Scalar(c) if n == 2 => Ok(vec![-c.0.clone()]),
        RawSpin::Vector(w) if n == 3 && w.len() == 3 => {
            let (w1, w2, w3) = (&w[0].0, &w[1].0, &w[2].0);
            Ok(vec![-w3.clone(), w2.clone(), -w1.clone()])
        }
        RawSpin::Matrix(m) if m.len() == n && m.iter().all(|r| r.len() == n) => {
            let at = |i: usize, j: usize| &m[i][j].0;
            for i in 0..n {
                for j in i..n {
                    if *at(i, j) != -at(j, i).clone() {
                        return Err(ctx.err(
                            place,
                            format!("not skew: entries ({i},{j}) and ({j},{i}) are not opposite"),
                        ));
                    }
                }
            }
            Ok((0..n)
                .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
                .map(|(i, j)| at(i, j).clone())
                .collect())
        }
        _ => Err(ctx.err(
            place,
            format!(
                "expected the {n} x {n} skew matrix{}",
                match n {
                    2 => " or a number c (U = c J)",
                    3 => " or a 3-vector omega (U x = omega x x)",
                    _ => "",
                }
            ),
        )),
    }
}

/// `random.temperature` when `random.velocities = "maxwellian"` (default 1, `> 0`; `speed` and
/// `spin` then refused), `None` for `"uniform"` (the default; `temperature` then refused).
fn temperature(ctx: &Ctx, raw: &RawScene) -> Result<Option<Q>, SceneError> {
    let r = &raw.random;
    match r.velocities.as_deref() {
        None | Some("uniform") => match r.temperature {
            Some(_) => Err(ctx.err(
                "random.temperature",
                "needs velocities = \"maxwellian\" (uniform velocities take speed and spin)",
            )),
            None => Ok(None),
        },
        Some("maxwellian") => {
            if let Some(key) = [("speed", &r.speed), ("spin", &r.spin)]
                .iter()
                .find_map(|(k, v)| v.is_some().then_some(k))
            {
                return Err(ctx.err(
                    format!("random.{key}"),
                    "Maxwellian velocities take a temperature, not speed or spin",
                ));
            }
            match &r.temperature {
                Some(t) => Ok(Some(ctx.positive("random.temperature", t)?)),
                None => Ok(Some(Q::one())),
            }
        }
        Some(other) => Err(ctx.err(
            "random.velocities",
            format!("must be \"uniform\" or \"maxwellian\", got {other:?}"),
        )),
    }
}

/// Squared distance of `a` and `b`, with the minimum image on periodic axes.
pub(crate) fn distance2(a: &[Q], b: &[Q], size: &[Q], boundary: &[Boundary]) -> Q {
    let mut d2 = Q::zero();
    for k in 0..a.len() {
        let mut d = (&a[k] - &b[k]).abs();
        if boundary.get(k) == Some(&Boundary::Periodic) {
            let other = &size[k] - &d;
            if other < d {
                d = other;
            }
        }
        d2 += &d * &d;
    }
    d2
}

/// The number of balls, explicit and random, summed in `u128` (no overflow), is at most
/// Two point masses (`lambda = 0`) that can collide under a law with a tangential part: the
/// no-slip map (and the rough one with `beta > -1`) is undefined there. Refused naming
/// `species` when the law is `contact.balls`, else the pair's `contact.pair[i].law`.
fn point_masses(ctx: &Ctx, scene: &Scene) -> Result<(), SceneError> {
    let per_species = scene.balls_per_species();
    let points: Vec<usize> = (0..scene.species.len())
        .filter(|&k| scene.species[k].gamma2.is_zero() && per_species[k] > 0)
        .collect();
    for (i, &a) in points.iter().enumerate() {
        for &b in &points[i..] {
            if (a == b && per_species[a] < 2) || !scene.ball_law(a, b).tangential() {
                continue;
            }
            let listed = (scene.pair_contacts.iter()).position(|p| p.species == [a, b]);
            return Err(ctx.err(
                listed.map_or("species".into(), |k| format!("contact.pair[{k}].law")),
                "two point masses (lambda = 0) could collide, where the no-slip map (and the \
                 rough one with beta > -1) is undefined: at most one ball may have lambda = 0, \
                 or point masses need a smooth law between them",
            ));
        }
    }
    Ok(())
}

/// [`MAX_BALLS`]; the error names the species whose `count` passes it.
fn count_limit(ctx: &Ctx, raw: &RawScene) -> Result<(), SceneError> {
    let mut total = raw.ball.len() as u128;
    for (i, s) in raw.species.iter().enumerate() {
        total += s.count as u128;
        if total > MAX_BALLS as u128 {
            return Err(ctx.err(
                format!("species[{i}].count"),
                format!(
                    "{total} balls (with the explicit ones and the species before) exceed the \
                     limit of 2^24 = {MAX_BALLS}: the simulator keeps a few hundred bytes per \
                     ball and places the random ones one by one"
                ),
            ));
        }
    }
    Ok(())
}

fn ball(ctx: &Ctx, i: usize, b: &RawBall, scene: &Scene) -> Result<BallSpec, SceneError> {
    let at = format!("ball[{i}]");
    let n = scene.dim;
    let species = scene.species.get(b.species).ok_or_else(|| {
        ctx.err(
            format!("{at}.species"),
            format!(
                "no species {} (the scene has {}, numbered from 0)",
                b.species,
                scene.species.len()
            ),
        )
    })?;
    let position = ctx.vector(&format!("{at}.position"), &b.position, n)?;
    let r = &species.radius;
    for (k, x) in position.iter().enumerate().take(scene.boundary.len()) {
        let (lo, hi, what) = match scene.boundary[k] {
            Boundary::Wall => (
                r.clone(),
                &scene.size[k] - r,
                "[R, L - R] (inside the walls)",
            ),
            Boundary::Periodic => (Q::zero(), scene.size[k].clone(), "[0, L)"),
        };
        let outside = x < &lo || x > &hi || (scene.boundary[k] == Boundary::Periodic && x == &hi);
        if outside {
            return Err(ctx.err(
                format!("{at}.position[{k}]"),
                format!("the ball is outside the box: {x} is not in {what} = [{lo}, {hi}]"),
            ));
        }
    }
    let velocity = match &b.velocity {
        Some(v) => ctx.vector(&format!("{at}.velocity"), v, n)?,
        None => vec![Q::zero(); n],
    };
    Ok(BallSpec {
        species: b.species,
        position,
        velocity,
        spin: spin(ctx, &at, &b.angular_velocity, n)?,
    })
}

pub(super) fn validate(raw: RawScene, origin: &str) -> Result<Scene, SceneError> {
    let ctx = Ctx { origin };
    let n = raw.dim;
    if !(2..=6).contains(&n) {
        return Err(ctx.err("dim", format!("must be in 2..=6, got {n}")));
    }
    let (size, boundary) = match &raw.domain {
        Some(domain) => {
            let size = ctx.vector("box.size", &domain.size, n)?;
            for (k, l) in size.iter().enumerate() {
                if !l.is_positive() {
                    return Err(ctx.err(
                        format!("box.size[{k}]"),
                        format!("must be positive, got {}", show_q(l)),
                    ));
                }
            }
            if domain.boundary.len() != n {
                return Err(ctx.err(
                    "box.boundary",
                    format!(
                        "has {} entries, expected dim = {n} (\"wall\" or \"periodic\" per axis)",
                        domain.boundary.len()
                    ),
                ));
            }
            (size, domain.boundary.clone())
        }
        None => (Vec::new(), Vec::new()),
    };
    let periodic = boundary.contains(&Boundary::Periodic);
    let (boundaries, polygons) = table::boundaries(&raw, origin, periodic)?;
    if raw.species.is_empty() {
        return Err(ctx.err("species", "a scene needs at least one species"));
    }
    let mut species = Vec::new();
    for (i, s) in raw.species.iter().enumerate() {
        let at = format!("species[{i}]");
        let mass = ctx.positive(&format!("{at}.mass"), &s.mass)?;
        let radius = ctx.positive(&format!("{at}.radius"), &s.radius)?;
        for (k, l) in size.iter().enumerate() {
            if *l <= q(2) * &radius {
                return Err(ctx.err(
                    format!("{at}.radius"),
                    format!("a ball of radius {radius} does not fit: box.size[{k}] = {l} <= 2 R"),
                ));
            }
        }
        let gamma2 = gamma2(&ctx, &at, s, &radius, n)?;
        let gamma2_key = match (&s.lambda, &s.gamma2, s.distribution) {
            (Some(_), _, _) => Some("lambda"),
            (_, Some(_), _) => Some("gamma2"),
            (_, _, Some(_)) => Some("distribution"),
            _ => None,
        };
        species.push(Species {
            name: s.name.clone().unwrap_or_else(|| format!("species{i}")),
            inv_mass: Q::one() / &mass,
            mass,
            radius,
            gamma2,
            gamma2_key,
            count: s.count,
        });
    }
    count_limit(&ctx, &raw)?;
    let placement = match raw.random.placement.as_deref() {
        None | Some("random") => Placement::Random,
        Some("lattice") => Placement::Lattice,
        Some(other) => {
            return Err(ctx.err(
                "random.placement",
                format!("must be \"random\" or \"lattice\", got {other:?}"),
            ))
        }
    };
    let random = Random {
        seed: raw.random.seed,
        placement,
        speed: raw
            .random
            .speed
            .as_ref()
            .map_or_else(Q::one, |x| x.0.clone()),
        spin: raw
            .random
            .spin
            .as_ref()
            .map_or_else(Q::zero, |x| x.0.clone()),
        temperature: None,
    };
    let random = Random {
        temperature: temperature(&ctx, &raw)?,
        ..random
    };
    for (key, x) in [
        ("random.speed", &random.speed),
        ("random.spin", &random.spin),
    ] {
        if x.is_negative() {
            return Err(ctx.err(key, format!("must be >= 0, got {}", show_q(x))));
        }
    }
    if raw.simulation.events == Some(0) {
        return Err(ctx.err(
            "simulation.events",
            "must be at least 1 (a run of no contacts has nothing to report)",
        ));
    }
    let simulation = RunDefaults {
        events: raw.simulation.events,
        time: match &raw.simulation.time {
            Some(t) => Some(ctx.positive("simulation.time", t)?),
            None => None,
        },
        orientation: raw.simulation.orientation,
    };
    let pair_contacts = crate::pair_law::pair_laws(&ctx, &raw.contact.pair, &species)?;
    let mut scene = Scene {
        origin: origin.to_string(),
        description: raw.description.unwrap_or_default(),
        dim: n,
        size,
        boundary,
        species,
        balls: Vec::new(),
        obstacles: Vec::new(),
        random,
        simulation,
        boundaries,
        polygons,
        ball_contact: ctx.contact("contact.balls", &raw.contact.balls)?,
        pair_contacts,
        box_contact: match &raw.domain {
            Some(domain) => ctx.contact("box.contact", &domain.contact)?,
            None => ContactKind::NoSlip,
        },
        tc: match &raw.contact.tc {
            Some(tc) => {
                let tc = ctx.positive("contact.tc", tc)?;
                // The engine compares times in f64: a t_c below the normal range has lost its
                // precision, and one that rounds to 0 would silently be no TC model.
                if !tc.to_f64().is_some_and(f64::is_normal) {
                    return Err(ctx.err(
                        "contact.tc",
                        format!(
                            "{tc} is not a normal f64 (the least is {:e}): the engine's times \
                             are f64, and a t_c that rounds to 0 is no TC model",
                            f64::MIN_POSITIVE
                        ),
                    ));
                }
                Some(tc)
            }
            None => None,
        },
        thermostat: crate::thermostat::thermostat(&ctx, &raw.thermostat)?,
    };
    if scene.size.is_empty() {
        if let Some(k) = scene.species.iter().position(|s| s.count > 0) {
            return Err(ctx.err(
                format!("species[{k}].count"),
                "random placement needs a [box] to place in: without one, place the balls \
                 with [[ball]]",
            ));
        }
    }
    for b in &scene.boundaries {
        if let Shape::Container { radius, .. } = &b.shape {
            if let Some(k) = scene
                .species
                .iter()
                .position(|s| s.count > 0 && &s.radius >= radius)
            {
                return Err(ctx.err(
                    format!("{}.radius", b.place),
                    format!(
                        "too small: the radius {radius} is not larger than species[{k}]'s \
                         radius {}",
                        scene.species[k].radius
                    ),
                ));
            }
        }
    }
    for (i, o) in raw.obstacle.iter().enumerate() {
        let at = format!("obstacle[{i}]");
        let position = ctx.vector(&format!("{at}.position"), &o.position, n)?;
        let radius = ctx.positive(&format!("{at}.radius"), &o.radius)?;
        if let Some(k) = (0..scene.size.len())
            .find(|&k| position[k].is_negative() || position[k] > scene.size[k])
        {
            return Err(ctx.err(
                format!("{at}.position[{k}]"),
                format!(
                    "the centre {} is outside the box [0, {}]",
                    position[k], scene.size[k]
                ),
            ));
        }
        scene.obstacles.push(Obstacle {
            position,
            radius,
            contact: ctx.contact(&format!("{at}.contact"), &o.contact)?,
        });
    }
    for (i, b) in raw.ball.iter().enumerate() {
        let spec = ball(&ctx, i, b, &scene)?;
        let r = &scene.species[spec.species].radius;
        let overlap = |p: &[Q], other_r: &Q| {
            let s = r + other_r;
            distance2(&spec.position, p, &scene.size, &scene.boundary) < &s * &s
        };
        if let Some(j) = scene
            .balls
            .iter()
            .position(|o| overlap(&o.position, &scene.species[o.species].radius))
        {
            return Err(ctx.err(
                format!("ball[{i}].position"),
                format!("overlaps ball[{j}] (centre distance < R_{i} + R_{j})"),
            ));
        }
        if let Some(j) = scene
            .obstacles
            .iter()
            .position(|o| overlap(&o.position, &o.radius))
        {
            return Err(ctx.err(
                format!("ball[{i}].position"),
                format!("overlaps obstacle[{j}]"),
            ));
        }
        if let Some(why) = scene
            .boundaries
            .iter()
            .find_map(|b| table::misfit(b, &spec.position, r))
        {
            return Err(ctx.err(format!("ball[{i}].position"), why));
        }
        if let Some(b) = scene
            .boundaries
            .iter()
            .find(|b| table::grazes_inside(b, &spec.position, r, &spec.velocity))
        {
            return Err(ctx.err(
                format!("ball[{i}].velocity"),
                format!(
                    "the ball touches {} from inside moving along it (velocity tangent): a \
                     degenerate graze whose straight flight leaves the container; move it \
                     inside or turn its velocity",
                    b.place
                ),
            ));
        }
        if let Some(g) = scene
            .boundaries
            .iter()
            .filter_map(|b| match (&b.shape, b.polygon) {
                // Each polygon obstacle once, by its first edge (a test per edge made the
                // check quadratic in the vertices).
                (Shape::Edge { .. }, Some((g, 0))) => Some(g),
                _ => None,
            })
            .find(|&g| table::inside_polygon(&scene.polygons[g], &spec.position))
        {
            let place = &scene.boundaries[scene
                .boundaries
                .iter()
                .position(|b| b.polygon.is_some_and(|(h, _)| h == g))
                .expect("a polygon's pieces")]
            .place;
            return Err(ctx.err(
                format!("ball[{i}].position"),
                format!("inside the polygon obstacle of {place}"),
            ));
        }
        scene.balls.push(spec);
    }
    point_masses(&ctx, &scene)?;
    if scene.ball_count() == 0 {
        return Err(ctx.err(
            "species",
            "the scene has no balls: give count or [[ball]] entries",
        ));
    }
    Ok(scene)
}
