//! Repeated keys. serde_json's `Value` keeps the last of an object's repeated keys, silently;
//! this second pass over the same text sees every key and finds the first one given twice.

use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::Value;
use std::borrow::Cow;
use std::cell::RefCell;
use std::fmt;

/// One step of a path into a JSON value.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PathStep {
    /// An index into an array.
    Index(usize),
    /// A key of an object.
    Key(String),
}

/// Whether `value`, read from `text` (valid JSON), kept every key of `text`: each `:` outside
/// the strings of valid JSON separates a key from its value, so the text has as many keys
/// as it has such colons, and `value` (whose objects keep one entry per distinct key) lost a
/// key exactly when it holds fewer entries. A quick test before [`first_repeated_key`]: one
/// pass over the bytes, no parsing.
pub fn has_every_key(text: &str, value: &Value) -> bool {
    fn entries(v: &Value) -> usize {
        match v {
            Value::Object(map) => map.len() + map.values().map(entries).sum::<usize>(),
            Value::Array(items) => items.iter().map(entries).sum(),
            _ => 0,
        }
    }
    let (mut colons, mut in_string, mut escaped) = (0usize, false, false);
    for b in text.bytes() {
        if in_string {
            match (escaped, b) {
                (true, _) => escaped = false,
                (false, b'\\') => escaped = true,
                (false, b'"') => in_string = false,
                _ => {}
            }
        } else if b == b'"' {
            in_string = true;
        } else if b == b':' {
            colons += 1;
        }
    }
    colons == entries(value)
}

/// The path of the first key that appears twice in one object of `text` (which must be
/// valid JSON), ending with that key; `None` if every object's keys are distinct.
pub fn first_repeated_key(text: &str) -> Option<Vec<PathStep>> {
    let path = RefCell::new(Vec::new());
    let found = RefCell::new(None);
    let walk = Walk {
        path: &path,
        found: &found,
    };
    // The walk stops with an error at the repeated key; any other error is the parser's,
    // which the caller has already reported.
    let _ = walk.deserialize(&mut serde_json::Deserializer::from_str(text));
    found.into_inner()
}

/// The walk over one value: `path` is the path to it (one stack for the whole walk, each
/// step pushed while its value is walked), `found` the answer.
#[derive(Clone, Copy)]
struct Walk<'a> {
    path: &'a RefCell<Vec<PathStep>>,
    found: &'a RefCell<Option<Vec<PathStep>>>,
}

/// A key as the text gives it: borrowed unless it holds escapes.
struct Key<'de>(Cow<'de, str>);

impl<'de> de::Deserialize<'de> for Key<'de> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct KeyVisitor;
        impl<'de> Visitor<'de> for KeyVisitor {
            type Value = Key<'de>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a key")
            }
            fn visit_borrowed_str<E: de::Error>(self, k: &'de str) -> Result<Key<'de>, E> {
                Ok(Key(Cow::Borrowed(k)))
            }
            fn visit_str<E: de::Error>(self, k: &str) -> Result<Key<'de>, E> {
                Ok(Key(Cow::Owned(k.to_string())))
            }
        }
        d.deserialize_str(KeyVisitor)
    }
}

impl<'a> Walk<'a> {
    /// Walk the next value of `walk` (an element or a map value) with `step` on the path.
    fn step<T, E>(
        self,
        step: PathStep,
        walk: impl FnOnce(Walk<'a>) -> Result<T, E>,
    ) -> Result<T, E> {
        self.path.borrow_mut().push(step);
        let result = walk(self);
        if result.is_ok() {
            self.path.borrow_mut().pop();
        }
        result
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
        while self
            .step(PathStep::Index(i), |w| seq.next_element_seed(w))?
            .is_some()
        {
            i += 1;
        }
        Ok(())
    }

    /// (With serde_json's `arbitrary_precision`, a number also arrives as a one-key map.) The
    /// keys seen are compared one by one: an object of a case has at most 7.
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let mut seen: Vec<Cow<'de, str>> = Vec::new();
        while let Some(Key(key)) = map.next_key::<Key<'de>>()? {
            if seen.contains(&key) {
                let mut path = self.path.borrow().clone();
                path.push(PathStep::Key(key.into_owned()));
                *self.found.borrow_mut() = Some(path);
                return Err(de::Error::custom("repeated key"));
            }
            let step = PathStep::Key(key.to_string());
            seen.push(key);
            self.step(step, |w| map.next_value_seed(w))?;
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

    /// The quick test agrees with the walk: colons inside strings (after escaped quotes and
    /// backslashes too) are not keys, and a repeated key at any depth is a lost entry.
    #[test]
    fn every_key_is_kept_exactly_when_no_key_repeats() {
        for text in [
            r#"{"a": 1, "b": [1, 2.5e3, "x"]}"#,
            r#"{"a": 1, "a": 2}"#,
            r#"[{}, {"b": [{"m": 1, "r": 2, "m": 3}]}]"#,
            r#"[{"m": 1e999}, {"m": -0.1}, {"m": {"m": 1}}]"#,
            r#"{"a": 1, "\u0061": 2}"#,
            r#"{"a:b": "c:d", "e": "\":\\", "f\\": ":"}"#,
            r#"{"a\":": 1, "a\":": 2}"#,
            r#"{"x": {"y": {"z": 1, "z": 1}}, "w": 0}"#,
            r#"["a:b", 1, {"k": ["::", {"k": 2}]}]"#,
            r#"3"#,
        ] {
            let value: Value = serde_json::from_str(text).unwrap();
            assert_eq!(
                has_every_key(text, &value),
                first_repeated_key(text).is_none(),
                "{text}"
            );
        }
    }
}
