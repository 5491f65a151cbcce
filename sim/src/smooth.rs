//! The smooth (specular) contact maps, from collision-core ([`collision_core::smooth`]):
//! the normal component of the relative velocity reverses (or is restituted by `e`),
//! tangential velocities and spins are untouched.

pub use collision_core::smooth::{fixed, pair, pair_restituted};
