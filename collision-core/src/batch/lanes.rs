//! The blocked (AoSoA) layout: `LANES` contacts side by side, every scalar field a
//! `[T; LANES]` lane array, so that lane `l` of a block is one contact and the batch
//! kernels read and write whole lane arrays with plain vector loads and stores.
//!
//! Every block type ([`StateLanes`], [`ContactLanes`], [`FreeLanes`], [`FixedLanes`]) is
//! aligned to a 64-byte cache line, so that an `f64` lane array *is* one cache line and an
//! AVX-512 load or store of it touches one line, not two. (A vector of blocks used to get
//! `malloc`'s 16-byte alignment, every lane array straddled two lines, and the in-cache
//! kernels at n = 6 ran about 1.2x slower; docs/batch.md.) In `f64` the alignment adds no
//! padding (every block is a whole number of lane arrays of 64 bytes); in `f32` (32-byte lane
//! arrays) a state block with an odd number of lane arrays (n = 2, 5, 6) is padded by 32 bytes.

use crate::{Ball, BodyState};

/// Contacts per block. 8 lanes of `f64` fill one AVX-512 register, two AVX2 registers or
/// four SSE2 registers; a lane array of `f64` is one 64-byte cache line.
pub const LANES: usize = 8;

/// The alignment of every block type: one cache line.
pub const BLOCK_ALIGN: usize = 64;

/// One scalar field of `LANES` contacts.
pub type Lanes<T> = [T; LANES];

/// A lane index, `0 <= l < LANES` by construction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Lane(usize);

impl Lane {
    /// `Some` for `l < LANES`.
    pub fn new(l: usize) -> Option<Self> {
        (l < LANES).then_some(Lane(l))
    }

    /// Every lane, in order.
    pub fn all() -> impl Iterator<Item = Lane> {
        (0..LANES).map(Lane)
    }

    /// The lane's index, `< LANES`.
    pub fn index(self) -> usize {
        self.0
    }
}

/// A block of `LANES` values of `Item`, one per lane.
pub trait Lanewise {
    /// What one lane holds, as a per-collision type.
    type Item;
    /// A block with `item` in every lane (how a batch pads its last block: the padding is
    /// a copy of a real contact, so the kernels never see made-up inputs).
    fn splat(item: &Self::Item) -> Self;
    /// The item in lane `l`.
    fn lane(&self, l: Lane) -> Self::Item;
    /// Put `item` into lane `l`.
    fn set_lane(&mut self, l: Lane, item: Self::Item);
}

fn splat<T: Clone, const K: usize>(x: &[T; K]) -> [Lanes<T>; K] {
    std::array::from_fn(|k| std::array::from_fn(|_| x[k].clone()))
}

#[inline(always)]
fn lane_of<T: Clone, const K: usize>(x: &[Lanes<T>; K], l: Lane) -> [T; K] {
    std::array::from_fn(|k| x[k][l.0].clone())
}

#[inline(always)]
fn set_lane_of<T, const K: usize>(x: &mut [Lanes<T>; K], l: Lane, item: [T; K]) {
    for (lanes, v) in x.iter_mut().zip(item) {
        lanes[l.0] = v;
    }
}

impl<B: Lanewise, const K: usize> Lanewise for [B; K] {
    type Item = [B::Item; K];
    fn splat(item: &Self::Item) -> Self {
        std::array::from_fn(|k| B::splat(&item[k]))
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        std::array::from_fn(|k| self[k].lane(l))
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, item: Self::Item) {
        for (b, v) in self.iter_mut().zip(item) {
            b.set_lane(l, v);
        }
    }
}

/// The parameters of `LANES` balls ([`Ball`]'s fields, lane by lane).
#[derive(Clone, Debug, PartialEq)]
pub struct BallLanes<T> {
    /// Inverse masses `w = 1/m`, one per lane.
    pub inv_mass: Lanes<T>,
    /// Radii `R`, one per lane.
    pub radius: Lanes<T>,
    /// `gamma^2 = 2 lambda / R^2`, one per lane.
    pub gamma2: Lanes<T>,
}

impl<T: Clone> Lanewise for BallLanes<T> {
    type Item = Ball<T>;
    fn splat(b: &Ball<T>) -> Self {
        let [inv_mass, radius, gamma2] =
            splat(&[b.inv_mass.clone(), b.radius.clone(), b.gamma2.clone()]);
        BallLanes {
            inv_mass,
            radius,
            gamma2,
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Ball<T> {
        Ball {
            inv_mass: self.inv_mass[l.0].clone(),
            radius: self.radius[l.0].clone(),
            gamma2: self.gamma2[l.0].clone(),
        }
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, b: Ball<T>) {
        self.inv_mass[l.0] = b.inv_mass;
        self.radius[l.0] = b.radius;
        self.gamma2[l.0] = b.gamma2;
    }
}

/// The states of `LANES` bodies ([`BodyState`]'s fields, lane by lane).
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub struct StateLanes<T, const N: usize, const S: usize> {
    /// Compact skew entries `U_ij`, `i < j`, each a lane array.
    pub spin: [Lanes<T>; S],
    /// Centre velocity components `u_k`, each a lane array.
    pub velocity: [Lanes<T>; N],
}

impl<T: Clone, const N: usize, const S: usize> Lanewise for StateLanes<T, N, S> {
    type Item = BodyState<T, N, S>;
    fn splat(s: &Self::Item) -> Self {
        StateLanes {
            spin: splat(&s.spin),
            velocity: splat(&s.velocity),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        BodyState {
            spin: lane_of(&self.spin, l),
            velocity: lane_of(&self.velocity, l),
        }
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, s: Self::Item) {
        set_lane_of(&mut self.spin, l, s.spin);
        set_lane_of(&mut self.velocity, l, s.velocity);
    }
}

/// The kinematics of one contact: the unit normal `nu` (from body 1's centre to body 2's)
/// and both bodies' states before the collision.
#[derive(Clone, Debug, PartialEq)]
pub struct Contact<T, const N: usize, const S: usize> {
    /// The unit contact normal `nu`, from body 1 to body 2.
    pub nu: [T; N],
    /// Body 1's and body 2's states before the collision.
    pub states: [BodyState<T, N, S>; 2],
}

/// [`Contact`]s of `LANES` contacts: the block of the shared-parameter kernels.
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub struct ContactLanes<T, const N: usize, const S: usize> {
    /// The components of `nu`, each a lane array.
    pub nu: [Lanes<T>; N],
    /// Body 1's and body 2's states, lane by lane.
    pub states: [StateLanes<T, N, S>; 2],
}

impl<T: Clone, const N: usize, const S: usize> Lanewise for ContactLanes<T, N, S> {
    type Item = Contact<T, N, S>;
    fn splat(c: &Self::Item) -> Self {
        ContactLanes {
            nu: splat(&c.nu),
            states: Lanewise::splat(&c.states),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        Contact {
            nu: lane_of(&self.nu, l),
            states: self.states.lane(l),
        }
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, c: Self::Item) {
        set_lane_of(&mut self.nu, l, c.nu);
        self.states.set_lane(l, c.states);
    }
}

/// `LANES` contacts of two free balls, each with its own ball parameters: the block of the
/// per-contact `free` kernel. One lane is `(contact, [ball1, ball2])`.
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub struct FreeLanes<T, const N: usize, const S: usize> {
    /// The contacts' normals and states.
    pub contact: ContactLanes<T, N, S>,
    /// Body 1's and body 2's parameters, lane by lane.
    pub balls: [BallLanes<T>; 2],
}

impl<T: Clone, const N: usize, const S: usize> Lanewise for FreeLanes<T, N, S> {
    type Item = (Contact<T, N, S>, [Ball<T>; 2]);
    fn splat((c, balls): &Self::Item) -> Self {
        FreeLanes {
            contact: ContactLanes::splat(c),
            balls: Lanewise::splat(balls),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        (self.contact.lane(l), self.balls.lane(l))
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, (c, balls): Self::Item) {
        self.contact.set_lane(l, c);
        self.balls.set_lane(l, balls);
    }
}

/// `LANES` contacts of a free ball (body 2) with an immovable one (body 1), each with its
/// own parameters: the block of the per-contact `fixed` kernel. One lane is
/// `(contact, radius1, ball2)`; the immovable body enters through its radius alone.
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub struct FixedLanes<T, const N: usize, const S: usize> {
    /// The contacts' normals and states.
    pub contact: ContactLanes<T, N, S>,
    /// The immovable body 1's radius `R_1`, one per lane.
    pub radius1: Lanes<T>,
    /// The free body 2's parameters, lane by lane.
    pub ball2: BallLanes<T>,
}

impl<T: Clone, const N: usize, const S: usize> Lanewise for FixedLanes<T, N, S> {
    type Item = (Contact<T, N, S>, T, Ball<T>);
    fn splat((c, radius1, ball2): &Self::Item) -> Self {
        FixedLanes {
            contact: ContactLanes::splat(c),
            radius1: std::array::from_fn(|_| radius1.clone()),
            ball2: BallLanes::splat(ball2),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        (
            self.contact.lane(l),
            self.radius1[l.0].clone(),
            self.ball2.lane(l),
        )
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, (c, radius1, ball2): Self::Item) {
        self.contact.set_lane(l, c);
        self.radius1[l.0] = radius1;
        self.ball2.set_lane(l, ball2);
    }
}
