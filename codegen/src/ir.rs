//! A hash-consed expression DAG over scalar inputs with exact rational constants.
//!
//! Every node is created through the smart constructors of [`Graph`], which
//! - fold constants exactly (`BigRational` arithmetic),
//! - apply the identities `x + 0 = x`, `x * 1 = x`, `x * 0 = 0`, `x * (-1) = -x`,
//!   `-(-x) = x`, `x - x = 0`, `x + (-y) = x - y`, `x - (-y) = x + y`, `(-x) * y = -(x y)`,
//!   `(-x) + (-y) = -(x + y)`,
//! - order the operands of `+` and `*` canonically,
//! - and return the existing node when an identical one exists (hash-consing), which is
//!   common-subexpression elimination by construction.
//!
//! All these rewrites are exact in IEEE arithmetic for finite operands (commutation, adding
//! zero, multiplying by one, negation are exact), so a kernel emitted from the DAG rounds
//! exactly as the formula it was built from, evaluated in the emitted order.

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::collections::HashMap;
use std::ops::{Add, Div, Mul, Neg, Sub};
use std::str::FromStr;

/// Index of a node in its [`Graph`]. Operands always have smaller ids than the node
/// itself, so increasing id order is a topological order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

impl Id {
    pub(crate) fn index(self) -> usize {
        self.0 as usize
    }
}

/// A kernel input: one scalar, named by its Rust binding (e.g. `nu_0`, `U1_01`, `inv_mass1`).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Input(pub String);

/// One node of the DAG.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A kernel input.
    Input(Input),
    /// An exact rational constant.
    Const(BigRational),
    /// `a + b`, operands in canonical order.
    Add(Id, Id),
    /// `a - b`.
    Sub(Id, Id),
    /// `a * b`, operands in canonical order (a constant first).
    Mul(Id, Id),
    /// `a / b`.
    Div(Id, Id),
    /// `-a`.
    Neg(Id),
    /// `sqrt(a)`, `a >= 0`: the Walton law's one root (`docs/derivation.md` §15.1).
    Sqrt(Id),
    /// `if x < y { a } else { b }`, `[x, y, a, b]`: a branch-free select (both arms are
    /// computed; the comparison picks one).
    SelectLt([Id; 4]),
}

impl Node {
    /// The operands, in order (`a` then `b`; none for an input or a constant).
    pub fn operands(&self) -> impl Iterator<Item = Id> {
        let ids = match *self {
            Node::Input(_) | Node::Const(_) => vec![],
            Node::Neg(a) | Node::Sqrt(a) => vec![a],
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => vec![a, b],
            Node::SelectLt(ids) => ids.to_vec(),
        };
        ids.into_iter()
    }
}

/// A hook of [`Graph::eval_all`]: a replacement value for node `id`, given the values of the
/// nodes before it, or `None` to evaluate the node as built.
pub type Rewrite<'a, T = BigRational> = dyn Fn(Id, &Node, &[T]) -> Option<T> + 'a;

/// The expression DAG. Nodes are append-only; see the module docs for the rewrites.
#[derive(Default, Debug)]
pub struct Graph {
    nodes: Vec<Node>,
    interned: HashMap<Node, Id>,
    labels: HashMap<Id, String>,
    reciprocal_constants: bool,
}

impl Graph {
    /// An empty graph (divisions by constants kept as divisions).
    pub fn new() -> Self {
        Self::default()
    }

    /// Rewrite every division by a constant `a / c` as the product `a * (1/c)` with the
    /// exact reciprocal folded into a literal (off by default). Exact in rationals; in floats
    /// it rounds `1/c` once more unless `c` is a power of two, so it is used only for
    /// specialised kernels, where it removes every run-time division.
    pub fn fold_reciprocals(&mut self, yes: bool) {
        self.reciprocal_constants = yes;
    }

    /// The node `id`.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no nodes.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// A readable name for a node (`dn`, `inv_d`, `t_0`): used by the emitter for the
    /// `let` binding of that node instead of a numbered temporary. The first label wins.
    pub fn label(&mut self, id: Id, name: impl Into<String>) {
        if matches!(self.node(id), Node::Input(_) | Node::Const(_)) {
            return;
        }
        self.labels.entry(id).or_insert_with(|| name.into());
    }

    /// The label given to `id` by [`Graph::label`], if any.
    pub fn label_of(&self, id: Id) -> Option<&str> {
        self.labels.get(&id).map(String::as_str)
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.interned.get(&node) {
            return id;
        }
        let id = Id(u32::try_from(self.nodes.len()).expect("graph larger than 2^32 nodes"));
        self.nodes.push(node.clone());
        self.interned.insert(node, id);
        id
    }

    /// The input named `name` (the same node for the same name).
    pub fn input(&mut self, name: impl Into<String>) -> Id {
        self.intern(Node::Input(Input(name.into())))
    }

    /// The constant `value`.
    pub fn constant(&mut self, value: BigRational) -> Id {
        self.intern(Node::Const(value))
    }

    /// The integer constant `value`.
    pub fn int(&mut self, value: i64) -> Id {
        self.constant(BigRational::from_integer(value.into()))
    }

    /// The constant value of a node, if it is a constant.
    pub fn as_const(&self, id: Id) -> Option<&BigRational> {
        match self.node(id) {
            Node::Const(c) => Some(c),
            _ => None,
        }
    }

    fn is_const(&self, id: Id, pred: impl Fn(&BigRational) -> bool) -> bool {
        self.as_const(id).is_some_and(pred)
    }

    fn negated(&self, id: Id) -> Option<Id> {
        match self.node(id) {
            Node::Neg(x) => Some(*x),
            _ => None,
        }
    }

    /// `a + b`: folded when both are constant, `x + 0 = x`, negations pulled out, operands ordered.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x + y);
        }
        if self.is_const(a, Zero::is_zero) {
            return b;
        }
        if self.is_const(b, Zero::is_zero) {
            return a;
        }
        match (self.negated(a), self.negated(b)) {
            (Some(x), Some(y)) => {
                let s = self.add(x, y);
                return self.neg(s);
            }
            (None, Some(y)) => return self.sub(a, y),
            (Some(x), None) => return self.sub(b, x),
            (None, None) => {}
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// `a - b`: `x - x = 0`, folded when both are constant, `x - 0 = x`, `0 - x = -x`,
    /// `x - (-y) = x + y`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.int(0);
        }
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x - y);
        }
        if self.is_const(b, Zero::is_zero) {
            return a;
        }
        if self.is_const(a, Zero::is_zero) {
            return self.neg(b);
        }
        if let Some(y) = self.negated(b) {
            return self.add(a, y);
        }
        self.intern(Node::Sub(a, b))
    }

    /// `a * b`: folded when both are constant, `x * 0 = 0`, `x * 1 = x`, `x * (-1) = -x`,
    /// negations pulled out, a constant first.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x * y);
        }
        if self.is_const(a, Zero::is_zero) || self.is_const(b, Zero::is_zero) {
            return self.int(0);
        }
        if self.is_const(a, One::is_one) {
            return b;
        }
        if self.is_const(b, One::is_one) {
            return a;
        }
        let minus_one = |c: &BigRational| c.is_negative() && c.abs().is_one();
        if self.is_const(a, minus_one) {
            return self.neg(b);
        }
        if self.is_const(b, minus_one) {
            return self.neg(a);
        }
        if let Some(x) = self.negated(a) {
            let p = self.mul(x, b);
            return self.neg(p);
        }
        if let Some(y) = self.negated(b) {
            let p = self.mul(a, y);
            return self.neg(p);
        }
        // Constants first, then by id: `2 * x` reads better than `x * 2`.
        let (a, b) = match (self.as_const(a).is_some(), self.as_const(b).is_some()) {
            (false, true) => (b, a),
            (true, false) => (a, b),
            _ if a <= b => (a, b),
            _ => (b, a),
        };
        self.intern(Node::Mul(a, b))
    }

    /// `a / b`. Panics on a constant zero divisor: that is a bug in the model builder.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        assert!(
            !self.is_const(b, Zero::is_zero),
            "model builder divided by the constant 0"
        );
        if let (Some(x), Some(y)) = (self.as_const(a), self.as_const(b)) {
            return self.constant(x / y);
        }
        if self.is_const(a, Zero::is_zero) {
            return self.int(0);
        }
        if self.is_const(b, One::is_one) {
            return a;
        }
        if a == b {
            return self.int(1);
        }
        if self.reciprocal_constants {
            if let Some(c) = self.as_const(b) {
                let r = self.constant(c.recip());
                return self.mul(a, r);
            }
        }
        self.intern(Node::Div(a, b))
    }

    /// `-a`: folded for a constant, `-(-x) = x`.
    pub fn neg(&mut self, a: Id) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(-x);
        }
        if let Some(x) = self.negated(a) {
            return x;
        }
        self.intern(Node::Neg(a))
    }

    /// `sqrt(a)`: folded for a constant that is the square of a rational; the builder
    /// guarantees `a >= 0` wherever the kernel is defined.
    pub fn sqrt(&mut self, a: Id) -> Id {
        if let Some(root) = self.as_const(a).and_then(rational_sqrt) {
            return self.constant(root);
        }
        self.intern(Node::Sqrt(a))
    }

    /// `if x < y { a } else { b }`: folded when `x` and `y` are constants or `a == b`.
    pub fn select_lt(&mut self, x: Id, y: Id, a: Id, b: Id) -> Id {
        if a == b {
            return a;
        }
        if let (Some(p), Some(q)) = (self.as_const(x), self.as_const(y)) {
            return if p < q { a } else { b };
        }
        self.intern(Node::SelectLt([x, y, a, b]))
    }

    /// `sum_k terms[k]`, left to right (so the rounding order is the order given).
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Id>) -> Id {
        let zero = self.int(0);
        terms.into_iter().fold(zero, |acc, t| self.add(acc, t))
    }

    /// `sum_k a[k] * b[k]`, left to right.
    pub fn dot(&mut self, a: &[Id], b: &[Id]) -> Id {
        assert_eq!(a.len(), b.len());
        let products: Vec<Id> = a.iter().zip(b).map(|(&x, &y)| self.mul(x, y)).collect();
        self.sum(products)
    }

    /// Exact values of every node, in id order. `input` gives each input's value; `rewrite`
    /// may replace a node's value, given the values of the nodes before it (the verifier
    /// corrupts kernels with it on purpose; `|_, _, _| None` evaluates the DAG as built).
    /// Errors name a missing input or a division by zero; a [`Node::Sqrt`] is an error here
    /// (see [`Graph::eval_all_rooted`]).
    ///
    /// `T` is any exact field whose values parse from `p/q` (the DAG's constants are written
    /// so): `BigRational`, `collision_core::Exact`.
    pub fn eval_all<T>(
        &self,
        input: &dyn Fn(&str) -> Option<T>,
        rewrite: &Rewrite<'_, T>,
    ) -> Result<Vec<T>, String>
    where
        T: Clone + Zero + FromStr + PartialOrd + std::fmt::Display,
        for<'a> &'a T: Add<&'a T, Output = T>
            + Sub<&'a T, Output = T>
            + Mul<&'a T, Output = T>
            + Div<&'a T, Output = T>
            + Neg<Output = T>,
    {
        self.eval_all_rooted(input, rewrite, &|_| None)
    }

    /// [`Graph::eval_all`] where a [`Node::Sqrt`] takes `root`, the exact square root
    /// (`None` when it is not rational: an error, since every value here is exact).
    pub fn eval_all_rooted<T>(
        &self,
        input: &dyn Fn(&str) -> Option<T>,
        rewrite: &Rewrite<'_, T>,
        root: &dyn Fn(&T) -> Option<T>,
    ) -> Result<Vec<T>, String>
    where
        T: Clone + Zero + FromStr + PartialOrd + std::fmt::Display,
        for<'a> &'a T: Add<&'a T, Output = T>
            + Sub<&'a T, Output = T>
            + Mul<&'a T, Output = T>
            + Div<&'a T, Output = T>
            + Neg<Output = T>,
    {
        let mut values: Vec<T> = Vec::with_capacity(self.nodes.len());
        for (i, node) in self.nodes.iter().enumerate() {
            let id = Id(i as u32);
            let v = match rewrite(id, node, &values) {
                Some(v) => v,
                None => {
                    let at = |x: &Id| &values[x.index()];
                    match node {
                        Node::Input(Input(name)) => {
                            input(name).ok_or_else(|| format!("no value for input {name}"))?
                        }
                        Node::Const(c) => c
                            .to_string()
                            .parse()
                            .map_err(|_| format!("constant {c} does not parse"))?,
                        Node::Add(a, b) => at(a) + at(b),
                        Node::Sub(a, b) => at(a) - at(b),
                        Node::Mul(a, b) => at(a) * at(b),
                        Node::Div(_, b) if at(b).is_zero() => return Err("division by zero".into()),
                        Node::Div(a, b) => at(a) / at(b),
                        Node::Neg(a) => -at(a),
                        Node::SelectLt([x, y, a, b]) => {
                            if at(x) < at(y) { at(a) } else { at(b) }.clone()
                        }
                        Node::Sqrt(a) => root(at(a)).ok_or_else(|| {
                            format!("the square root of {} is not rational", at(a))
                        })?,
                    }
                }
            };
            values.push(v);
        }
        Ok(values)
    }
}

/// The square root of `x` if it is the square of a rational (numerator and denominator
/// perfect squares), else `None`.
pub fn rational_sqrt(x: &BigRational) -> Option<BigRational> {
    if x.is_negative() {
        return None;
    }
    let (p, q) = (x.numer().sqrt(), x.denom().sqrt());
    (&p * &p == *x.numer() && &q * &q == *x.denom()).then(|| BigRational::new(p, q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_consing_shares_commuted_products() {
        let mut g = Graph::new();
        let (x, y) = (g.input("x"), g.input("y"));
        let xy = g.mul(x, y);
        let yx = g.mul(y, x);
        assert_eq!(xy, yx);
        assert_eq!(g.add(x, y), g.add(y, x));
        assert_ne!(g.sub(x, y), g.sub(y, x));
        assert_eq!(g.len(), 6); // x, y, x y, x + y, x - y, y - x
    }

    #[test]
    fn identities_fold_away() {
        let mut g = Graph::new();
        let x = g.input("x");
        let (zero, one, minus_one) = (g.int(0), g.int(1), g.int(-1));
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.sub(x, x), zero);
        let nx = g.mul(minus_one, x);
        assert_eq!(g.node(nx), &Node::Neg(x));
        assert_eq!(g.neg(nx), x);
        let y = g.input("y");
        let x_plus_neg_y = {
            let ny = g.neg(y);
            g.add(x, ny)
        };
        assert_eq!(x_plus_neg_y, g.sub(x, y));
        assert_eq!(g.div(x, one), x);
    }

    #[test]
    fn constants_fold_exactly() {
        let mut g = Graph::new();
        let (a, b) = (g.int(1), g.int(3));
        let third = g.div(a, b);
        let sum = g.add(third, third);
        let expected = BigRational::new(2.into(), 3.into());
        assert_eq!(g.as_const(sum), Some(&expected));
    }

    #[test]
    fn eval_follows_the_dag() {
        let mut g = Graph::new();
        let (x, y) = (g.input("x"), g.input("y"));
        let q = g.div(x, y);
        let e = g.sub(q, y);
        let v = g
            .eval_all(
                &|name| match name {
                    "x" => Some(BigRational::from_integer(3.into())),
                    _ => Some(BigRational::from_integer(2.into())),
                },
                &|_, _, _| None,
            )
            .unwrap();
        assert_eq!(v[e.index()], BigRational::new((-1).into(), 2.into()));
        let y_zero = |name: &str| Some(BigRational::from_integer((name == "x").into()));
        assert_eq!(
            g.eval_all(&y_zero, &|_, _, _| None),
            Err("division by zero".into())
        );
        assert_eq!(
            g.eval_all::<BigRational>(&|_| None, &|_, _, _| None),
            Err("no value for input x".into())
        );
    }
}
