//! The cell grid (`cells.rs`): the width rule and its cell counts (`O(bodies)` in a huge box),
//! the cells within reach of every cell (interior offsets and the odometer alike, shifts on
//! periodic axes, none beyond a wall, their count) and the layers a crossing reaches.

use super::*;

/// The (cell, shift) pairs `f` is called with.
fn listed<const N: usize>(
    visit: impl FnOnce(&mut dyn FnMut(Neighbour<N>)),
) -> Vec<(usize, [i8; N])> {
    let mut out = Vec::new();
    visit(&mut |nb: Neighbour<N>| out.push((nb.cell, nb.shift)));
    out
}

#[test]
fn a_layer_is_the_new_cells_within_reach_after_a_move() {
    // 2D: a periodic axis of 6 cells (reach 1), a walled one of 5; then a periodic axis of
    // one cell shorter than the contact distance (reach 2).
    let g = Grid::<2>::new([10.0, 8.0], [true, false], 1.5, 40).unwrap();
    assert_eq!((g.n, g.reach()), ([6, 5], [1, 1]));
    let moves = [
        ([0, 0], 0, 1),
        ([0, 0], 0, -1),
        ([5, 2], 0, 1),
        ([1, 2], 1, 1),
        ([1, 1], 1, -1),
    ];
    for (from, axis, step) in moves {
        let mut to: [usize; 2] = from;
        to[axis] = ((from[axis] as i64 + step).rem_euclid(g.n[axis] as i64)) as usize;
        let all = listed(|f| g.for_neighbours(&to, f));
        let old = listed(|f| g.for_neighbours(&from, f));
        let layer = listed(|f| g.for_layer(&to, axis, step, f));
        // Every layer cell is within reach of the new cell, none of the old one (by
        // cell index: with 6 cells, offset 2 from the old cell is not within reach).
        assert!(
            layer.iter().all(|x| all.contains(x)),
            "{from:?} {axis} {step}"
        );
        assert!(
            layer.iter().all(|(c, _)| old.iter().all(|(o, _)| o != c)),
            "{from:?}"
        );
        // Together with the old cells, every new one: |layer| = |all| - |kept|.
        let kept = all
            .iter()
            .filter(|(c, _)| old.iter().any(|(o, _)| o == c))
            .count();
        assert_eq!(layer.len() + kept, all.len(), "{from:?} {axis} {step}");
    }
    // Towards a wall from the last cell there is no layer.
    assert!(listed(|f| g.for_layer(&[2, 4], 1, 1, f)).is_empty());
    // Reach 2: the layer is the offset +-2.
    let g = Grid::<1>::new([1.0], [true], 1.5, 2).unwrap();
    assert_eq!(g.reach(), [2]);
    assert_eq!(listed(|f| g.for_layer(&[0], 0, 1, f)), vec![(0, [2])]);
    assert_eq!(listed(|f| g.for_layer(&[0], 0, -1, f)), vec![(0, [-2])]);
}

#[test]
fn interior_cells_list_what_the_odometer_lists() {
    // Every cell of grids with periodic, walled, one-cell and reach-2 axes: the offset
    // tables give the odometer's (cell, shift) list, in its order, for the whole
    // neighbourhood and for each layer; and the tables serve every interior cell.
    fn check<const N: usize>(g: &Grid<N>) {
        let mut tabled = 0;
        for flat in 0..g.cells() {
            let c: [usize; N] = std::array::from_fn(|k| flat / g.stride[k] % g.n[k]);
            let mut onlys = vec![None];
            for axis in 0..N {
                onlys.push(Some(g.layer(axis, 1)));
                onlys.push(Some(g.layer(axis, -1)));
            }
            for only in onlys {
                let near = listed(|f| g.for_cells(&c, only, f));
                let odometer = listed(|f| g.odometer(&c, only).for_each(f));
                assert_eq!(near, odometer, "{:?} {c:?} {only:?}", g.n);
                // `near_len` counts an interior cell's list; an edge's is no longer.
                let interior = g.near(&c, None).odometer.is_none();
                assert!(near.len() <= g.near_len(only), "{:?} {c:?} {only:?}", g.n);
                if interior {
                    assert_eq!(near.len(), g.near_len(only), "{:?} {c:?} {only:?}", g.n);
                }
            }
            tabled += usize::from(g.near(&c, None).odometer.is_none());
        }
        let interior: usize = (0..N)
            .map(|k| (g.n[k] as i64 - 2 * g.reach[k]).max(0) as usize)
            .product();
        assert_eq!(tabled, interior, "{:?}", g.n);
    }
    check(&Grid::<2>::new([10.0, 8.0], [true, false], 1.5, 40).unwrap());
    check(&Grid::<2>::new([1.0, 9.0], [true, true], 1.5, 40).unwrap());
    check(&Grid::<3>::new([7.0, 6.0, 0.5], [true, false, false], 1.0, 100).unwrap());
    check(&Grid::<3>::new([21.9; 3], [true; 3], 1.0, 4000).unwrap());
    check(&Grid::<4>::new([5.0; 4], [false, true, true, false], 1.0, 200).unwrap());
    check(&Grid::<2>::single([3.0, 4.0]));
}

#[test]
fn sides_that_are_multiples_of_the_contact_distance_have_reach_one() {
    // gas3d: side 16, d_max = 1. The old rule (w = 16 / 16 = d_max) needed reach 2.
    let g = Grid::<3>::new([16.0; 3], [true; 3], 1.0, 1000).unwrap();
    assert_eq!(g.reach(), [1; 3]);
    assert_eq!(g.n, [15; 3]);
    assert!(g.width.iter().all(|&w| w > 1.0 + slack(1.0, 16.0)));
    let mut scanned = 0;
    g.for_neighbours(&[0, 7, 14], |_| scanned += 1);
    assert_eq!(scanned, 27);
    // gas2d: side 60, d_max = 2; gas4d: side 8, d_max = 1 (200 bodies: capped at 800).
    let g = Grid::<2>::new([60.0; 2], [false; 2], 2.0, 750).unwrap();
    assert_eq!((g.reach(), g.n), ([1; 2], [29; 2]));
    let g = Grid::<4>::new([8.0; 4], [false, true, true, true], 1.0, 200).unwrap();
    assert_eq!(g.reach(), [1; 4]);
    assert!(g.cells() <= CELLS_PER_BODY * 200, "{:?}", g.n);
    assert!(g.width.iter().all(|&w| w > 1.0));
}

#[test]
fn every_width_beats_the_contact_distance_with_its_slack() {
    for side in [1.0, 2.0, 2.5, 3.0, 10.0, 10.5, 16.0, 16.0001, 60.0, 1e3] {
        for d_max in [0.1, 0.5, 1.0, 2.0] {
            if side <= d_max {
                continue;
            }
            let g = Grid::<2>::new([side, side], [true, false], d_max, 1 << 30).unwrap();
            for k in 0..2 {
                let w = g.width[k];
                assert!(w > d_max + slack(d_max, side), "{side} {d_max}");
                // And the cells are the most that allow it (or 1).
                let more = side / (g.n[k] + 1) as f64;
                assert!(more <= d_max + slack(d_max, side), "{side} {d_max}");
            }
            assert_eq!(g.reach(), [1, if g.n[1] == 1 { 0 } else { 1 }]);
        }
    }
}

#[test]
fn narrow_periodic_sides_reach_the_images_they_touch() {
    // Periodic side 1 with d_max 1.5: images at -1, 0, +1 and +-2 may touch.
    let g = Grid::<2>::new([1.0, 4.0], [true, true], 1.5, 4).unwrap();
    assert_eq!((g.n[0], g.reach()[0]), (1, 2));
    let mut shifts = Vec::new();
    g.for_neighbours(&[0, 0], |nb| shifts.push(nb.shift[0]));
    shifts.sort();
    shifts.dedup();
    assert_eq!(shifts, [-2, -1, 0, 1, 2]);
    let err = Grid::<2>::new([0.5, 4.0], [true, true], 1.5, 4).unwrap_err();
    assert!(
        matches!(err, SetupError::ShortSide { axis: 0, .. }),
        "{err}"
    );
}

#[test]
fn huge_boxes_get_o_bodies_cells() {
    // issue 16: 10 balls in a 6D periodic box of side 1e6 overflowed the cell count;
    // 100 disks in a 1e5 x 1e5 box allocated 60 GB.
    let g = Grid::<6>::new([1e6; 6], [true; 6], 1.0, 10).unwrap();
    assert!(g.cells() <= CELLS_PER_BODY * 10, "{:?}", g.n);
    assert_eq!(g.reach(), [1; 6]);
    let g = Grid::<2>::new([1e5; 2], [false; 2], 1.0, 100).unwrap();
    assert!(g.cells() <= CELLS_PER_BODY * 100, "{:?}", g.n);
    // Balanced: the cells are as square as the cap allows (20 x 20 = 400).
    assert_eq!(g.n, [20, 20]);
    // 6D, 10 balls: a common width gives 1 cell per axis (2^6 > 40); 2^5 fit.
    let g = Grid::<6>::new([1e6; 6], [true; 6], 1.0, 10).unwrap();
    assert_eq!(g.cells(), 32, "{:?}", g.n);
    // A long thin box keeps its cells along the long side.
    let g = Grid::<2>::new([1e6, 3.0], [true, true], 1.0, 10).unwrap();
    assert_eq!(g.n, [40, 1]);
    assert_eq!(g.reach(), [1, 1]);
}

/// The cells within reach by the definition: every offset in the box of the reach, the
/// cell `(c + delta) mod n` and shift `floor((c + delta) / n)` on a periodic axis, skipped
/// outside a walled one; the flat index `sum_k c_k prod_{l > k} n_l`.
fn by_definition<const N: usize>(g: &Grid<N>, c: &[usize; N]) -> Vec<(usize, [i8; N])> {
    let mut out = Vec::new();
    let count: i64 = (0..N).map(|k| 2 * g.reach[k] + 1).product();
    'offsets: for mut code in 0..count {
        let mut delta = [0i64; N];
        for k in (0..N).rev() {
            let width = 2 * g.reach[k] + 1;
            delta[k] = code % width - g.reach[k];
            code /= width;
        }
        let mut cell = [0usize; N];
        let mut shift = [0i8; N];
        for k in 0..N {
            let t = c[k] as i64 + delta[k];
            let n = g.n[k] as i64;
            if g.periodic[k] {
                cell[k] = t.rem_euclid(n) as usize;
                shift[k] = t.div_euclid(n) as i8;
            } else if (0..n).contains(&t) {
                cell[k] = t as usize;
            } else {
                continue 'offsets;
            }
        }
        let flat = (0..N).fold(0, |acc, k| acc * g.n[k] + cell[k]);
        out.push((flat, shift));
    }
    out
}

#[test]
fn neighbours_are_the_cells_of_the_definition_in_its_order() {
    let grids = [
        Grid::<2>::new([10.0, 4.0], [true, false], 1.0, 100).unwrap(),
        Grid::<2>::new([1.0, 4.0], [true, true], 1.5, 4).unwrap(),
        Grid::<2>::new([2.5, 7.0], [true, true], 1.0, 100).unwrap(),
    ];
    for g in &grids {
        for c0 in 0..g.n[0] {
            for c1 in 0..g.n[1] {
                let mut got = Vec::new();
                g.for_neighbours(&[c0, c1], |nb| got.push((nb.cell, nb.shift)));
                assert_eq!(got, by_definition(g, &[c0, c1]), "{:?} {c0} {c1}", g.n);
                assert_eq!(g.flat(&[c0, c1]), c0 * g.n[1] + c1);
                // `distinct` says whether no cell is listed twice (at two images).
                let cells: std::collections::BTreeSet<usize> = got.iter().map(|g| g.0).collect();
                let distinct = g.odometer(&[c0, c1], None).distinct;
                assert_eq!(distinct, cells.len() == got.len(), "{:?} {c0} {c1}", g.n);
            }
        }
    }
    let g = Grid::<3>::new([5.0, 3.5, 4.0], [true, false, true], 1.0, 100).unwrap();
    for c in [[0, 0, 0], [4, 2, 3], [2, 1, 0], [0, 2, 2]] {
        let mut got = Vec::new();
        g.for_neighbours(&c, |nb| got.push((nb.cell, nb.shift)));
        assert_eq!(got, by_definition(&g, &c), "{c:?}");
    }
}

/// A crossing's next cell and wrap, chosen without a branch on the direction (`crossed`),
/// are `(c +- 1) mod n` and whether it passed the axis's end, on every cell and axis of
/// grids with 1, 2 and 7 cells an axis; and the layer it reaches is the one a step of
/// `+-1` gives.
#[test]
fn a_crossing_steps_one_cell_modulo_the_axis() {
    for (size, n) in [([10.0, 1.0, 3.0], [7, 1, 2]), ([10.0, 3.0, 1.2], [7, 2, 1])] {
        let g = Grid::<3>::new(size, [true, true, false], 1.4, 100).unwrap();
        assert_eq!(g.n, n);
        for c0 in 0..g.n[0] {
            for c1 in 0..g.n[1] {
                for c2 in 0..g.n[2] {
                    let c = [c0, c1, c2];
                    for axis in 0..3 {
                        for up in [false, true] {
                            let n = g.n[axis] as i64;
                            let step = if up { 1 } else { -1 };
                            let mut want = c;
                            want[axis] = (c[axis] as i64 + step).rem_euclid(n) as usize;
                            let wrapped = if up {
                                c[axis] + 1 == g.n[axis]
                            } else {
                                c[axis] == 0
                            };
                            assert_eq!(
                                g.crossed(&c, axis, up),
                                (want, wrapped),
                                "{c:?} {axis} {up}"
                            );
                            assert_eq!(g.reached(axis, up), g.layer(axis, step));
                        }
                    }
                }
            }
        }
    }
}
