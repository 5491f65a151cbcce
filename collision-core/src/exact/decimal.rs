//! Decimal digits of big integers, for printing exact rationals (`collide --exact` prints a
//! dozen rationals of about a hundred digits each side of the slash).
//!
//! An integer of `k` 64-bit words `w_0 .. w_{k-1}` (little-endian) is cut into chunks of 19
//! decimal digits by repeated short division by `D = 10^19` (the largest power of ten below
//! `2^64`): one pass over the words gives the lowest chunk (the remainder) and the quotient,
//! and so on, about `k^2 / 2` two-by-one word divisions in all. Each of those divides
//! `u1 2^64 + u0` (`u1 < D`) by the invariant `D` with its precomputed reciprocal (Möller and
//! Granlund, "Improved division by invariant integers", IEEE Trans. Comput. 60 (2011),
//! Algorithm 4): two multiplications instead of a hardware division. Integers of more than
//! [`MAX_WORDS`] words (over 600 digits) go to dashu's formatter, whose conversion is
//! subquadratic.

use dashu_int::{UBig, Word};
use std::fmt;

/// `D = 10^19`: `2^63 < D < 2^64`, so `D` is already normalised (top bit set).
const D: u64 = 10_000_000_000_000_000_000;

/// The reciprocal `v = floor((2^128 - 1) / D) - 2^64` of Möller and Granlund.
const V: u64 = (u128::MAX / D as u128 - (1u128 << 64)) as u64;

/// The longest integer, in words, converted here; longer ones go to dashu.
pub const MAX_WORDS: usize = 32;

/// `(q, r)` with `u1 2^64 + u0 = q D + r`, `0 <= r < D`, for `u1 < D` (so `q < 2^64`).
#[inline]
fn div_by_d(u1: u64, u0: u64) -> (u64, u64) {
    let u = (u128::from(u1) << 64) | u128::from(u0);
    let p = u128::from(V).wrapping_mul(u128::from(u1)).wrapping_add(u);
    let (mut q1, q0) = (((p >> 64) as u64).wrapping_add(1), p as u64);
    let mut r = u0.wrapping_sub(q1.wrapping_mul(D));
    if r > q0 {
        q1 = q1.wrapping_sub(1);
        r = r.wrapping_add(D);
    }
    if r >= D {
        q1 += 1;
        r -= D;
    }
    (q1, r)
}

/// The two-digit pairs `00`, `01`, ..., `99`.
const PAIRS: &[u8; 200] = b"\
0001020304050607080910111213141516171819\
2021222324252627282930313233343536373839\
4041424344454647484950515253545556575859\
6061626364656667686970717273747576777879\
8081828384858687888990919293949596979899";

/// The 19 digits of `x < 10^19`, with leading zeros.
fn chunk_digits(mut x: u64) -> [u8; 19] {
    let mut buf = [b'0'; 19];
    let mut end = 19;
    while end > 1 {
        let pair = (x % 100) as usize * 2;
        x /= 100;
        buf[end - 2..end].copy_from_slice(&PAIRS[pair..pair + 2]);
        end -= 2;
    }
    buf[0] = b'0' + x as u8;
    buf
}

/// Write the decimal digits of the unsigned integer whose little-endian words are `words`
/// (no leading zeros; `0` for no words or only zero words).
pub fn write_words<W: fmt::Write>(words: &[Word], w: &mut W) -> fmt::Result {
    if words.len() <= 1 {
        // No word (zero) or one (most small rationals): the digits straight from a `u64`,
        // with no arrays of `MAX_WORDS` words to clear.
        #[allow(clippy::unnecessary_cast)]
        return write_word(words.first().map_or(0, |&x| x as u64), w);
    }
    if Word::BITS != 64 || words.len() > MAX_WORDS {
        return write!(w, "{}", UBig::from_words(words));
    }
    let mut x = [0u64; MAX_WORDS];
    for (xi, &wi) in x.iter_mut().zip(words) {
        // `Word` is `u64` here (checked above); the cast compiles where it is narrower.
        #[allow(clippy::unnecessary_cast)]
        {
            *xi = wi as u64;
        }
    }
    let mut len = words.len();
    while len > 0 && x[len - 1] == 0 {
        len -= 1;
    }
    // 64 k bits are at most ceil(64 k / log2(10^19)) <= k + 1 chunks of 19 digits, written
    // from the end, lowest first.
    let mut digits = [b'0'; (MAX_WORDS + 1) * 19];
    let mut start = digits.len();
    while len > 1 || (len == 1 && x[0] >= D) {
        let mut r = 0;
        for xi in x[..len].iter_mut().rev() {
            (*xi, r) = div_by_d(r, *xi);
        }
        start -= 19;
        digits[start..start + 19].copy_from_slice(&chunk_digits(r));
        while len > 0 && x[len - 1] == 0 {
            len -= 1;
        }
    }
    // What is left, below `D`, leads (unless it is 0 ahead of other chunks).
    if len == 1 || start == digits.len() {
        start -= 19;
        digits[start..start + 19].copy_from_slice(&chunk_digits(x[0]));
    }
    let first = digits[start..]
        .iter()
        .position(|&d| d != b'0')
        .map_or(digits.len() - 1, |k| start + k);
    // The digits are ASCII: always UTF-8.
    w.write_str(std::str::from_utf8(&digits[first..]).map_err(|_| fmt::Error)?)
}

/// The decimal digits of `x` (no leading zeros; `0` for 0), two at a time from the end.
fn write_word<W: fmt::Write>(mut x: u64, w: &mut W) -> fmt::Result {
    let mut buf = [0u8; 20];
    let mut start = buf.len();
    while x >= 10 {
        let pair = (x % 100) as usize * 2;
        x /= 100;
        start -= 2;
        buf[start..start + 2].copy_from_slice(&PAIRS[pair..pair + 2]);
    }
    // The leading digit, unless the last pair (10 to 99) led already.
    if x > 0 || start == buf.len() {
        start -= 1;
        buf[start] = b'0' + x as u8;
    }
    // The digits are ASCII: always UTF-8.
    w.write_str(std::str::from_utf8(&buf[start..]).map_err(|_| fmt::Error)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    #[test]
    fn division_by_ten_to_the_19_matches_u128_division() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let edges = [0, 1, D - 1, D, D + 1, u64::MAX, 1 << 63, (1 << 63) - 1];
        let check = |u1: u64, u0: u64| {
            let u = (u128::from(u1) << 64) | u128::from(u0);
            let want = ((u / u128::from(D)) as u64, (u % u128::from(D)) as u64);
            assert_eq!(div_by_d(u1, u0), want, "{u1} {u0}");
        };
        for &u1 in &edges[..3] {
            for &u0 in &edges {
                check(u1, u0);
            }
        }
        for _ in 0..100_000 {
            check(rng.random_range(0..D), rng.random());
        }
    }

    /// Every length up to past [`MAX_WORDS`], powers of ten and their neighbours (where a
    /// chunk is all zeros or all nines), and random words: the same digits as dashu's.
    #[test]
    fn digits_match_dashu() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let mut cases: Vec<UBig> = vec![UBig::ZERO, UBig::ONE, UBig::from(D), UBig::from(D - 1)];
        for k in 0..700u32 {
            let p = UBig::from(10u8).pow(k as usize);
            cases.extend([
                &p - UBig::ONE,
                p.clone(),
                &p + UBig::ONE,
                &p * UBig::from(D),
            ]);
        }
        for len in 1..=MAX_WORDS + 3 {
            for _ in 0..20 {
                let words: Vec<Word> = (0..len).map(|_| rng.random()).collect();
                cases.push(UBig::from_words(&words));
            }
        }
        for x in cases {
            let mut s = String::new();
            write_words(x.as_words(), &mut s).unwrap();
            assert_eq!(s, x.to_string());
        }
    }
}
