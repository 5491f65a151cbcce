//! # noslip-sim
//!
//! An event-driven simulation of rigid balls with no-slip collisions (a rough-ball gas, a
//! no-slip billiard) in a box whose axes are walled or periodic, with fixed ball obstacles, and
//! tables of other shapes ([`table`]: walls, containers, polygons; bounded or not), each
//! contact no-slip or smooth.
//!
//! Between events every ball flies freely: `a(t) = a + t u`, `U` constant, orientation
//! `A(t) = exp(t U) A` (the mass distributions are radial, so the inertia is isotropic and the
//! spatial angular velocity is constant). At a contact the state jumps by the no-slip map of
//! the pair: [`PairKernels`], the generic generated kernels ([`GenericKernels`]) or a scene's
//! specialised ones (noslip-codegen's `specialise`).
//!
//! Events are found with a cell list (cells wider than the largest contact distance, so only
//! the `3^n` neighbouring cells are scanned, at most 4 cells per body whatever the box) and a
//! calendar queue that holds, per ball, its one earliest predicted event ([`engine`] gives the
//! invariants: the image rule across periodic faces, the local clock); contact times solve
//! `|d + t dv|^2 = (R_i + R_j)^2` ([`predict`]). A run stops by itself when no contact can
//! happen again ([`no_contact`]).
//!
//! Around the engine: [`setup`] turns a validated scene (`noslip-scene`) into a [`Setup`],
//! checked in the f64 arithmetic the engine uses ([`range`]) and placed in O(N) ([`place`],
//! [`cover`], [`sequential`]); [`run`] runs it to its limits, writing the event log ([`log`],
//! [`run::event_json`]) and keeping bounded traces ([`trace`]) for the pictures ([`plot`]) and the browser
//! animation ([`animation`], [`animation_page`]). [`huge_pages`] is the allocator the binaries
//! that run the engine register, so that its large arrays sit on 2 MiB pages.
//! This crate must not parse command lines, print, or write files other than through the
//! writers it is given: that is the `noslip` command's business.

#![warn(missing_docs, unreachable_pub)]

pub mod animation;
pub mod animation_page;
pub mod boundary_map;
mod buckets;
mod canonical;
mod cells;
mod clock;
pub mod collapse;
pub mod conserving;
pub mod cover;
pub mod dilute;
pub mod displacement;
pub mod engine;
mod extent;
pub mod granular;
pub mod granular_plot;
pub mod huge_pages;
mod immovable;
mod last_contact;
pub mod lattice;
#[cfg(test)]
mod lattice_tests;
pub mod law;
pub mod left_table;
pub mod lists;
pub mod log;
pub mod maxwell;
mod motion;
mod nearest;
pub mod no_contact;
mod normal;
pub mod observables_plot;
mod observe;
mod orientation;
pub mod pair_correlation;
pub mod pair_losses;
pub mod place;
pub mod plot;
mod png;
pub mod portrait;
mod portrait_png;
pub mod predict;
mod queue;
pub mod range;
#[cfg(test)]
mod reference;
mod residents;
pub mod rough;
pub mod run;
mod select;
pub mod self_diffusion;
pub mod sequential;
pub mod setup;
pub mod smooth;
pub mod species_laws;
pub mod speed_range;
mod stage;
pub mod table;
#[cfg(test)]
mod table_tests;
#[cfg(test)]
mod tests;
pub mod thermostat;
pub mod trace;

pub use conserving::Conserving;
pub use engine::{Contact, Event, SetupError, Simulation, Step};
pub use left_table::LeftTable;
pub use lists::{ListSimulation, ListsRefusal};
pub use no_contact::NoContact;
pub use observe::Observables;
pub use table::{Boundary, ContactKind, Geometry, Shape, Table};

use collision_core::{Ball, BodyState, Generated, Kernel, RefArith, Scalar};

/// The maps of the pair kinds a simulation meets, by species index ([`PairKernels::laws`]
/// says which law each applies: the no-slip map unless it says otherwise). Body 1 of
/// `ball_ball` is species `a` and `nu` points from body 1 to body 2; walls and obstacles are
/// at rest and immovable, `nu` from the obstacle's centre to the ball's, and a wall's normal
/// is `+e_axis` (the wall at `x_axis = 0`) or `-e_axis` (`upper`, at `x_axis = L`).
pub trait PairKernels<T, const N: usize, const S: usize> {
    /// The contact law each kind of kernel applies ([`law::FoldedLaws`]): the engines call
    /// `ball_ball`, `ball_wall` and `ball_obstacle` for contacts of that law and the generic
    /// kernels of their law otherwise. The default, the no-slip map for all three, is the
    /// generic kernels'; scene-specialised kernels (`noslip_codegen::specialise`) may have a
    /// rough law folded in.
    fn laws(&self) -> law::FoldedLaws {
        law::FoldedLaws::NO_SLIP
    }
    /// The law `ball_ball(a, b, ..)` applies (either order of `a`, `b`): by default
    /// [`law::FoldedLaws::ball`] of [`PairKernels::laws`] for every pair; kernels specialised
    /// to a scene whose species pairs have several laws (`[[contact.pair]]`) name each pair's,
    /// with `laws().ball` then `None`. The engines call `ball_ball` for a contact of this law
    /// and the generic kernels of its law otherwise.
    fn ball_law(&self, a: usize, b: usize) -> Option<ContactKind> {
        let _ = (a, b);
        self.laws().ball
    }
    /// The states of balls of species `a` (body 1) and `b` (body 2) after their contact.
    fn ball_ball(
        &self,
        a: usize,
        b: usize,
        nu: &[T; N],
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2];
    /// The state of a ball of `species` after hitting the wall of `axis` (at `x_axis = L` if
    /// `upper`, else at `x_axis = 0`).
    fn ball_wall(
        &self,
        species: usize,
        axis: usize,
        upper: bool,
        state: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
    /// The state of a ball of `species` after hitting an immovable body at rest with the
    /// local unit normal `nu` (from the body to the ball): a fixed ball obstacle, and every
    /// other boundary of the table (walls, containers, polygon edges and vertices): the
    /// `fixed` map, which depends on the body only through `nu` ([`table`]).
    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[T; N],
        state: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S>;
}

/// The generic generated kernels with each species' parameters passed at run time.
#[derive(Clone, Debug)]
pub struct GenericKernels<T> {
    /// Each species' parameters, by species index.
    pub species: Vec<Ball<T>>,
}

impl<T: Scalar, const N: usize, const S: usize> PairKernels<T, N, S> for GenericKernels<T>
where
    for<'a> &'a T: RefArith<T>,
    Generated: Kernel<T, N, S>,
{
    #[inline]
    fn ball_ball(
        &self,
        a: usize,
        b: usize,
        nu: &[T; N],
        state1: &BodyState<T, N, S>,
        state2: &BodyState<T, N, S>,
    ) -> [BodyState<T, N, S>; 2] {
        Generated::free(nu, &self.species[a], &self.species[b], state1, state2)
    }

    #[inline]
    fn ball_wall(
        &self,
        species: usize,
        axis: usize,
        upper: bool,
        state: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S> {
        let sign = if upper { -T::one() } else { T::one() };
        let nu = std::array::from_fn(|k| if k == axis { sign.clone() } else { T::zero() });
        Generated::fixed(
            &nu,
            &T::one(),
            &self.species[species],
            &BodyState::zero(),
            state,
        )
    }

    #[inline]
    fn ball_obstacle(
        &self,
        species: usize,
        nu: &[T; N],
        state: &BodyState<T, N, S>,
    ) -> BodyState<T, N, S> {
        Generated::fixed(
            nu,
            &T::one(),
            &self.species[species],
            &BodyState::zero(),
            state,
        )
    }
}

/// A ball of a simulation: its species, centre and velocity state.
#[derive(Clone, Debug, PartialEq)]
pub struct Body<const N: usize, const S: usize> {
    /// The index of its species in [`Setup::species`].
    pub species: usize,
    /// The centre `a`.
    pub position: [f64; N],
    /// Angular velocity `U` and centre velocity `u`.
    pub state: BodyState<f64, N, S>,
}

/// A fixed ball obstacle, at rest.
#[derive(Clone, Debug, PartialEq)]
pub struct FixedBall<const N: usize> {
    /// The centre.
    pub position: [f64; N],
    /// The radius `R`.
    pub radius: f64,
}

/// What a simulation starts from. The box is `[0, size_0] x ..`; axis `k` is periodic when
/// `periodic[k]`, else bounded by flat walls at `0` and `size_k`.
#[derive(Clone, Debug)]
pub struct Setup<const N: usize, const S: usize> {
    /// The box sides `L_k`.
    pub size: [f64; N],
    /// Per axis: periodic, or bounded by walls at `0` and `L_k`.
    pub periodic: [bool; N],
    /// Each species' parameters, by species index.
    pub species: Vec<Ball<f64>>,
    /// The fixed ball obstacles.
    pub obstacles: Vec<FixedBall<N>>,
    /// The balls.
    pub bodies: Vec<Body<N, S>>,
    /// Track orientations `A_i` (starting at the identity).
    pub orientation: bool,
    /// The table's other boundaries and the contact kinds ([`Table::boxed`] for the box
    /// alone, every contact no-slip).
    pub table: Table<N>,
}
