//! A direct simulation Monte Carlo (DSMC) of the homogeneous Boltzmann equation of rough
//! balls, written without the engine (its own random numbers, its own collision rule with the
//! angular velocity as a vector in 3D and the out-of-plane component in 2D, no positions): the
//! kinetic equation's homogeneous cooling state, which `boltzmann.rs` checks and
//! `cooling_state.rs` holds the engine to.

/// SplitMix64, as in `cli/tests/c_recipe.rs` and `codegen/src/bound/tests.rs`: the project's
/// ChaCha8 stream (`collision_core::rng`) lives in a crate the test profile leaves unoptimised,
/// and with it this file's default test takes 64 s instead of 3.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`.
    fn uniform(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Standard normal (Box-Muller).
    fn normal(&mut self) -> f64 {
        let u = 1.0 - self.uniform();
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * self.uniform()).cos()
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `T_rot / T_tr` of `balls` particles (`m = R = 1`, `I = k`, `k = 2 / (n + 2)`: uniform balls)
/// in R^n, `n = 2, 3`, started Maxwellian at equal temperatures, sampled every half
/// collision per particle from `skip` to `skip + window` collisions per particle: returns the
/// mean of the samples' `T_rot / T_tr` and `<T_rot / E> / <T_tr / E>`, `E = n T_tr + S T_rot`
/// (the ratio of the means with the cooling scaled out, as the engine's `Run::ratio_of_means`
/// in `tests/common/cooling.rs`), and the samples' mean fourth cumulant `a_2 = n / (n + 2)
/// <|c|^4> / <|c|^2>^2 - 1` of the translational velocities `c` about their mean.
///
/// Each round pairs all particles at random and draws each pair's unit vector `s` (from
/// particle 1 to 2) uniformly; the pair collides with probability `max(0, w . s) / c`, `w =
/// v_1 - v_2`, `c` above every `w . s` that occurs (7 sqrt(2 T_tr): a Gaussian's 7 sigma), so
/// the collisions sample the hard-ball kernel `max(0, w . s)` of the homogeneous Boltzmann
/// equation; time enters only through the number of collisions. The contact points' relative
/// velocity is `g = w - s x (omega_1 + omega_2)`; with `g_n = (w . s) s`, `g_t = g - g_n`,
/// `eta_n = (1 + e) / 2` and `eta = k (1 + beta) / (2 (1 + k))`, the collision adds `-Dv`
/// to `v_1`, `+Dv` to `v_2` and `s x Dv / k` to both spins, `Dv = eta_n g_n + eta g_t`:
/// `g_n -> -e g_n`, `g_t -> -beta g_t`, momentum and angular momentum about the contact
/// point conserved. Each round starts by taking out the mean velocity and scaling all
/// velocities and spins to `T_tr = 1` (the kernel is homogeneous: the collision sequence
/// only speeds up or slows down).
pub fn dsmc(
    dim: usize,
    e: f64,
    beta: f64,
    balls: usize,
    seed: u64,
    skip: f64,
    window: f64,
) -> (f64, f64, f64) {
    let k = 2.0 / (dim as f64 + 2.0);
    let (eta_n, eta) = ((1.0 + e) / 2.0, k * (1.0 + beta) / (2.0 * (1.0 + k)));
    let mut rng = Rng(0x5EED_0000 + seed);
    let mut v = vec![[0.0f64; 3]; balls];
    let mut w = vec![[0.0f64; 3]; balls];
    let spins = if dim == 3 { 0..3 } else { 2..3 };
    for (vi, wi) in v.iter_mut().zip(&mut w) {
        for x in &mut vi[..dim] {
            *x = rng.normal();
        }
        for c in spins.clone() {
            wi[c] = rng.normal() / k.sqrt();
        }
    }
    let temperatures = |v: &[[f64; 3]], w: &[[f64; 3]]| {
        let n = balls as f64;
        let mean: [f64; 3] = std::array::from_fn(|c| v.iter().map(|x| x[c]).sum::<f64>() / n);
        let tr = v
            .iter()
            .map(|x| (0..dim).map(|c| (x[c] - mean[c]).powi(2)).sum::<f64>())
            .sum::<f64>()
            / (dim as f64 * (n - 1.0));
        let rot = w
            .iter()
            .map(|x| k * x.iter().map(|y| y * y).sum::<f64>())
            .sum::<f64>()
            / (spins.len() as f64 * n);
        (tr, rot)
    };
    let mut order: Vec<usize> = (0..balls).collect();
    let kurtosis = |v: &[[f64; 3]]| {
        let n = balls as f64;
        let mean: [f64; 3] = std::array::from_fn(|c| v.iter().map(|x| x[c]).sum::<f64>() / n);
        let (mut m2, mut m4) = (0.0, 0.0);
        for x in v {
            let c2 = (0..dim).map(|c| (x[c] - mean[c]).powi(2)).sum::<f64>();
            m2 += c2;
            m4 += c2 * c2;
        }
        let d = dim as f64;
        d / (d + 2.0) * (m4 / n) / (m2 / n).powi(2) - 1.0
    };
    let (mut collisions, mut next, mut sum, mut samples) = (0u64, 0.0, 0.0, 0usize);
    let mut a2 = 0.0;
    let mut scaled = [0.0f64; 2];
    let c_max = 7.0 * 2f64.sqrt();
    loop {
        // Momentum is conserved: the mean velocity would grow against the thermal ones under
        // the scaling, so it is taken out first.
        let n = balls as f64;
        let mean: [f64; 3] = std::array::from_fn(|c| v.iter().map(|x| x[c]).sum::<f64>() / n);
        let scale = 1.0 / temperatures(&v, &w).0.sqrt();
        for x in &mut v {
            *x = std::array::from_fn(|c| (x[c] - mean[c]) * scale);
        }
        for x in &mut w {
            *x = x.map(|y| y * scale);
        }
        for i in (1..balls).rev() {
            order.swap(i, (rng.next() % (i as u64 + 1)) as usize);
        }
        for pair in order.chunks_exact(2) {
            let (a, b) = (pair[0], pair[1]);
            let mut s = [0.0; 3];
            let length = loop {
                for x in &mut s[..dim] {
                    *x = rng.normal();
                }
                let l = s.iter().map(|x| x * x).sum::<f64>().sqrt();
                if l > 1e-12 {
                    break l;
                }
            };
            s = s.map(|x| x / length);
            let rel: [f64; 3] = std::array::from_fn(|c| v[a][c] - v[b][c]);
            let gn = rel[0] * s[0] + rel[1] * s[1] + rel[2] * s[2];
            if gn <= 0.0 || rng.uniform() * c_max > gn {
                continue;
            }
            let sw = cross(s, std::array::from_fn(|c| w[a][c] + w[b][c]));
            let gt: [f64; 3] = std::array::from_fn(|c| rel[c] - sw[c] - gn * s[c]);
            let dv: [f64; 3] = std::array::from_fn(|c| eta_n * gn * s[c] + eta * gt[c]);
            let dw = cross(s, dv).map(|x| -x / k);
            for c in 0..3 {
                v[a][c] -= dv[c];
                v[b][c] += dv[c];
                w[a][c] += dw[c];
                w[b][c] += dw[c];
            }
            collisions += 1;
        }
        let tau = 2.0 * collisions as f64 / balls as f64;
        if tau >= next {
            next = tau + 0.5;
            if tau >= skip {
                let (tr, rot) = temperatures(&v, &w);
                sum += rot / tr;
                a2 += kurtosis(&v);
                samples += 1;
                let energy = dim as f64 * tr + spins.len() as f64 * rot;
                scaled[0] += tr / energy;
                scaled[1] += rot / energy;
            }
        }
        if tau >= skip + window {
            let k = samples as f64;
            return (sum / k, scaled[1] / scaled[0], a2 / k);
        }
    }
}
