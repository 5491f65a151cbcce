//! Which input to blame when a result does not fit the format, and how to say it.

use super::{max_abs, Prepared};
use crate::error::{BodyField, Field, InputError};
use crate::Scalar;
use num_traits::{One, Signed};

/// Which input sets the speed scale of the contact: the largest of `|u_i|` and `R_i |U_i|`
/// (entries' magnitudes), with the input field to blame and how to say it.
pub(super) fn speed_source<W: Scalar>(p: &Prepared<W>) -> (W, Field, String) {
    let mut best: Option<(W, Field, String)> = None;
    for b in 0..2 {
        let u = max_abs(&p.velocities[b]);
        let r = p.balls[b].radius.clone();
        let spin = r.clone() * max_abs(&p.spins[b]);
        let candidates = [
            (
                u,
                Field::Body(b, BodyField::Velocity),
                "the speed".to_string(),
            ),
            (
                spin,
                Field::Body(b, BodyField::AngularVelocity),
                format!(
                    "with body {}'s radius R = {}, the contact-point speed R |U|",
                    b + 1,
                    r.show()
                ),
            ),
        ];
        for c in candidates {
            if best.as_ref().is_none_or(|(v, _, _)| c.0 > *v) {
                best = Some(c);
            }
        }
    }
    best.unwrap_or_else(|| unreachable!("two bodies"))
}

/// The error for a result of body `b` (`spin` or velocity) beyond the range of `T`, naming the
/// input at fault: the velocity results are bounded by a few times the speed scale `V` (see
/// [`speed_source`]), so its source is named; the angular ones by `V / R_b`, so the radius is
/// named when it brings more of the magnitude (`R_b V < 1`), else the source of `V`.
pub(super) fn overflow<T: Scalar>(
    p: &Prepared<T::Unbounded>,
    b: usize,
    spin: bool,
    value: &T::Unbounded,
) -> InputError {
    let (speed, field, what) = speed_source(p);
    let tail = format!(
        "overflow {} (about {}); exact arithmetic computes it",
        T::NAME,
        value.show()
    );
    if !spin {
        return InputError::new(
            field,
            format!(
                "{what} up to {} makes body {}'s velocity after contact {tail}",
                speed.show(),
                b + 1
            ),
        );
    }
    let radius = p.balls[b].radius.clone();
    let rate = speed.clone() / radius.clone();
    if radius.clone() * speed.clone() < T::Unbounded::one() {
        return InputError::new(
            Field::Body(b, BodyField::Radius),
            format!(
                "{} is so small that the contact-point speed, up to {}, spins the body at up to \
                 {}: its angular velocity after contact would {tail}",
                radius.show(),
                speed.show(),
                rate.show()
            ),
        );
    }
    InputError::new(
        field,
        format!(
            "{what} up to {}, over body {}'s radius {}, spins it at up to {}: its angular \
             velocity after contact would {tail}",
            speed.show(),
            b + 1,
            radius.show(),
            rate.show()
        ),
    )
}

/// The result component of a body whose rounding to `T` costs the most of the body's energy
/// norm `sqrt(gamma2 R^2 sum U_ij^2 + |u|^2)` (so it lies below the normal range of `T`).
#[derive(Clone, Debug)]
pub(super) struct Lost<W> {
    /// The component after contact, in the unbounded arithmetic.
    pub value: W,
    /// An entry of the angular velocity `U` (else of the velocity `u`).
    pub spin: bool,
    /// The largest component of the body's velocity after contact.
    pub speed: W,
}

/// The error for a body whose result would lose more than the rounding allowance of its
/// energy norm in `T`: its `lost` component lies below the normal range. The input named:
///
/// - the body's mass, when it is over `2^64` times the other's (the impulse's share of its
///   change is suppressed by the mass ratio);
/// - for an angular velocity, whose size is about `V / R_b` (`V` the speed scale, see
///   [`speed_source`]): the radius when it brings more of the smallness (`R_b V > 1`), else
///   the source of `V`;
/// - for a velocity: the source of `V`;
/// - the body's own velocity or angular velocity, when the lost component lies below the
///   rounding of `V` itself (the contact, not the scale, made it small).
pub(super) fn underflow<T: Scalar>(
    p: &Prepared<T::Unbounded>,
    b: usize,
    lost: &Lost<T::Unbounded>,
) -> InputError {
    let radius = p.balls[b].radius.clone();
    let part = if lost.spin {
        format!(
            "body {}'s angular velocity after contact has an entry of about {}, below the \
             normal range of {}, yet it carries a contact-point speed R |U| of about {} (the \
             body's velocity after contact is about {})",
            b + 1,
            lost.value.show(),
            T::NAME,
            (radius.clone() * lost.value.clone()).abs().show(),
            lost.speed.show(),
        )
    } else {
        format!(
            "body {}'s velocity after contact (about {}) is below the normal range of {}",
            b + 1,
            lost.value.show(),
            T::NAME,
        )
    };
    let tail = format!(
        "{part}: rounded to {} it would lose more than the rounding allowance of the body's \
         energy norm; exact arithmetic computes it",
        T::NAME
    );
    // A 2^-64 share of the impulse: the mass ratio suppresses the body's change.
    let other = p.balls[1 - b].inv_mass.clone();
    let own = p.balls[b].inv_mass.clone();
    let ratio = T::Unbounded::from_ratio(1, 1 << 32);
    if own < other * ratio.clone() * ratio {
        return InputError::new(
            Field::Body(b, BodyField::Mass),
            format!("the body is so much heavier than the other that {tail}"),
        );
    }
    let (speed, field, what) = speed_source(p);
    if lost.spin && radius.clone() * speed.clone() > T::Unbounded::one() {
        return InputError::new(
            Field::Body(b, BodyField::Radius),
            format!(
                "{} is so large that, with the contact-point speed up to {}, {tail}",
                radius.show(),
                speed.show()
            ),
        );
    }
    // A result far below the speed scale (beneath its rounding) is not made small by the
    // scale: the contact leaves the body little of the motion (an equal partner takes its
    // normal velocity, and what stays is a component far below the rest).
    if lost.value.clone().abs() < speed.clone() * T::rounding_slack().unbounded() {
        let part = if lost.spin {
            BodyField::AngularVelocity
        } else {
            BodyField::Velocity
        };
        return InputError::new(
            Field::Body(b, part),
            format!(
                "the contact leaves body {} with motion far below its speed scale \
                 ({what}, up to {}): {tail}",
                b + 1,
                speed.show()
            ),
        );
    }
    InputError::new(
        field,
        format!("{what}, up to {}, is so small that {tail}", speed.show()),
    )
}
