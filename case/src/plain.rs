//! The plain shape of a case, read from the text in one pass with no tree: the reader of
//! the direct path ([`crate::direct`]).
//!
//! A plain case is one JSON object with the keys `dim`, `normal` and `bodies` (each once,
//! in any order, no `contact`); `dim` a JSON integer literal; `bodies` an array of two
//! objects with the keys `mass`, `radius`, `angular_velocity` and `velocity` and at most one
//! of `lambda` and `gamma2` (no `distribution`); every angular velocity a matrix (an array
//! of rows); every number a JSON number or a string that the short reader
//! ([`crate::short`]) reads: at most 18 digits per integer, no exponent, read into a
//! [`Fraction`]; a mass may also be the string `"inf"`. Vectors and rows hold at most
//! [`MOST`] numbers; strings hold no escape (the pieces of [`crate::text`]'s reader).
//!
//! [`read`] answers `None` for anything else (another shape, invalid JSON, a key given twice,
//! a longer number): the caller then reads the text the general way, which reports every
//! error. It checks no length against `dim`: [`crate::direct`] does.

use crate::fraction::Fraction;
use crate::short;
use crate::text::Parser;

/// The most numbers in a vector or a row, and rows in a matrix: the largest `dim` with
/// generated kernels.
pub(crate) const MOST: usize = 6;

/// Up to [`MOST`] numbers.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Numbers {
    /// How many were given.
    pub len: usize,
    /// The numbers, `len` of them used.
    pub x: [Fraction; MOST],
}

impl Numbers {
    /// The numbers given.
    pub(crate) fn as_slice(&self) -> &[Fraction] {
        &self.x[..self.len]
    }
}

/// How a plain body's inertia is given.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Inertia {
    /// Neither `lambda` nor `gamma2`: uniform density.
    Uniform,
    /// `lambda`.
    Lambda(Fraction),
    /// `gamma2`.
    Gamma2(Fraction),
}

/// One body of a plain case.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Body {
    /// `mass`; `None` for `"inf"`.
    pub mass: Option<Fraction>,
    /// `radius`.
    pub radius: Fraction,
    /// `lambda`, `gamma2` or neither.
    pub inertia: Inertia,
    /// The rows of `angular_velocity`, `rows` of them used.
    pub spin: [Numbers; MOST],
    /// How many rows were given.
    pub rows: usize,
    /// `velocity`.
    pub velocity: Numbers,
}

/// A plain case as given.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Plain {
    /// `dim`.
    pub dim: usize,
    /// `normal`.
    pub normal: Numbers,
    /// `bodies`.
    pub bodies: [Body; 2],
}

/// `text` as a plain case, if it is one (see the module documentation).
pub(crate) fn read(text: &str) -> Option<Plain> {
    let mut p = Parser::new(text);
    let (mut dim, mut normal, mut bodies) = (None, None, None);
    object(&mut p, |p, key| match key {
        "dim" if dim.is_none() => {
            dim = Some(integer(p)?);
            Some(())
        }
        "normal" if normal.is_none() => {
            normal = Some(numbers(p)?);
            Some(())
        }
        "bodies" if bodies.is_none() => {
            p.expect(b'[')?;
            let first = body(p)?;
            p.expect(b',')?;
            let second = body(p)?;
            p.expect(b']')?;
            bodies = Some([first, second]);
            Some(())
        }
        _ => None,
    })?;
    p.end()?;
    Some(Plain {
        dim: dim?,
        normal: normal?,
        bodies: bodies?,
    })
}

/// An object here, each member's value read by `member(p, key)` (which declines a key it
/// does not know or has seen).
fn object<'a>(
    p: &mut Parser<'a>,
    mut member: impl FnMut(&mut Parser<'a>, &'a str) -> Option<()>,
) -> Option<()> {
    p.expect(b'{')?;
    loop {
        p.skip_whitespace();
        if p.peek()? != b'"' {
            return None;
        }
        let key = p.string()?;
        p.expect(b':')?;
        member(p, key)?;
        p.skip_whitespace();
        match p.peek()? {
            b',' => p.skip(),
            b'}' => {
                p.skip();
                return Some(());
            }
            _ => return None,
        }
    }
}

/// A JSON integer literal (`dim`), at most 2 digits.
fn integer(p: &mut Parser<'_>) -> Option<usize> {
    p.skip_whitespace();
    let text = p.number()?;
    if text.len() > 2 || !text.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    text.parse().ok()
}

/// A number: a JSON number or a string, read by the short reader.
fn number(p: &mut Parser<'_>) -> Option<Fraction> {
    p.skip_whitespace();
    match p.peek()? {
        b'"' => short::fraction(p.string()?),
        _ => short::fraction(p.number()?),
    }
}

/// An array of up to [`MOST`] items read by `item`, into `out`; their count.
fn array<'a, T>(
    p: &mut Parser<'a>,
    out: &mut [T; MOST],
    mut item: impl FnMut(&mut Parser<'a>) -> Option<T>,
) -> Option<usize> {
    p.expect(b'[')?;
    p.skip_whitespace();
    if p.peek()? == b']' {
        p.skip();
        return Some(0);
    }
    let mut len = 0;
    loop {
        *out.get_mut(len)? = item(p)?;
        len += 1;
        p.skip_whitespace();
        match p.peek()? {
            b',' => p.skip(),
            b']' => {
                p.skip();
                return Some(len);
            }
            _ => return None,
        }
    }
}

/// An array of up to [`MOST`] numbers.
fn numbers(p: &mut Parser<'_>) -> Option<Numbers> {
    let mut out = Numbers::default();
    out.len = array(p, &mut out.x, number)?;
    Some(out)
}

/// A body.
fn body(p: &mut Parser<'_>) -> Option<Body> {
    let (mut mass, mut radius, mut inertia) = (None, None, None);
    let (mut spin, mut velocity) = (None, None);
    object(p, |p, key| {
        match key {
            "mass" if mass.is_none() => {
                p.skip_whitespace();
                mass = Some(if p.peek()? == b'"' {
                    match p.string()? {
                        "inf" => None,
                        s => Some(short::fraction(s)?),
                    }
                } else {
                    Some(short::fraction(p.number()?)?)
                });
            }
            "radius" if radius.is_none() => radius = Some(number(p)?),
            "lambda" if inertia.is_none() => inertia = Some(Inertia::Lambda(number(p)?)),
            "gamma2" if inertia.is_none() => inertia = Some(Inertia::Gamma2(number(p)?)),
            "angular_velocity" if spin.is_none() => {
                let mut rows = [Numbers::default(); MOST];
                // A matrix: an array of rows (the 2D scalar and 3D omega forms decline).
                let n = array(p, &mut rows, |p| {
                    p.skip_whitespace();
                    if p.peek()? != b'[' {
                        return None;
                    }
                    numbers(p)
                })?;
                spin = Some((rows, n));
            }
            "velocity" if velocity.is_none() => velocity = Some(numbers(p)?),
            _ => return None,
        }
        Some(())
    })?;
    let (spin, rows) = spin?;
    Some(Body {
        mass: mass?,
        radius: radius?,
        inertia: inertia.unwrap_or(Inertia::Uniform),
        spin,
        rows,
        velocity: velocity?,
    })
}
