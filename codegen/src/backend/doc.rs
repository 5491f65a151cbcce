//! The comment above a generic, rough-ball or Walton kernel: what it computes and writes,
//! the closed form, the parameters and the storage order, the preconditions the checked Rust
//! `collide` validates, and the op counts.

use crate::arith::Arith;
use crate::model::{skew_pairs, Law, Variant};
use crate::schedule::OpCount;

/// The comment of a generic kernel: the formula, the parameters, the preconditions, the
/// storage order and the op counts.
pub(super) fn generic_doc(
    n: usize,
    (law, variant): (Law, Variant),
    arith: Arith,
    ops: OpCount,
    terms: usize,
) -> Vec<String> {
    let mut doc = match (law, variant) {
        (Law::NoSlip, Variant::Free) => vec![
            format!("No-slip collision of two free balls in R^{n}: writes body 1 to out1, body 2 to out2."),
            String::new(),
        ],
        (Law::NoSlip, Variant::Fixed) => vec![
            format!("No-slip collision in R^{n} of a free ball (body 2) with an immovable one (body 1):"),
            "writes body 2 to out2 (body 1 is unchanged). Reads radius1 and ball2's radius, gamma2.".into(),
            String::new(),
        ],
        (Law::Rough, Variant::Free) => vec![
            format!("Rough-ball collision of two free balls in R^{n}, law = {{e, beta}} (docs/derivation.md §15):"),
            "writes body 1 to out1, body 2 to out2. (e, beta) = (1, 1) is the no-slip kernel, (1, -1) the smooth map.".into(),
            String::new(),
        ],
        (Law::Rough, Variant::Fixed) => vec![
            format!("Rough-ball collision in R^{n} of a free ball (body 2) with an immovable one (body 1),"),
            "law = {e, beta}: writes body 2 to out2 (body 1 is unchanged).".into(),
            String::new(),
        ],
        (Law::Walton, Variant::Free) => vec![
            format!("Walton-law collision of two free balls in R^{n}, law = {{e, mu, beta0}} (docs/derivation.md §15.1):"),
            "writes body 1 to out1, body 2 to out2. beta = min(beta0, beta_C); while sticking the rough kernel at beta0.".into(),
            String::new(),
        ],
        (Law::Walton, Variant::Fixed) => vec![
            format!("Walton-law collision in R^{n} of a free ball (body 2) with an immovable one (body 1),"),
            "law = {e, mu, beta0}: writes body 2 to out2 (body 1 is unchanged).".into(),
            String::new(),
        ],
    };
    doc.extend(law.closed_form(variant).lines().map(|l| format!("    {l}")));
    doc.push(String::new());
    doc.push("w_i = inv_mass, g_i = gamma2 = 2 lambda_i / R_i^2 in [0, 2/n]; ball = {inv_mass, radius, gamma2}.".into());
    doc.push(format!(
        "state = spin U_ij (i < j) in the order {:?}, then velocity u_0..u_{}.",
        skew_pairs(n),
        n - 1
    ));
    doc.push(
        "Preconditions (what the checked Rust `collide` validates): every input finite, |nu| = 1,"
            .into(),
    );
    doc.push(
        "0 <= gamma2 <= 2/n, radius > 0, inv_mass >= 0, (u_2 - u_1) . nu <= 0 (approach or graze);"
            .into(),
    );
    if law == Law::Rough {
        doc.push("0 <= e <= 1, -1 <= beta <= 1 (collision_core::Restitution::new);".into());
    }
    if law == Law::Walton {
        doc.push("0 <= e <= 1, mu >= 0, -1 <= beta0 <= 1 (collision_core::Walton::new);".into());
    }
    if variant == Variant::Free {
        doc.push(
            "w_1 + w_2 > 0 and D > 0 (not both immovable, not both movable point masses).".into(),
        );
    } else {
        doc.push("its denominator 1 + g_2 is at least 1.".into());
    }
    if arith == Arith::Fma {
        doc.push("FMA form: every single-use product fused into the addition that consumes it (one rounding).".into());
    }
    doc.push(format!("Ops: {ops}; {terms} intermediate terms."));
    doc
}
