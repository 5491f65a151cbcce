//! An order of a kernel's steps that holds fewer values at once, for the batch kernels' lane
//! loop (a value that does not fit AVX2's 16 registers is spilled to the stack and read
//! back).
//!
//! Any topological order of the same steps computes the same values, bit for bit: each step
//! keeps its operation and its operands. Only how many values are held at once changes. The
//! scalar kernel's order computes every shared quantity first and then every output, so the
//! `n (n - 1) / 2` entries of `nu ^ t` wait, all held, for both bodies' spins, and the impulse
//! `P` for both velocities. [`tail_last`] keeps that order for the steps that feed three
//! outputs or more (the shared quantities) and then emits the rest, the *tail*, output by
//! output, body 1's and body 2's component `k` one after the other, each depth first: so an
//! entry of `nu ^ t` is formed just before the two spin entries that use it.
//! [`fewer_held`] takes that order only where it holds fewer values than the given one: at
//! n = 4, 5, 6 the most values held fall from 13, 18, 24 to 12, 15, 20 (both variants); at
//! n = 2, 3 (7 and 9, within the registers) the given order is kept.

use crate::ir::{Graph, Id};
use std::collections::{HashMap, HashSet};

/// For each step `i` of `steps` (in this order), the last step that reads its value, or `i`
/// itself if none does.
pub fn last_reads(graph: &Graph, steps: &[Id]) -> Vec<usize> {
    let position: HashMap<Id, usize> = steps.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    let mut last: Vec<usize> = (0..steps.len()).collect();
    for (i, &id) in steps.iter().enumerate() {
        for a in graph.node(id).operands() {
            if let Some(&p) = position.get(&a) {
                last[p] = last[p].max(i);
            }
        }
    }
    last
}

/// The most values held at once when `steps` run in this order: after each step, the values
/// computed so far that a later step still reads, and the step's own (inputs, constants and
/// values from outside the steps are read where they are used, so they are not counted).
pub fn held(graph: &Graph, steps: &[Id]) -> usize {
    let last = last_reads(graph, steps);
    // Step i's value is held after steps i..last_i - 1 (after step i alone if unused).
    let mut change = vec![0i64; steps.len() + 1];
    for (i, &l) in last.iter().enumerate() {
        change[i] += 1;
        change[l.max(i + 1)] -= 1;
    }
    let mut now = 0i64;
    let mut most = 0i64;
    for d in &change[..steps.len()] {
        now += d;
        most = most.max(now);
    }
    most as usize
}

/// `steps` (a topological order) with the tail last (module docs): the steps feeding at most
/// two of `outputs` are moved after the others and emitted depth first from `outputs` in the
/// given order (interleave the bodies there).
pub fn tail_last(graph: &Graph, steps: &[Id], outputs: &[Id]) -> Vec<Id> {
    let in_steps: HashSet<Id> = steps.iter().copied().collect();
    // How many outputs each step feeds.
    let mut feeds: HashMap<Id, usize> = HashMap::new();
    for &o in outputs {
        let (mut stack, mut seen) = (vec![o], HashSet::new());
        while let Some(x) = stack.pop() {
            if in_steps.contains(&x) && seen.insert(x) {
                *feeds.entry(x).or_default() += 1;
                stack.extend(graph.node(x).operands());
            }
        }
    }
    let tail: HashSet<Id> = steps
        .iter()
        .copied()
        .filter(|id| feeds.get(id).copied().unwrap_or(0) <= 2)
        .collect();
    let mut order: Vec<Id> = steps
        .iter()
        .copied()
        .filter(|id| !tail.contains(id))
        .collect();
    let mut done = HashSet::new();
    fn visit(
        graph: &Graph,
        id: Id,
        tail: &HashSet<Id>,
        done: &mut HashSet<Id>,
        order: &mut Vec<Id>,
    ) {
        if !tail.contains(&id) || !done.insert(id) {
            return;
        }
        for a in graph.node(id).operands() {
            visit(graph, a, tail, done, order);
        }
        order.push(id);
    }
    for &o in outputs {
        visit(graph, o, &tail, &mut done, &mut order);
    }
    // A tail step that reaches no output would be dead: a schedule has none.
    assert_eq!(order.len(), steps.len(), "every step is live");
    order
}

/// [`tail_last`]'s order, with the outputs of `bodies` (each body's in its component order)
/// interleaved by component, if it holds fewer values than `steps`' order ([`held`]); else
/// `steps` as given.
pub fn fewer_held(graph: &Graph, steps: &[Id], bodies: &[Vec<Id>]) -> Vec<Id> {
    let components = bodies.iter().map(Vec::len).max().unwrap_or(0);
    let outputs: Vec<Id> = (0..components)
        .flat_map(|k| bodies.iter().filter_map(move |b| b.get(k).copied()))
        .collect();
    let reordered = tail_last(graph, steps, &outputs);
    if held(graph, &reordered) < held(graph, steps) {
        reordered
    } else {
        steps.to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{self, Variant};
    use crate::schedule::schedule;

    /// Whether every step comes after the steps it reads.
    fn topological(graph: &Graph, order: &[Id]) -> bool {
        let position: HashMap<Id, usize> =
            order.iter().enumerate().map(|(i, &id)| (id, i)).collect();
        order.iter().enumerate().all(|(i, &id)| {
            graph
                .node(id)
                .operands()
                .all(|a| position.get(&a).is_none_or(|&p| p < i))
        })
    }

    #[test]
    fn values_held_are_counted_from_their_step_to_their_last_use() {
        // s = (x0 y0 + x1 y1) + x2 y2: all products first holds three at once (at the
        // third product); summing each at once holds two.
        let mut g = Graph::new();
        let p: Vec<Id> = (0..3)
            .map(|k| {
                let (x, y) = (g.input(format!("x{k}")), g.input(format!("y{k}")));
                g.mul(x, y)
            })
            .collect();
        let s1 = g.add(p[0], p[1]);
        let s = g.add(s1, p[2]);
        assert_eq!(held(&g, &[p[0], p[1], p[2], s1, s]), 3);
        assert_eq!(held(&g, &[p[0], p[1], s1, p[2], s]), 2);
        assert_eq!(held(&g, &[p[0]]), 1);
    }

    #[test]
    fn a_shared_factor_is_formed_just_before_the_two_outputs_it_feeds() {
        // Body 1's u_k + f_k and body 2's v_k - f_k, f_k = a_k b (the tail), b = x y shared:
        // the given order forms every f_k first (four held with b), the tail order one at a
        // time, each just before its two outputs.
        let mut g = Graph::new();
        let (x, y) = (g.input("x"), g.input("y"));
        let b = g.mul(x, y);
        let a: Vec<Id> = (0..3).map(|k| g.input(format!("a{k}"))).collect();
        let f: Vec<Id> = a.iter().map(|&ak| g.mul(ak, b)).collect();
        let (mut given, mut bodies) = (vec![b], vec![Vec::new(), Vec::new()]);
        given.extend(&f);
        for (k, &fk) in f.iter().enumerate() {
            let u = g.input(format!("u{k}"));
            bodies[0].push(g.add(u, fk));
        }
        for (k, &fk) in f.iter().enumerate() {
            let v = g.input(format!("v{k}"));
            bodies[1].push(g.sub(v, fk));
        }
        given.extend(bodies.concat());
        let order = fewer_held(&g, &given, &bodies);
        let [o1, o2] = [&bodies[0], &bodies[1]];
        assert_eq!(
            order,
            vec![b, f[0], o1[0], o2[0], f[1], o1[1], o2[1], f[2], o1[2], o2[2]]
        );
        assert_eq!((held(&g, &given), held(&g, &order)), (4, 3));
    }

    #[test]
    fn every_kernel_keeps_its_steps_and_holds_at_most_as_many_values() {
        // (n, free: given -> chosen, fixed: given -> chosen), from `held`. The `fixed`
        // kernels carry the unbiased spin coefficient's `y = rho' t` (`crate::unbiased`).
        let expected = [
            (2, (7, 7), (7, 7)),
            (3, (9, 9), (9, 9)),
            (4, (13, 12), (12, 12)),
            (5, (18, 15), (17, 17)),
            (6, (24, 20), (23, 21)),
        ];
        for (n, free, fixed) in expected {
            for (variant, (before, after)) in [(Variant::Free, free), (Variant::Fixed, fixed)] {
                let kernel = model::build(n, variant);
                let components = |o: &model::BodyOutput| -> Vec<Id> {
                    o.velocity.iter().chain(&o.spin).copied().collect()
                };
                let bodies: Vec<Vec<Id>> = kernel.outputs.iter().map(components).collect();
                let steps = schedule(&kernel.graph, bodies.concat()).steps;
                let order = fewer_held(&kernel.graph, &steps, &bodies);
                let (mut sorted, mut given) = (order.clone(), steps.clone());
                sorted.sort();
                given.sort();
                assert_eq!(sorted, given, "n = {n} {variant:?}: the same steps");
                assert!(topological(&kernel.graph, &order), "n = {n} {variant:?}");
                assert_eq!(
                    (held(&kernel.graph, &steps), held(&kernel.graph, &order)),
                    (before, after),
                    "n = {n} {variant:?}"
                );
            }
        }
    }
}
