//! The units of each kernel family, named and with their parameters in the ABI's order: the
//! generic kernels (as the Rust module `kernels::dN`), the rough-ball and Walton kernels (as
//! `dN::rough`, `dN::walton`: a `law` array after the balls) and the kernels specialised to a
//! scene's pairs.

use super::doc::generic_doc;
use super::unit::{Param, Unit};
use crate::arith::Arith;
use crate::model::{names, skew_pairs, Law, Variant};
use crate::program::Program;
use noslip_scene::{Pair, PairSet};

/// The kernel inputs of one body's `{inv_mass, radius, gamma2}`.
fn ball_elems(body: usize) -> Vec<String> {
    vec![
        names::inv_mass(body),
        names::radius(body),
        names::gamma2(body),
    ]
}

/// The kernel inputs of one body's state: spin, then velocity.
fn state_elems(n: usize, body: usize) -> Vec<String> {
    skew_pairs(n)
        .into_iter()
        .map(|(i, j)| names::spin(body, i, j))
        .chain((0..n).map(|k| names::velocity(body, k)))
        .collect()
}

fn nu_elems(n: usize) -> Vec<String> {
    (0..n).map(names::nu).collect()
}

/// The generic kernels of dimension `n`: each variant in each arithmetic, as in the Rust
/// module `kernels::dN` (`free`, `fixed`, `free_fma`, `fixed_fma`).
pub fn generic_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::NoSlip)
}

/// The rough-ball kernels of dimension `n` (`noslip_dN_rough_free`, ...), as in the Rust
/// module `kernels::dN::rough`: the generic kernels' parameters with `law = {e, beta}` after
/// the balls.
pub fn rough_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::Rough)
}

/// The Walton kernels of dimension `n` (`noslip_dN_walton_free`, ...), as in the Rust
/// module `kernels::dN::walton`: the generic kernels' parameters with
/// `law = {e, mu, beta0}` after the balls.
pub fn walton_units(n: usize) -> Vec<Unit> {
    law_units(n, Law::Walton)
}

fn law_units(n: usize, law: Law) -> Vec<Unit> {
    let law_param = || {
        let fields = match law {
            Law::Walton => vec![
                names::restitution_e(),
                names::friction_mu(),
                names::walton_beta0(),
            ],
            Law::NoSlip | Law::Rough => {
                vec![names::restitution_e(), names::restitution_beta()]
            }
        };
        Param::Array("law", fields)
    };
    Arith::ALL
        .iter()
        .flat_map(|&arith| {
            Variant::ALL.iter().map(move |&variant| {
                let program = Program::lower(&crate::laws::build_law(n, variant, law), arith);
                let mut params = match variant {
                    Variant::Free => vec![
                        Param::Array("nu", nu_elems(n)),
                        Param::Array("ball1", ball_elems(1)),
                        Param::Array("ball2", ball_elems(2)),
                        Param::Array("state1", state_elems(n, 1)),
                        Param::Array("state2", state_elems(n, 2)),
                        Param::Out("out1", 1),
                        Param::Out("out2", 2),
                    ],
                    Variant::Fixed => vec![
                        Param::Array("nu", nu_elems(n)),
                        Param::Scalar(names::radius(1)),
                        Param::Array("ball2", ball_elems(2)),
                        Param::Array("state1", state_elems(n, 1)),
                        Param::Array("state2", state_elems(n, 2)),
                        Param::Out("out2", 2),
                    ],
                };
                let prefix = match law {
                    Law::NoSlip => "",
                    Law::Rough => {
                        params.insert(3, law_param());
                        "rough_"
                    }
                    Law::Walton => {
                        params.insert(3, law_param());
                        "walton_"
                    }
                };
                let doc = generic_doc(n, (law, variant), arith, program.ops, program.terms());
                Unit {
                    name: format!("noslip_d{n}_{prefix}{}", arith.function_name(variant)),
                    program,
                    params,
                    doc,
                }
            })
        })
        .collect()
}

/// The kernels specialised to a scene's pairs ([`crate::specialise`]), plain arithmetic as
/// in Rust: `noslip_{scene}_{pair}`, e.g. `noslip_gas2d_ball_ball_0_0`.
pub fn scene_units(set: &PairSet) -> Vec<Unit> {
    let n = set.dim;
    set.all()
        .into_iter()
        .map(|pair| {
            let kernel = crate::specialise::build(set, pair);
            let program = Program::lower(&kernel, Arith::Plain);
            let params = match pair {
                Pair::BallBall(..) => vec![
                    Param::Array("nu", nu_elems(n)),
                    Param::Array("state1", state_elems(n, 1)),
                    Param::Array("state2", state_elems(n, 2)),
                    Param::Out("out1", 1),
                    Param::Out("out2", 2),
                ],
                Pair::BallWall(..) => vec![
                    Param::Array("state", state_elems(n, 2)),
                    Param::Out("out", 2),
                ],
                Pair::BallObstacle(..) => vec![
                    Param::Array("nu", nu_elems(n)),
                    Param::Array("state", state_elems(n, 2)),
                    Param::Out("out", 2),
                ],
            };
            let mut doc = vec![format!(
                "Scene `{}`, {} kernel `{}` (the `{}` {} map with the species constants and the law folded in).",
                set.name,
                pair.kind(),
                pair.fn_name(),
                crate::specialise::variant(pair).name(),
                crate::specialise::law_name(set, pair)
            )];
            doc.push(format!(
                "Ops: {}; {} intermediate terms.",
                program.ops,
                program.terms()
            ));
            Unit {
                name: format!("noslip_{}_{}", set.name, pair.fn_name()),
                program,
                params,
                doc,
            }
        })
        .collect()
}
