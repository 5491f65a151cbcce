//! Golden-file tests of the generator: the emitted text of the n = 2 kernels and the op
//! counts of every kernel are checked in; a change to the generator shows up as a diff.
//! Regenerate with `UPDATE_GOLDEN=1 cargo test -p noslip-codegen --test golden`.

use noslip_codegen::{
    generate, generate_rough, generate_walton, straight_line, Arith, Variant, DIMS,
};
use noslip_verify::diff::unified;
use std::path::PathBuf;

fn golden(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

fn compare(name: &str, actual: &str) {
    let path = golden(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e}; run with UPDATE_GOLDEN=1", path.display()));
    let golden_name = format!("golden {name}");
    let now_name = format!("generated {name}");
    if let Some(diff) = unified(&golden_name, &now_name, &expected, actual, 3) {
        panic!(
            "{name} differs from the golden copy:\n{diff}\n\
             If the change is intended, run with UPDATE_GOLDEN=1 and review the diff."
        );
    }
}

#[test]
fn emitted_text_of_the_2d_kernels() {
    compare("kernels_2.rs", &generate(2, "crate").source);
}

#[test]
fn op_counts_of_every_kernel() {
    let mut table = String::from("# dim variant: ops; intermediate terms\n");
    for dim in DIMS {
        for k in generate(dim, "crate").kernels {
            table.push_str(&format!(
                "{dim} {}: {}; {} terms\n",
                k.name(),
                k.ops,
                k.terms
            ));
        }
    }
    compare("op_counts.txt", &table);
}

#[test]
fn divisions_do_not_grow_with_the_dimension() {
    // 1/(w_1 + w_2), g_1 g_2 / D and one per angular update (free); the fixed variant keeps
    // p = g_2 / (1 + g_2) and divides each component of y = 2 (1 - p) t / R_2 by R_2
    // (`noslip_codegen::unbiased`): 1 + n.
    for dim in DIMS {
        for k in generate(dim, "crate").kernels {
            let expected = match k.variant {
                Variant::Free => 4,
                Variant::Fixed => 1 + dim,
            };
            assert_eq!(k.ops.div, expected, "n = {dim}, {:?}", k.variant);
        }
    }
}

#[test]
fn every_generated_kernel_is_straight_line() {
    for dim in DIMS {
        let module = generate(dim, "crate");
        let file = syn::parse_file(&module.source).expect("generated source parses");
        let fns = file
            .items
            .iter()
            .filter(|i| matches!(i, syn::Item::Fn(_)))
            .count();
        assert_eq!(fns, Variant::ALL.len() * Arith::ALL.len());
        assert_eq!(straight_line::check(&file), vec![], "n = {dim}");
        assert!(module.source.starts_with("// @generated"));
    }
}

#[test]
fn emitted_text_of_the_2d_batch_kernels() {
    compare(
        "batch_2.rs",
        &noslip_codegen::batch::generate(2, "crate").source,
    );
}

/// docs/benchmarks.md quotes the free kernels' op counts next to its timings ("free op counts
/// a, b, c, d, e for n = 2..6"); they must be the generator's.
#[test]
fn benchmarks_page_quotes_the_generated_op_counts() {
    let page = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/benchmarks.md"),
    )
    .unwrap();
    let start = page.find("free op counts ").expect("the sentence") + "free op counts ".len();
    let end = start
        + page[start..]
            .find(" for n = 2..6")
            .expect("the sentence's end");
    let quoted: Vec<usize> = page[start..end]
        .split(", ")
        .map(|x| x.trim().parse().expect("a count"))
        .collect();
    let generated: Vec<usize> = DIMS
        .map(|dim| {
            generate(dim, "crate")
                .kernels
                .iter()
                .find(|k| k.variant == Variant::Free && k.arith == Arith::Plain)
                .expect("the free kernel")
                .ops
                .total()
        })
        .collect();
    assert_eq!(quoted, generated, "docs/benchmarks.md's op counts");
}

#[test]
fn emitted_text_of_the_2d_rough_kernels() {
    compare("rough_2.rs", &generate_rough(2, "crate").source);
}

/// The rough-ball kernels' costs: the no-slip kernel's, plus `h_n`, `h_t` (one addition and
/// one multiplication each) and the scaled `P_n`, `P_t` and `rho_i` (one multiplication
/// each), checked in a table of their own.
#[test]
fn op_counts_of_every_rough_kernel() {
    let mut table = String::from("# dim variant: ops; intermediate terms\n");
    for dim in DIMS {
        for k in generate_rough(dim, "crate").kernels {
            table.push_str(&format!(
                "{dim} rough::{}: {}; {} terms\n",
                k.name(),
                k.ops,
                k.terms
            ));
        }
    }
    compare("rough_op_counts.txt", &table);
}

#[test]
fn rough_kernels_cost_the_no_slip_ones_plus_the_scaling() {
    for dim in DIMS {
        let plain = generate(dim, "crate").kernels;
        let rough = generate_rough(dim, "crate").kernels;
        for (p, r) in plain.iter().zip(&rough) {
            assert_eq!((p.variant, p.arith), (r.variant, r.arith));
            if p.arith == Arith::Plain {
                // h_n, h_t: 2 add + 2 mul; P_n, P_t: 2 mul; rho_1, rho_2 (free): 2 mul, or
                // the head and tail of `fixed`'s unbiased 2 (1 - p): 2 mul. `fixed` also
                // computes `nu_k (h_n dn)`, n products, where the no-slip kernel reuses the
                // slip's `nu_k dn`.
                let extra = match p.variant {
                    Variant::Free => 2,
                    Variant::Fixed => 2 + dim,
                };
                assert_eq!(r.ops.add, p.ops.add + 2, "n = {dim}, {:?}", p.variant);
                assert_eq!(
                    r.ops.mul,
                    p.ops.mul + 4 + extra,
                    "n = {dim}, {:?}",
                    p.variant
                );
                assert_eq!(r.ops.div, p.ops.div, "n = {dim}, {:?}", p.variant);
            }
        }
        let file = syn::parse_file(&generate_rough(dim, "crate").source).expect("parses");
        assert_eq!(straight_line::check(&file), vec![], "n = {dim}");
    }
}

#[test]
fn emitted_text_of_the_2d_walton_kernels() {
    compare("walton_2.rs", &generate_walton(2, "crate").source);
}

/// The Walton kernels' costs, checked in a table of their own; beside the rough kernel's,
/// each has exactly one square root and two selects (`rho`'s numerator and denominator),
/// the same divisions plus `rho`, and is straight-line.
#[test]
fn op_counts_of_every_walton_kernel() {
    let mut table = String::from("# dim variant: ops; intermediate terms\n");
    for dim in DIMS {
        let rough = generate_rough(dim, "crate").kernels;
        let walton = generate_walton(dim, "crate");
        for (r, k) in rough.iter().zip(&walton.kernels) {
            assert_eq!(
                (k.ops.sqrt, k.ops.select),
                (1, 2),
                "n = {dim}, {}",
                k.name()
            );
            assert_eq!(k.ops.div, r.ops.div + 1, "n = {dim}, {}", k.name());
            if k.arith == Arith::Plain {
                // |t|^2: n products, n - 1 sums; the two sides, rho and h_t: 10 products
                // (9 in `fixed`, where its constants fold). docs/kernels.md quotes these.
                let products = match k.variant {
                    Variant::Free => 10 + dim,
                    Variant::Fixed => 9 + dim,
                };
                assert_eq!(k.ops.add, r.ops.add + dim - 1, "n = {dim}, {}", k.name());
                assert_eq!(k.ops.mul, r.ops.mul + products, "n = {dim}, {}", k.name());
            }
            table.push_str(&format!(
                "{dim} walton::{}: {}; {} terms\n",
                k.name(),
                k.ops,
                k.terms
            ));
        }
        let file = syn::parse_file(&walton.source).expect("parses");
        assert_eq!(straight_line::check(&file), vec![], "n = {dim}");
    }
    compare("walton_op_counts.txt", &table);
}
