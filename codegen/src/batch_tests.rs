//! The batch kernels (`batch.rs`): per-contact and per-call operations partition the scalar
//! kernel's, every output lane is stored once and right after its last use, and the law and
//! the shared parameters are read where their mode says.

use super::*;
use crate::schedule::OpCount;
use crate::DIMS;
use std::collections::HashMap;

/// How many lane stores one block writes: every output component of every lane.
fn stores_per_lane(dim: usize, variant: Variant) -> usize {
    let bodies = match variant {
        Variant::Free => 2,
        Variant::Fixed => 1,
    };
    bodies * (dim + dim * (dim - 1) / 2)
}

fn add(a: OpCount, b: OpCount) -> OpCount {
    OpCount {
        add: a.add + b.add,
        mul: a.mul + b.mul,
        div: a.div + b.div,
        neg: a.neg + b.neg,
        fma: a.fma + b.fma,
        sqrt: a.sqrt + b.sqrt,
        select: a.select + b.select,
    }
}

#[test]
fn per_contact_and_per_call_ops_partition_the_scalar_kernel() {
    for dim in DIMS {
        let scalar: HashMap<Variant, OpCount> = crate::generate(dim, "crate")
            .kernels
            .into_iter()
            .filter(|k| k.arith == crate::Arith::Plain)
            .map(|k| (k.variant, k.ops))
            .collect();
        for k in generate(dim, "crate").kernels {
            let ops = match k.law {
                model::Law::Rough => emit::emit_body(&model::build_rough(dim, k.variant)).ops,
                model::Law::Walton => {
                    emit::emit_body(&crate::walton::build_walton(dim, k.variant)).ops
                }
                model::Law::NoSlip => scalar[&k.variant],
            };
            assert_eq!(
                add(k.per_contact, k.per_batch),
                ops,
                "n = {dim}, {:?} {:?} {:?}",
                k.law,
                k.variant,
                k.params
            );
            // The rough law's h_n = (1 + e)/2 and h_t = (1 + beta)/2 are computed once
            // per call in both modes.
            let law = match k.law {
                model::Law::Rough => OpCount {
                    add: 2,
                    mul: 2,
                    ..OpCount::default()
                },
                // h_n, h_0 and the Coulomb side's mu h_n: law-only nodes.
                model::Law::Walton => k.per_batch,
                model::Law::NoSlip => OpCount::default(),
            };
            match k.params {
                Params::PerContact => assert_eq!(k.per_batch, law),
                // The law per contact: nothing is left for the call.
                Params::Each => assert_eq!(k.per_batch, OpCount::default(), "{k:?}"),
                // D, g_1 g_2 / D and the rho_i leave the lane loop; of `fixed`,
                // g_2 / (1 + g_2) does, and the divisions of y_k = .. / R_2 stay in it
                // (`crate::unbiased`).
                Params::Shared => {
                    let hoisted = if k.variant == Variant::Free { 2 } else { 1 };
                    assert!(k.per_batch.div >= hoisted, "{k:?}");
                }
            }
        }
    }
}

#[test]
fn every_output_lane_is_stored_once() {
    for dim in DIMS {
        let source = generate(dim, "crate").source;
        let file = syn::parse_file(&source).expect("generated source parses");
        assert_eq!(file.items.len(), 2 + 16, "two use items, sixteen kernels");
        for (law, v) in [model::Law::NoSlip, model::Law::Rough, model::Law::Walton]
            .into_iter()
            .flat_map(|l| Variant::ALL.map(|v| (l, v)))
        {
            let each = (law != model::Law::NoSlip).then_some(Params::Each);
            for p in Params::ALL.into_iter().chain(each) {
                let name = p.function_name_of(law, v);
                let body = source
                    .split(&format!("pub fn {name}<"))
                    .nth(1)
                    .expect("kernel emitted");
                let body = body.split("\npub fn ").next().unwrap_or(body);
                let stores = body.matches("[l] = ").count();
                assert_eq!(stores, stores_per_lane(dim, v), "n = {dim}, {name}");
            }
        }
    }
}

#[test]
fn outputs_are_stored_right_after_their_last_use() {
    // In every lane loop, a stored value is read by no later line, and the nearest line
    // before its store (other than stores) defines or reads it.
    let is_store = |l: &str| l.contains("[l] = ");
    for dim in DIMS {
        let source = generate(dim, "crate").source;
        for body in source.split("for l in group * W..group * W + W {").skip(1) {
            let lines: Vec<&str> = body.lines().map(str::trim).collect();
            let end = lines
                .iter()
                .position(|l| *l == "}")
                .expect("end of the lane loop");
            let lines = &lines[..end];
            for (i, line) in lines.iter().enumerate().filter(|(_, l)| is_store(l)) {
                let value = line.split(" = ").nth(1).unwrap().trim_end_matches(';');
                let value = value.trim_end_matches(".clone()");
                if !value.starts_with("tmp") && !value.chars().any(|c| c == '_') {
                    continue; // a constant or an input
                }
                let reads = |l: &str| {
                    l.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .any(|w| w == value)
                };
                assert!(
                    !lines[i + 1..].iter().any(|l| !is_store(l) && reads(l)),
                    "n = {dim}: {value} is read after its store"
                );
                let before = lines[..i].iter().rev().find(|l| !is_store(l));
                assert!(
                    before.is_some_and(|l| reads(l)),
                    "n = {dim}: {line} is not right after the last use of {value}"
                );
            }
        }
    }
}

/// The rough kernels' law is a parameter of the call: `h_n`, `h_t` leave the lane loop
/// in both modes, and in the per-contact mode nothing else does.
#[test]
fn the_rough_law_leaves_the_lane_loop() {
    let source = generate(3, "crate").source;
    for name in ["rough_free", "rough_fixed", "rough_free_shared"] {
        let body = source.split(&format!("pub fn {name}<")).nth(1).unwrap();
        let (before_loop, in_loop) = body.split_once("for k in 0..").unwrap();
        let in_loop = in_loop.split("\npub fn ").next().unwrap();
        assert!(before_loop.contains("law: &Restitution<T>"), "{name}");
        assert!(before_loop.contains("let h_n: T ="), "{name}");
        assert!(before_loop.contains("let h_t: T ="), "{name}");
        assert!(
            !in_loop.contains("law."),
            "{name}: the law is read per lane"
        );
    }
}

/// With a law per contact (`_each`), every law field is read per lane from the block's
/// law lanes, and `h_n` is computed in the lane loop.
#[test]
fn the_law_per_contact_is_read_in_the_lane_loop() {
    let source = generate(3, "crate").source;
    for (name, fields) in [
        ("rough_free_each", &["law.e[l]", "law.beta[l]"][..]),
        ("rough_fixed_each", &["law.e[l]", "law.beta[l]"]),
        (
            "walton_free_each",
            &["law.e[l]", "law.mu[l]", "law.beta0[l]"],
        ),
        (
            "walton_fixed_each",
            &["law.e[l]", "law.mu[l]", "law.beta0[l]"],
        ),
    ] {
        let body = source.split(&format!("pub fn {name}<")).nth(1).unwrap();
        let (before_loop, in_loop) = body.split_once("for k in 0..").unwrap();
        let in_loop = in_loop.split("\npub fn ").next().unwrap();
        assert!(before_loop.contains("WithLaw<"), "{name}");
        assert!(
            !before_loop.contains("law."),
            "{name}: nothing of the law per call"
        );
        for f in fields {
            assert!(in_loop.contains(f), "{name}: {f} per lane");
        }
        assert!(in_loop.contains("let h_n: T ="), "{name}");
    }
}

#[test]
fn shared_parameters_leave_the_lane_loop() {
    let source = generate(3, "crate").source;
    let shared = source.split("pub fn free_shared<").nth(1).unwrap();
    let (before_loop, in_loop) = shared.split_once("for k in 0..").unwrap();
    let in_loop = in_loop.split("\npub fn ").next().unwrap();
    assert!(before_loop.contains("let d: T ="), "D is computed once");
    assert!(before_loop.contains("let rho1: T ="));
    assert!(
        !in_loop.contains("ball1."),
        "no ball field is read per lane"
    );
}
