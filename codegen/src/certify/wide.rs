//! `f32` companions with the bound computed in `f64` ([`super::Format::F32Wide`]):
//! `kernels::dN::certified::{free_f32_wide, fixed_f32_wide}` (running error analysis).
//!
//! The kernel runs in `f32` as the plain `f32` kernel (its values bit for bit); the bound's
//! statements read its values widened to `f64` (exact) and run in `f64`. The rules of
//! [`super`] are unchanged with the kernel's `u = 2^-24`: every rounding of the kernel is
//! at most `u m_z`, `m_z >= s`, now with `s = 2^-126`, since `u s = 2^-150` is the `f32`
//! subnormal half-spacing. The proof of the bound's own arithmetic needs each of its
//! operations to lose at most a factor `1 - 2u`: in `f64` one loses at most `1 - 2^-53`
//! in the normal range; every product `m e >= s u s = 2^-276` is normal in `f64`, and a
//! quotient's underflow (`2^-1075` at most) is far below `2^-75` of the rule's value
//! (`u m_z >= 2^-150`). So the same inflation `F(d)` (with `u = 2^-24`, generous here)
//! makes the bound rigorous. What changes: no overflow of the bound below `1.8e308` (the
//! `f32` companions overflow where products of magnitudes pass `3.4e38`), and outputs down
//! to `1e-38` keep a relative bound (the `f32` companions' floor `2^-51` swamps outputs
//! below about `1e-15`). The bounds are returned as `f64`.
