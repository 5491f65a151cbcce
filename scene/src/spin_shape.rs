//! [`RawSpin`] read by its shape: a number (2D `c`), a list of numbers (3D `omega`) or a
//! list of rows (the `n x n` matrix). An untagged enum would report only that no variant
//! matched ("data did not match any variant of untagged enum RawSpin"); this reader reports
//! the entry's own error ("must be finite, got NaN", "not a number: ...").

use crate::number::{Number, NumberVisitor};
use crate::raw::RawSpin;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use std::fmt;

/// What a spin is, for a message about a value of another kind.
const EXPECTING: &str = "a number (2D: c), a list of 3 numbers (3D: omega) or the n x n skew \
                         matrix as a list of rows";

/// The visitor methods of a number (`NumberVisitor`'s), their value wrapped by `$wrap`.
macro_rules! numbers_as {
    ($wrap:path) => {
        fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
            NumberVisitor.visit_i64(v).map($wrap)
        }

        fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
            NumberVisitor.visit_u64(v).map($wrap)
        }

        fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
            NumberVisitor.visit_f64(v).map($wrap)
        }

        fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
            NumberVisitor.visit_str(v).map($wrap)
        }
    };
}

impl<'de> Deserialize<'de> for RawSpin {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(SpinVisitor)
    }
}

struct SpinVisitor;

impl<'de> Visitor<'de> for SpinVisitor {
    type Value = RawSpin;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(EXPECTING)
    }

    numbers_as!(RawSpin::Scalar);

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RawSpin, A::Error> {
        let (mut numbers, mut rows) = (Vec::new(), Vec::new());
        while let Some(entry) = seq.next_element::<Entry>()? {
            match entry {
                Entry::Number(x) => numbers.push(x),
                Entry::Row(r) => rows.push(r),
            }
        }
        match (numbers.is_empty(), rows.is_empty()) {
            (_, true) => Ok(RawSpin::Vector(numbers)),
            (true, false) => Ok(RawSpin::Matrix(rows)),
            (false, false) => Err(de::Error::custom(format!(
                "mixes numbers and rows: expected {EXPECTING}"
            ))),
        }
    }
}

/// An entry of a spin's list: a number (of `omega`) or a row (of the matrix).
enum Entry {
    Number(Number),
    Row(Vec<Number>),
}

impl<'de> Deserialize<'de> for Entry {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(EntryVisitor)
    }
}

struct EntryVisitor;

impl<'de> Visitor<'de> for EntryVisitor {
    type Value = Entry;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number (of omega) or a row of numbers (of the matrix)")
    }

    numbers_as!(Entry::Number);

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Entry, A::Error> {
        let mut row = Vec::new();
        while let Some(x) = seq.next_element::<Number>()? {
            row.push(x);
        }
        Ok(Entry::Row(row))
    }
}

#[cfg(test)]
mod tests {
    use crate::raw::RawSpin;

    /// The spin of a one-key TOML table, or its error's message.
    fn spin(text: &str) -> Result<RawSpin, String> {
        #[derive(serde::Deserialize)]
        struct T {
            angular_velocity: RawSpin,
        }
        toml::from_str::<T>(&format!("angular_velocity = {text}"))
            .map(|t| t.angular_velocity)
            .map_err(|e| e.message().to_string())
    }

    #[test]
    fn every_shape_is_read() {
        assert!(matches!(spin("1.5"), Ok(RawSpin::Scalar(_))));
        assert!(matches!(spin("\"3/5\""), Ok(RawSpin::Scalar(_))));
        assert!(matches!(spin("[1, 2, \"1/3\"]"), Ok(RawSpin::Vector(v)) if v.len() == 3));
        assert!(matches!(spin("[]"), Ok(RawSpin::Vector(v)) if v.is_empty()));
        assert!(matches!(
            spin("[[0, 1], [-1, 0]]"),
            Ok(RawSpin::Matrix(m)) if m.len() == 2 && m.iter().all(|r| r.len() == 2)
        ));
    }

    #[test]
    fn a_bad_entry_is_reported_as_itself() {
        for (text, said) in [
            ("nan", "must be finite, got NaN"),
            ("inf", "must be finite, got inf"),
            ("\"x\"", "not a number: \"x\""),
            ("[nan, 0, 0]", "must be finite, got NaN"),
            ("[[0, nan], [nan, 0]]", "must be finite, got NaN"),
            ("true", "expected a number (2D: c), a list of 3 numbers"),
            ("{}", "expected a number (2D: c), a list of 3 numbers"),
            ("[[0, 1], 2]", "mixes numbers and rows"),
            ("[true]", "expected a number (of omega) or a row"),
        ] {
            let err = spin(text)
                .err()
                .unwrap_or_else(|| panic!("{text} accepted"));
            assert!(err.contains(said), "{text}: {err}");
            assert!(!err.contains("untagged"), "{text}: {err}");
        }
    }
}
