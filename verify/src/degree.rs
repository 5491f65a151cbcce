//! Degree bounds of the rational functions a DAG computes, for the Schwartz-Zippel bound.
//!
//! Each node gets `(num, den)`: bounds on the total degrees of a numerator and a
//! denominator that represent it, in the free variables of [`crate::sample`]:
//! `a/b + c/d = (a d + c b) / (b d)`, `(a/b)(c/d) = a c / (b d)`, `(a/b)/(c/d) = a d / (b c)`.
//! An identity `f = 0` that is false has a non-zero numerator of degree `<= num`, which
//! vanishes at a uniform random point of `S^k` with probability `<= num / |S|`.
//! Shared denominators are not detected, so the bounds are loose, never low.

use noslip_codegen::ir::{Graph, Id, Node};

/// Bounds on the total degrees of a numerator and a denominator that represent a node.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Degree {
    /// The numerator's degree, at most.
    pub num: u64,
    /// The denominator's degree, at most.
    pub den: u64,
}

/// The input degrees: the normal's components are `(2 y_k or |y|^2 - 1) / (|y|^2 + 1)` in
/// the stereographic variables `y` (degree 2 over 2); every other input is a variable.
pub fn input_degree(name: &str) -> Degree {
    if name.starts_with("nu_") {
        Degree { num: 2, den: 2 }
    } else {
        Degree { num: 1, den: 0 }
    }
}

/// Degree bounds of every node of `g`.
pub fn degrees(g: &Graph) -> Vec<Degree> {
    let mut d: Vec<Degree> = Vec::with_capacity(g.len());
    for index in 0..g.len() {
        let at = |id: &Id| d[id.0 as usize];
        let x = match g.node(Id(index as u32)) {
            Node::Input(input) => input_degree(&input.0),
            Node::Const(_) => Degree::default(),
            Node::Add(a, b) | Node::Sub(a, b) => {
                let (a, b) = (at(a), at(b));
                Degree {
                    num: (a.num + b.den).max(b.num + a.den),
                    den: a.den + b.den,
                }
            }
            Node::Mul(a, b) => {
                let (a, b) = (at(a), at(b));
                Degree {
                    num: a.num + b.num,
                    den: a.den + b.den,
                }
            }
            Node::Div(a, b) => {
                let (a, b) = (at(a), at(b));
                Degree {
                    num: a.num + b.den,
                    den: a.den + b.num,
                }
            }
            Node::Neg(a) => at(a),
            // The value is one of the two arms, on each side of the comparison.
            Node::SelectLt([_, _, a, b]) => {
                let (a, b) = (at(a), at(b));
                Degree {
                    num: a.num.max(b.num),
                    den: a.den.max(b.den),
                }
            }
            // Where the verifier evaluates a root, its argument is the square of a rational
            // function of the sample's variables (it draws such points: `crate::sample`), a
            // square's numerator and denominator of half the degrees.
            Node::Sqrt(a) => {
                let a = at(a);
                Degree {
                    num: a.num.div_ceil(2),
                    den: a.den.div_ceil(2),
                }
            }
        };
        d.push(x);
    }
    d
}

/// The largest numerator degree among `zeros`: the degree of the identity "all are 0".
pub fn identity_degree(g: &Graph, zeros: &[Id]) -> u64 {
    let d = degrees(g);
    zeros.iter().map(|z| d[z.0 as usize].num).max().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_bound_sums_products_and_quotients() {
        let mut g = Graph::new();
        let (x, y) = (g.input("x"), g.input("y"));
        let q = g.div(x, y); // x / y: (1, 1)
        let s = g.add(q, x); // (x + x y) / y: (2, 1)
        let p = g.mul(s, s); // (4, 2)
        let d = degrees(&g);
        assert_eq!(d[q.0 as usize], Degree { num: 1, den: 1 });
        assert_eq!(d[s.0 as usize], Degree { num: 2, den: 1 });
        assert_eq!(identity_degree(&g, &[p, q]), 4);
    }
}
