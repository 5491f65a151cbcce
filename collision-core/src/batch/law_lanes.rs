//! A law of the rough-ball family per contact in the blocked layout: the lanes of `e` and
//! `beta` ([`RestitutionLanes`]) or of `e`, `mu` and `beta0` ([`WaltonLanes`]), carried by
//! each block beside its contacts ([`WithLaw`]), for the `_each` batch kernels
//! (`rough_free_each`, ...: lane `l` runs `kernels::dN::rough::free` under its own law
//! `(e_l, beta_l)`).

use super::lanes::{FixedLanes, FreeLanes, Lane, Lanes, Lanewise};
use crate::{Restitution, Walton};

/// The laws `(e, beta)` of a block's contacts: lane `l` is contact `l`'s [`Restitution`].
#[derive(Clone, Debug, PartialEq)]
pub struct RestitutionLanes<T> {
    /// Normal restitutions `e`.
    pub e: Lanes<T>,
    /// Tangential restitutions `beta`.
    pub beta: Lanes<T>,
}

/// The Walton laws `(e, mu, beta0)` of a block's contacts: lane `l` is contact `l`'s [`Walton`].
#[derive(Clone, Debug, PartialEq)]
pub struct WaltonLanes<T> {
    /// Normal restitutions `e`.
    pub e: Lanes<T>,
    /// Friction coefficients `mu`.
    pub mu: Lanes<T>,
    /// Sticking tangential restitutions `beta0`.
    pub beta0: Lanes<T>,
}

/// A block `B` of contacts with the lanes `L` of their laws: the input block of the `_each`
/// kernels. Cache-line aligned as every block ([`super::BLOCK_ALIGN`]); the law lanes follow
/// the contacts, so a block of `f64` is whole cache lines (2 or 3 more than `B`).
#[derive(Clone, Debug, PartialEq)]
#[repr(align(64))]
pub struct WithLaw<B, L> {
    /// The contacts (and their balls).
    pub block: B,
    /// Their laws, lane by lane.
    pub law: L,
}

/// A law of the family and its lanes: [`Restitution`] in [`RestitutionLanes`], [`Walton`]
/// in [`WaltonLanes`].
pub trait FamilyLaw: Sized {
    /// The lanes of a block's laws.
    type Lanes: Lanewise<Item = Self> + Clone + Send + Sync;
}

impl<T: Clone + Send + Sync> FamilyLaw for Restitution<T> {
    type Lanes = RestitutionLanes<T>;
}

impl<T: Clone + Send + Sync> FamilyLaw for Walton<T> {
    type Lanes = WaltonLanes<T>;
}

impl<T: Clone> Lanewise for RestitutionLanes<T> {
    type Item = Restitution<T>;
    fn splat(r: &Restitution<T>) -> Self {
        RestitutionLanes {
            e: std::array::from_fn(|_| r.e.clone()),
            beta: std::array::from_fn(|_| r.beta.clone()),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Restitution<T> {
        Restitution {
            e: self.e[l.index()].clone(),
            beta: self.beta[l.index()].clone(),
        }
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, r: Restitution<T>) {
        self.e[l.index()] = r.e;
        self.beta[l.index()] = r.beta;
    }
}

impl<T: Clone> Lanewise for WaltonLanes<T> {
    type Item = Walton<T>;
    fn splat(w: &Walton<T>) -> Self {
        WaltonLanes {
            e: std::array::from_fn(|_| w.e.clone()),
            mu: std::array::from_fn(|_| w.mu.clone()),
            beta0: std::array::from_fn(|_| w.beta0.clone()),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Walton<T> {
        Walton {
            e: self.e[l.index()].clone(),
            mu: self.mu[l.index()].clone(),
            beta0: self.beta0[l.index()].clone(),
        }
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, w: Walton<T>) {
        self.e[l.index()] = w.e;
        self.mu[l.index()] = w.mu;
        self.beta0[l.index()] = w.beta0;
    }
}

impl<B: Lanewise, L: Lanewise> Lanewise for WithLaw<B, L> {
    type Item = (B::Item, L::Item);
    fn splat((item, law): &Self::Item) -> Self {
        WithLaw {
            block: B::splat(item),
            law: L::splat(law),
        }
    }
    #[inline(always)]
    fn lane(&self, l: Lane) -> Self::Item {
        (self.block.lane(l), self.law.lane(l))
    }
    #[inline(always)]
    fn set_lane(&mut self, l: Lane, (item, law): Self::Item) {
        self.block.set_lane(l, item);
        self.law.set_lane(l, law);
    }
}

impl<T, const N: usize, const S: usize> AsMut<FreeLanes<T, N, S>> for FreeLanes<T, N, S> {
    fn as_mut(&mut self) -> &mut FreeLanes<T, N, S> {
        self
    }
}

impl<T, const N: usize, const S: usize, L> AsMut<FreeLanes<T, N, S>>
    for WithLaw<FreeLanes<T, N, S>, L>
{
    fn as_mut(&mut self) -> &mut FreeLanes<T, N, S> {
        &mut self.block
    }
}

impl<T, const N: usize, const S: usize> AsMut<FixedLanes<T, N, S>> for FixedLanes<T, N, S> {
    fn as_mut(&mut self) -> &mut FixedLanes<T, N, S> {
        self
    }
}

impl<T, const N: usize, const S: usize, L> AsMut<FixedLanes<T, N, S>>
    for WithLaw<FixedLanes<T, N, S>, L>
{
    fn as_mut(&mut self) -> &mut FixedLanes<T, N, S> {
        &mut self.block
    }
}
