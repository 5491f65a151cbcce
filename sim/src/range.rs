//! The scene in the simulator's arithmetic. A scene is exact; the simulator rounds each number
//! once to f64 and the engine then forms products of a few of them. A scene runs only if every
//! such quantity is a **normal** f64, `2^-1022 <= |x| < 2^1024`: no overflow to infinity and
//! no underflow to 0 or to a subnormal (which keeps fewer than 53 bits) of a quantity that
//! must be positive. Otherwise the command exits with code 2 and names the field. The
//! quantities, with the code that forms them:
//!
//! - per species: `m` and `w = 1/m` (`w` in every contact map, `m = 1/w` in the energy):
//!   `2^-1022 <= m <= 2^1022`; `R^2` (contact times compare `|d|^2` with `(R_i + R_j)^2`,
//!   [`crate::predict`]): `2^-511 <= R < 2^511`; when `gamma^2 > 0`, `gamma^2`
//!   and `lambda = gamma^2 R^2 / 2` (energy and the maps);
//! - per pair of species that can meet: the contact map's `D = w_1 g_2 (1 + g_1) + g_1 w_2 (1
//!   + g_2)`, `R_1 D`, `R_2 D`, `g_1 g_2` (`g = gamma^2`) and the map's `g_1 g_2 / D` and
//!   `2 w_1 g_2 / (R_1 D)`, in the kernel's order of operations;
//! - the box: every side `L_k`, and the square of the **box scale** `B = 4 sqrt(n) max(L_max,
//!   d_max)` (`d_max` the largest contact distance, ball-ball or ball-obstacle), which bounds
//!   every centre offset `|d|` the cell search forms (a neighbouring cell and one image
//!   away); an obstacle's radius enters only there and in `R + R_o >= R`;
//! - **resolution**: the smallest radius is at least `2^-26 L_max`. Positions near the far
//!   side of the box are rounded to about `eps L_max` (`eps = 2^-52`); this keeps the contact
//!   distance, and `nu`, to at least half the f64 digits;
//! - the start: each ball's `|u|^2` and `|U|^2` (sums of squares, when not 0), `R |U|` (the
//!   contact-point speed), `lambda |U|^2` and its energy `1/2 m (|u|^2 + 2 lambda |U|^2)`;
//!   for the random balls the same with every component at `random.speed` and
//!   `random.spin`; the total mass `M` and an upper bound `E` of the start energy (finite),
//!   and `E > 0` (something moves: the drift `(E - E_0)/E_0` needs `E_0 > 0`);
//! - the largest speed: by energy conservation no ball ever has `|u| > sqrt(2 E / m)` nor a
//!   contact-point speed `R |U| > sqrt(2 E / (m gamma^2))`; with `V` twice the largest of
//!   these (a relative speed), `(B V)^2` bounds the terms `b^2` and `a c` of the contact-time
//!   discriminant at the box scale and must be finite, as must `B sqrt(2 E M)` (angular
//!   momentum);
//! - after placement, the actual start energy `E_0` (normal), the typical speed `v =
//!   sqrt(2 E_0 / M)`: the discriminant at the contact scale, `(R_min v)^2`, must be normal
//!   and the time to cross the box, `B / v`, finite.
//!
//! The bounds hold for any choice of units: scaling lengths, times and masses by powers of
//! two changes no digit of a run, so a scene far from 1 in every unit is fine as long as the
//! products above stay in range.

use crate::nearest::f;
use crate::{Observables, Setup};
use noslip_scene::Scene;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// The smallest radius as a fraction of the largest box side, `2^-26`: positions are rounded
/// to `eps L = 2^-52 L`, so contact distances keep at least 26 of the 52 bits.
pub const RESOLUTION: f64 = 1.0 / (1u64 << 26) as f64;

/// What the check after placement needs from the check before it.
#[derive(Clone, Debug)]
pub struct Scales {
    /// `B = 4 sqrt(n) max(L_max, d_max)`.
    pub box_scale: f64,
    /// The field that sets `B`.
    box_field: String,
    /// The smallest radius of a ball, and its field.
    radius_min: f64,
    radius_field: String,
    /// Total mass `M`.
    mass: f64,
    /// The field of the largest start-energy term.
    energy_field: String,
}

/// A number for messages: its f64 value when that is normal, else its decimal magnitude.
fn show(x: &BigRational) -> String {
    let v = f(x);
    if v.is_normal() || x.is_zero() {
        format!("{v:e}")
    } else {
        // Beyond the normal range of f64: its decimal logarithm from the integers' leading
        // bits (the quotient itself would round to 0, a subnormal or infinity).
        let log10 = |n: &num_bigint::BigInt| {
            let shift = n.bits().saturating_sub(60);
            let lead = (n.magnitude() >> shift).to_f64().unwrap_or(f64::NAN);
            lead.log10() + shift as f64 * std::f64::consts::LOG10_2
        };
        let l = log10(x.numer()) - log10(x.denom());
        let (mut e, mut m) = (
            l.floor(),
            (10f64.powf(l - l.floor()) * 100.0).round() / 100.0,
        );
        if m >= 10.0 {
            (e, m) = (e + 1.0, m / 10.0);
        }
        let sign = if x.is_negative() { "-" } else { "" };
        format!("about {sign}{m:.2}e{e:.0}")
    }
}

/// The field of the quantity farther from 1 (in binary orders of magnitude) of two factors.
fn farther<'a>(a: f64, a_field: &'a str, b: f64, b_field: &'a str) -> &'a str {
    if a.log2().abs() >= b.log2().abs() {
        a_field
    } else {
        b_field
    }
}

/// One species in f64, as the engine sees it.
struct Constants {
    m: f64,
    w: f64,
    r: f64,
    g: f64,
    lambda: f64,
}

fn species(scene: &Scene) -> Result<Vec<Constants>, String> {
    let mut out = Vec::new();
    for (k, s) in scene.species.iter().enumerate() {
        let (m, w) = (f(&s.mass), f(&s.inv_mass));
        if !(m.is_normal() && w.is_normal() && (1.0 / w).is_normal()) {
            return Err(format!(
                "species[{k}].mass: m = {} gives 1/m = {w:e} in f64: m and 1/m must both be \
                 normal f64 numbers, 2^-1022 <= m <= 2^1022 (about 2.2e-308 to 4.5e307); the \
                 engine uses 1/m in every contact and m in the energy",
                show(&s.mass)
            ));
        }
        let r = f(&s.radius);
        if !(r * r).is_normal() {
            return Err(format!(
                "species[{k}].radius: R = {} gives R^2 = {:e} in f64: contact times compare \
                 squared distances with (R_i + R_j)^2, so R^2 must be a normal f64, \
                 2^-511 <= R < 2^511 (about 1.5e-154 to 6.7e153)",
                show(&s.radius),
                r * r
            ));
        }
        let g = f(&s.gamma2);
        let lambda = g * r * r / 2.0;
        if !(s.gamma2.is_zero() || g.is_normal() && lambda.is_normal()) {
            // A uniform or shell ball has gamma^2 >= 1/4: only its radius can be at fault.
            let key = s
                .gamma2_key
                .filter(|&k| k != "distribution")
                .unwrap_or("radius");
            return Err(format!(
                "species[{k}].{key}: gamma^2 = {} gives lambda = gamma^2 R^2 / 2 = {lambda:e} in \
                 f64: a positive lambda must be a normal f64 (it weighs the spin in the energy \
                 and in every contact)",
                show(&s.gamma2)
            ));
        }
        out.push(Constants { m, w, r, g, lambda });
    }
    Ok(out)
}

/// The species constants the ball-ball map forms (see the generated `free`), for species `a`
/// (body 1) and `b` (body 2): all must be normal, or finite where they may be 0.
fn pair(a: &Constants, b: &Constants) -> Result<(), String> {
    let d = (a.g + 1.0) * (a.w * b.g) + (b.g + 1.0) * (a.g * b.w);
    let (rd1, rd2) = (a.r * d, b.r * d);
    let both = a.g > 0.0 && b.g > 0.0;
    let p_t = a.g * b.g / d;
    let rho1 = b.g * (2.0 * a.w) / rd1;
    let rho2 = a.g * (2.0 * b.w) / rd2;
    let fine = d.is_normal()
        && rd1.is_normal()
        && rd2.is_normal()
        && (!both || (a.g * b.g).is_normal())
        && p_t.is_finite()
        && rho1.is_finite()
        && rho2.is_finite()
        && (a.w + b.w).is_finite();
    if fine {
        Ok(())
    } else {
        Err(format!(
            "the contact map's D = w_1 g_2 (1 + g_1) + g_1 w_2 (1 + g_2) = {d:e}, R_1 D = \
             {rd1:e}, R_2 D = {rd2:e} (g = gamma^2) must be normal f64 numbers: the masses, \
             radii or inertias are too far apart"
        ))
    }
}

/// The checks before placement (see the module docs); errors are `field: message`.
pub fn check_scene(scene: &Scene) -> Result<Scales, String> {
    let n = scene.dim;
    let s_len = n * (n - 1) / 2;
    let sp = species(scene)?;
    let per_species = scene.balls_per_species();
    let used: Vec<usize> = (0..sp.len()).filter(|&k| per_species[k] > 0).collect();
    for (x, &k) in used.iter().enumerate() {
        for &l in &used[x..] {
            let meets = k != l || per_species[k] > 1;
            let points = scene.species[k].gamma2.is_zero() && scene.species[l].gamma2.is_zero();
            if meets && !points {
                pair(&sp[k], &sp[l])
                    .map_err(|e| format!("species[{l}]: with species[{k}], {e}"))?;
            }
        }
    }
    // An obstacle's radius enters only through the contact distance R + R_o (the map takes
    // the obstacle's radius as 1), which the ball's R^2 and the box scale bound.
    let mut obstacle_max = (0.0f64, 0);
    for (i, o) in scene.obstacles.iter().enumerate() {
        let r = f(&o.radius);
        if r > obstacle_max.0 {
            obstacle_max = (r, i);
        }
    }
    let mut side_max = (0.0f64, 0);
    if scene.size.is_empty() {
        // No box: the table's extent (`crate::extent`) plays the box's part.
        let (lo, size) = crate::extent::extent_dyn(scene);
        let side = size.iter().copied().fold(0.0, f64::max);
        let corner = lo.iter().map(|x| x.abs()).fold(0.0, f64::max);
        side_max.0 = side.max(corner);
        if !(side_max.0.is_finite() && (side_max.0 * side_max.0).is_finite()) {
            return Err(format!(
                "{}: the table's extent {:e} overflows f64 when squared",
                scene
                    .boundaries
                    .first()
                    .map_or("ball[0].position", |b| &b.place),
                side_max.0
            ));
        }
    }
    for (k, l) in scene.size.iter().enumerate() {
        let v = f(l);
        if !v.is_normal() {
            return Err(format!(
                "box.size[{k}]: {} rounds to {v:e} in f64, which is not a normal f64",
                show(l)
            ));
        }
        if v > side_max.0 {
            side_max = (v, k);
        }
    }
    let (mut r_max, mut r_min) = (0.0f64, (f64::INFINITY, 0));
    for &k in &used {
        r_max = r_max.max(sp[k].r);
        if sp[k].r < r_min.0 {
            r_min = (sp[k].r, k);
        }
    }
    let d_max = (2.0 * r_max).max(r_max + obstacle_max.0);
    let box_field = if scene.size.is_empty() {
        "the table's extent".to_string()
    } else if side_max.0 >= d_max {
        format!("box.size[{}]", side_max.1)
    } else {
        format!("obstacle[{}].radius", obstacle_max.1)
    };
    let box_scale = 4.0 * (n as f64).sqrt() * side_max.0.max(d_max);
    if !(box_scale * box_scale).is_finite() {
        return Err(format!(
            "{box_field}: the box scale B = 4 sqrt(n) max(L_max, d_max) = {box_scale:e} bounds \
             the centre offsets the engine squares, and B^2 overflows f64: B must stay below \
             2^511 (about 6.7e153)"
        ));
    }
    if r_min.0 < RESOLUTION * side_max.0 {
        return Err(format!(
            "species[{}].radius: R = {:e} is less than 2^-26 of the largest box side {:e}: \
             positions are rounded to about 2^-52 of the box side, so contact distances would \
             keep fewer than half the f64 digits",
            r_min.1, r_min.0, side_max.0
        ));
    }
    let start = start_bounds(scene, &sp, &per_species, n, s_len)?;
    if let Some(t) = &scene.simulation.time {
        let v = f(t);
        if !v.is_normal() {
            return Err(format!(
                "simulation.time: {} rounds to {v:e} in f64, which is not a normal f64",
                show(t)
            ));
        }
    }
    // The largest relative speed a contact can ever see (energy conservation).
    let e = start.energy;
    let mut v_max = start.point_spin;
    for &k in &used {
        v_max = v_max.max((2.0 * e / sp[k].m).sqrt());
        if sp[k].g > 0.0 {
            v_max = v_max.max((2.0 * e / (sp[k].m * sp[k].g)).sqrt());
        }
    }
    v_max *= 2.0;
    let bv = box_scale * v_max;
    let momentum = box_scale * (2.0 * e).sqrt() * start.mass.sqrt();
    if !(bv * bv).is_finite() || !momentum.is_finite() {
        return Err(format!(
            "{}: the box scale B = {box_scale:e} times the largest speed energy allows, V = \
             {v_max:e}, overflows the contact-time discriminant: (B V)^2 = {:e} (or the \
             angular momentum B sqrt(2 E M) = {momentum:e}) must be finite",
            farther(box_scale, &box_field, v_max, &start.energy_field),
            bv * bv
        ));
    }
    Ok(Scales {
        box_scale,
        box_field,
        radius_min: r_min.0,
        radius_field: format!("species[{}].radius", r_min.1),
        mass: start.mass,
        energy_field: start.energy_field,
    })
}

/// Upper bounds of the start state (before the random draws).
struct Start {
    /// An upper bound of the start energy.
    energy: f64,
    /// Total mass `M`.
    mass: f64,
    /// The field of the largest energy term.
    energy_field: String,
    /// The largest `R |U|` of a point mass (`lambda = 0`: not bounded by the energy).
    point_spin: f64,
}

/// `|u|^2`, `|U|^2`, `R |U|`, `lambda |U|^2` and the energy of one ball (or a bound for the
/// random ones); errors name `velocity` or `spin` through the two fields given.
fn ball_energy(
    c: &Constants,
    u: &[f64],
    moving: bool,
    spin: &[f64],
    spinning: bool,
    fields: [&str; 2],
) -> Result<f64, String> {
    let u2: f64 = u.iter().map(|x| x * x).sum();
    if !u2.is_finite() || (moving && !u2.is_normal()) {
        return Err(format!(
            "{}: |u|^2 = {u2:e} in f64: a speed squared must be a normal f64, 2^-511 <= |u| \
             < 2^511 (about 1.5e-154 to 6.7e153)",
            fields[0]
        ));
    }
    let s2: f64 = spin.iter().map(|x| x * x).sum();
    let contact_speed = c.r * s2.sqrt();
    let weighted = 2.0 * c.lambda * s2;
    let spin_fine =
        s2.is_normal() && contact_speed.is_finite() && (c.lambda == 0.0 || weighted.is_normal());
    if !s2.is_finite() || (spinning && !spin_fine) {
        return Err(format!(
            "{}: |U|^2 = {s2:e}, R |U| = {contact_speed:e}, 2 lambda |U|^2 = {weighted:e} in \
             f64: each must be a normal f64 (the spin enters the energy and the contact-point \
             speed)",
            fields[1]
        ));
    }
    let e = 0.5 * c.m * (u2 + weighted);
    if !e.is_finite() || (e != 0.0 && !e.is_normal()) {
        let field = if u2 >= weighted { fields[0] } else { fields[1] };
        return Err(format!(
            "{field}: the kinetic energy 1/2 m (|u|^2 + 2 lambda |U|^2) = {e:e} in f64 must be \
             a normal f64"
        ));
    }
    Ok(e)
}

fn start_bounds(
    scene: &Scene,
    sp: &[Constants],
    per_species: &[usize],
    n: usize,
    s_len: usize,
) -> Result<Start, String> {
    let mut start = Start {
        energy: 0.0,
        mass: 0.0,
        energy_field: String::new(),
        point_spin: 0.0,
    };
    let mut largest = -1.0;
    let mut add = |start: &mut Start, e: f64, count: usize, m: f64, field: String| {
        start.energy += e * count as f64;
        start.mass += m * count as f64;
        if e > largest {
            largest = e;
            start.energy_field = field;
        }
    };
    for (i, b) in scene.balls.iter().enumerate() {
        let c = &sp[b.species];
        let u: Vec<f64> = b.velocity.iter().map(f).collect();
        let spin: Vec<f64> = b.spin.iter().map(f).collect();
        let moving = b.velocity.iter().any(|x| !x.is_zero());
        let spinning = b.spin.iter().any(|x| !x.is_zero());
        let (vf, sf) = (
            format!("ball[{i}].velocity"),
            format!("ball[{i}].angular_velocity"),
        );
        let e = ball_energy(c, &u, moving, &spin, spinning, [&vf, &sf])?;
        if c.g == 0.0 {
            start.point_spin = start
                .point_spin
                .max(c.r * spin.iter().map(|x| x * x).sum::<f64>().sqrt());
        }
        let field = if moving || !spinning { vf } else { sf };
        add(&mut start, e, 1, c.m, field);
    }
    let (speed, spin) = (&scene.random.speed, &scene.random.spin);
    for (k, s) in scene.species.iter().enumerate() {
        if s.count == 0 {
            continue;
        }
        let c = &sp[k];
        let u = vec![f(speed); n];
        let w = vec![f(spin); s_len];
        let fields = ["random.speed", "random.spin"];
        let e = ball_energy(c, &u, speed.is_positive(), &w, spin.is_positive(), fields)?;
        let field = if speed.is_positive() || !spin.is_positive() {
            fields[0]
        } else {
            fields[1]
        };
        if c.g == 0.0 {
            start.point_spin = start.point_spin.max(c.r * f(spin) * (s_len as f64).sqrt());
        }
        add(&mut start, e, s.count, c.m, field.to_string());
    }
    let total_field = || {
        (0..per_species.len())
            .rev()
            .find(|&k| scene.species[k].count > 0)
            .map_or_else(
                || start.energy_field.clone(),
                |k| format!("species[{k}].count"),
            )
    };
    if !start.mass.is_finite() || !start.energy.is_finite() {
        return Err(format!(
            "{}: the total mass M = {:e} and the start energy (at most {:e}) must be finite \
             f64 numbers",
            total_field(),
            start.mass,
            start.energy
        ));
    }
    if start.energy == 0.0 {
        let field = if per_species.iter().sum::<usize>() > scene.balls.len() {
            "random.speed".to_string()
        } else {
            "ball[0].velocity".to_string()
        };
        return Err(format!(
            "{field}: nothing moves (every velocity and weighted spin is 0): the start energy \
             is 0, so no contact can happen and the energy drift (E - E_0) / E_0 is undefined"
        ));
    }
    Ok(start)
}

/// The checks after placement: the start energy `E_0` in f64, the discriminant at the
/// contact scale `(R_min v)^2` and the box-crossing time `B / v`, `v = sqrt(2 E_0 / M)`.
pub fn check_start<const N: usize, const S: usize>(
    scales: &Scales,
    setup: &Setup<N, S>,
) -> Result<(), String> {
    let e0 = Observables::of(
        setup
            .bodies
            .iter()
            .map(|b| (&setup.species[b.species], &b.position, &b.state)),
    )
    .energy;
    if !e0.is_normal() {
        return Err(format!(
            "{}: the start energy is {e0:e} in f64: it must be a normal f64",
            scales.energy_field
        ));
    }
    let v = (2.0 * e0 / scales.mass).sqrt();
    let contact = scales.radius_min * v;
    let crossing = scales.box_scale / v;
    if !(contact * contact).is_normal() || !crossing.is_finite() {
        let field = if !crossing.is_finite() {
            farther(scales.box_scale, &scales.box_field, v, &scales.energy_field)
        } else {
            farther(
                scales.radius_min,
                &scales.radius_field,
                v,
                &scales.energy_field,
            )
        };
        return Err(format!(
            "{field}: with the typical speed v = sqrt(2 E_0 / M) = {v:e}, the contact-time \
             discriminant at the contact scale, (R_min v)^2 = {:e}, must be a normal f64 and \
             the time to cross the box, B / v = {crossing:e}, finite",
            contact * contact
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::show;
    use num_bigint::BigInt;
    use num_rational::BigRational;

    /// Beyond the normal range the magnitude is written to three digits (a review saw
    /// `5e-324` written as `about 1e-323`).
    #[test]
    fn values_beyond_the_normal_range_are_shown_to_three_digits() {
        let exact = |x: f64| BigRational::from_float(x).unwrap();
        assert_eq!(show(&exact(5e-324)), "about 4.94e-324");
        assert_eq!(show(&exact(-1e-310)), "about -1.00e-310");
        let big = BigRational::from_integer(BigInt::from(10).pow(400) * 3);
        assert_eq!(show(&big), "about 3.00e400");
        let tiny = BigRational::new(BigInt::from(7), BigInt::from(10).pow(500));
        assert_eq!(show(&tiny), "about 7.00e-500");
        assert_eq!(show(&exact(0.25)), "2.5e-1");
        // A mantissa that rounds up to 10 moves to the next decade.
        let near = BigRational::new(BigInt::from(99999), BigInt::from(10).pow(405));
        assert_eq!(show(&near), "about 1.00e-400");
    }
}
