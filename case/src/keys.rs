//! Repeated keys. serde_json's `Value` keeps the last of an object's repeated keys, silently;
//! this second pass over the same text sees every key and finds the first one given twice.

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use std::cell::RefCell;
use std::collections::HashSet;
use std::fmt;

/// One step of a path into a JSON value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PathStep {
    /// An index into an array.
    Index(usize),
    /// A key of an object.
    Key(String),
}

/// The path of the first key that appears twice in one object of `text` (which must be
/// valid JSON), ending with that key; `None` if every object's keys are distinct.
pub fn first_repeated_key(text: &str) -> Option<Vec<PathStep>> {
    let found = RefCell::new(None);
    let walk = Walk {
        path: Vec::new(),
        found: &found,
    };
    // The walk stops with an error at the repeated key; any other error is the parser's,
    // which the caller has already reported.
    let _ = walk.deserialize(&mut serde_json::Deserializer::from_str(text));
    found.into_inner()
}

struct Walk<'a> {
    path: Vec<PathStep>,
    found: &'a RefCell<Option<Vec<PathStep>>>,
}

impl<'a> Walk<'a> {
    fn child(&self, step: PathStep) -> Walk<'a> {
        let mut path = self.path.clone();
        path.push(step);
        Walk {
            path,
            found: self.found,
        }
    }
}

impl<'de> DeserializeSeed<'de> for Walk<'_> {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Walk<'_> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E: de::Error>(self, _: bool) -> Result<(), E> {
        Ok(())
    }
    fn visit_i64<E: de::Error>(self, _: i64) -> Result<(), E> {
        Ok(())
    }
    fn visit_u64<E: de::Error>(self, _: u64) -> Result<(), E> {
        Ok(())
    }
    fn visit_f64<E: de::Error>(self, _: f64) -> Result<(), E> {
        Ok(())
    }
    fn visit_str<E: de::Error>(self, _: &str) -> Result<(), E> {
        Ok(())
    }
    fn visit_unit<E: de::Error>(self) -> Result<(), E> {
        Ok(())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let mut i = 0;
        while seq
            .next_element_seed(self.child(PathStep::Index(i)))?
            .is_some()
        {
            i += 1;
        }
        Ok(())
    }

    /// (With serde_json's `arbitrary_precision`, a number also arrives as a one-key map.)
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let mut seen = HashSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                let mut path = self.path.clone();
                path.push(PathStep::Key(key));
                *self.found.borrow_mut() = Some(path);
                return Err(de::Error::custom("repeated key"));
            }
            map.next_value_seed(self.child(PathStep::Key(key)))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(k: &str) -> PathStep {
        PathStep::Key(k.into())
    }

    #[test]
    fn the_first_repeated_key_is_found_with_its_path() {
        assert_eq!(
            first_repeated_key(r#"{"a": 1, "b": [1, 2.5e3, "x"]}"#),
            None
        );
        assert_eq!(
            first_repeated_key(r#"{"a": 1, "a": 2}"#),
            Some(vec![key("a")])
        );
        assert_eq!(
            first_repeated_key(r#"[{}, {"b": [{"m": 1, "r": 2, "m": 3}]}]"#),
            Some(vec![
                PathStep::Index(1),
                key("b"),
                PathStep::Index(0),
                key("m")
            ])
        );
        // The same key in different objects is fine; numbers of any form are no keys.
        assert_eq!(
            first_repeated_key(r#"[{"m": 1e999}, {"m": -0.1}, {"m": {"m": 1}}]"#),
            None
        );
        // Escapes are decoded before comparing: "a" and "\u0061" are the same key.
        assert_eq!(
            first_repeated_key(r#"{"a": 1, "\u0061": 2}"#),
            Some(vec![key("a")])
        );
    }
}
