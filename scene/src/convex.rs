//! Strict convexity of a polygon in `O(m)` exact operations.
//!
//! A closed polygon `v_0 .. v_{m-1}` (counterclockwise by its signed area) is the boundary of
//! a strictly convex polygon, in order, exactly when
//!
//! 1. every turn is strictly to the left: `(v_{k+1} - v_k) x (v_{k+2} - v_{k+1}) > 0` for
//!    every `k` (indices mod `m`), which refuses a repeated consecutive vertex (a zero edge)
//!    and three consecutive vertices on a line; and
//! 2. the edge directions turn once around: with every turn left and less than a half turn,
//!    the direction angle grows monotonically and its total is `2 pi w`, `w` the number of
//!    edges `k` whose direction `e_k` is in the lower half-plane `[pi, 2 pi)` while `e_{k+1}`
//!    is in the upper one `[0, pi)` (a left turn of less than `pi` from the lower half to the
//!    upper one passes angle 0 exactly once). `w = 1`, else the polygon winds `w` times and
//!    crosses itself (a pentagram: `w = 2`).
//!
//! A closed curve whose tangent turns monotonically by exactly `2 pi` is convex and simple
//! (the converse of the theorem of turning tangents for polygons), so 1 and 2 are equivalent
//! to the quadratic definition "every vertex strictly inside the line of every edge it is not
//! on", which this replaces: that one took 25 s at 1000 vertices (issue 26, item 8).

use num_rational::BigRational;
use num_traits::{Signed, Zero};

type Q = BigRational;

/// Why a counterclockwise polygon is not strictly convex.
#[derive(Debug, PartialEq)]
pub(crate) enum NotConvex {
    /// Vertex `v[turn + 2]` is not strictly left of the edge `v[turn] -> v[turn + 1]` (indices
    /// mod `m`).
    Turn(usize),
    /// Every turn is left, but the edges turn this many times around (at least 2).
    Winds(usize),
}

/// `a_0 b_1 - a_1 b_0`.
pub(crate) fn cross(a: &[Q], b: &[Q]) -> Q {
    &a[0] * &b[1] - &a[1] * &b[0]
}

fn edge(v: &[Vec<Q>], k: usize) -> [Q; 2] {
    let (a, b) = (&v[k % v.len()], &v[(k + 1) % v.len()]);
    [&b[0] - &a[0], &b[1] - &a[1]]
}

/// Whether direction `e` is in the upper half-plane of angles `[0, pi)`: `e_1 > 0`, or `e_1 =
/// 0` and `e_0 > 0`.
fn upper(e: &[Q; 2]) -> bool {
    e[1].is_positive() || (e[1].is_zero() && e[0].is_positive())
}

/// Checks 1 and 2 of the module docs on the counterclockwise polygon `v` (at least 3
/// vertices): the first left turn that fails, else the winding if it is not 1.
pub(crate) fn strictly_convex(v: &[Vec<Q>]) -> Result<(), NotConvex> {
    let m = v.len();
    let mut winds = 0;
    let mut e = edge(v, 0);
    for k in 0..m {
        let next = edge(v, k + 1);
        if !cross(&e, &next).is_positive() {
            return Err(NotConvex::Turn(k));
        }
        winds += usize::from(!upper(&e) && upper(&next));
        e = next;
    }
    if winds == 1 {
        Ok(())
    } else {
        Err(NotConvex::Winds(winds))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn polygon(points: &[(i64, i64)]) -> Vec<Vec<Q>> {
        points
            .iter()
            .map(|&(x, y)| vec![Q::from_integer(x.into()), Q::from_integer(y.into())])
            .collect()
    }

    /// The quadratic definition: every vertex strictly left of every edge it is not on.
    fn quadratic(v: &[Vec<Q>]) -> bool {
        let m = v.len();
        (0..m).all(|k| {
            let e = edge(v, k);
            (0..m).filter(|&j| j != k && j != (k + 1) % m).all(|j| {
                let d = [&v[j][0] - &v[k][0], &v[j][1] - &v[k][1]];
                cross(&e, &d).is_positive()
            })
        })
    }

    #[test]
    fn a_pentagram_winds_twice_and_a_dent_turns_right() {
        let star = polygon(&[(0, 0), (2, 1), (-1, 1), (1, 0), (0, 2)]);
        // (The pentagram as given is clockwise by area? Its signed area decides; both
        // orientations of it wind twice.)
        let mut ccw = star.clone();
        ccw[1..].reverse();
        let got = [strictly_convex(&star), strictly_convex(&ccw)];
        assert!(got.contains(&Err(NotConvex::Winds(2))), "{got:?}");
        let dent = polygon(&[(0, 0), (10, 0), (10, 10), (9, 1)]);
        assert_eq!(strictly_convex(&dent), Err(NotConvex::Turn(2)));
        let square = polygon(&[(0, 0), (1, 0), (1, 1), (0, 1)]);
        assert_eq!(strictly_convex(&square), Ok(()));
    }

    /// The linear test agrees with the quadratic definition on every counterclockwise (by
    /// signed area) polygon of 3 to 6 vertices drawn from a small grid: convex ones,
    /// repeated and collinear vertices, dents, stars.
    #[test]
    fn it_agrees_with_the_quadratic_definition() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n) as i64
        };
        let (mut convex, mut not) = (0, 0);
        for case in 0..40_000 {
            let m = 3 + case % 4;
            let mut v: Vec<(i64, i64)> = (0..m).map(|_| (next(5), next(5))).collect();
            let area2: i64 = (0..m)
                .map(|k| {
                    let (a, b) = (v[k], v[(k + 1) % m]);
                    a.0 * b.1 - a.1 * b.0
                })
                .sum();
            if area2 == 0 {
                continue;
            }
            if area2 < 0 {
                v[1..].reverse();
            }
            let p = polygon(&v);
            let want = quadratic(&p);
            assert_eq!(strictly_convex(&p).is_ok(), want, "{v:?}");
            if want {
                convex += 1;
            } else {
                not += 1;
            }
        }
        // Both outcomes are well represented.
        assert!(convex > 1000 && not > 1000, "{convex} {not}");
    }
}
