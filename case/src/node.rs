//! What the reading of a case needs of a JSON value, so that one reader ([`crate::case`])
//! serves both trees it is read from: serde_json's [`Value`] (every input, and every error
//! message) and the borrowed tree of [`crate::text`] (the fast path of inputs it can read).

use serde_json::{Map, Value};

/// A JSON value: its type, and its parts.
pub trait Node: Sized {
    /// The object type: its members by key.
    type Object: Members<Self> + ?Sized;
    /// The JSON type, for messages: `"null"`, `"a boolean"`, `"a number"`, `"a string"`,
    /// `"an array"`, `"an object"`.
    fn kind(&self) -> &'static str;
    /// The members of an object.
    fn as_object(&self) -> Option<&Self::Object>;
    /// The items of an array.
    fn as_array(&self) -> Option<&[Self]>;
    /// The text of a JSON number (as serde_json's `arbitrary_precision` keeps it).
    fn as_number(&self) -> Option<&str>;
    /// The contents of a string.
    fn as_str(&self) -> Option<&str>;
    /// Whether the value is an array.
    fn is_array(&self) -> bool {
        self.as_array().is_some()
    }
    /// Whether the value is a JSON number.
    fn is_number(&self) -> bool {
        self.as_number().is_some()
    }
}

/// The members of an object (its keys are distinct).
pub trait Members<V> {
    /// The value of `key`.
    fn get(&self, key: &str) -> Option<&V>;
    /// Whether `key` is given.
    fn contains_key(&self, key: &str) -> bool {
        self.get(key).is_some()
    }
    /// The first key that is not one of `known` (serde_json's objects: in key order).
    fn unknown_key(&self, known: &[&str]) -> Option<&str>;
}

impl Node for Value {
    type Object = Map<String, Value>;
    fn kind(&self) -> &'static str {
        crate::error::kind(self)
    }
    fn as_object(&self) -> Option<&Map<String, Value>> {
        Value::as_object(self)
    }
    fn as_array(&self) -> Option<&[Self]> {
        Value::as_array(self).map(Vec::as_slice)
    }
    fn as_number(&self) -> Option<&str> {
        match self {
            Value::Number(n) => Some(n.as_str()),
            _ => None,
        }
    }
    fn as_str(&self) -> Option<&str> {
        Value::as_str(self)
    }
}

impl Members<Value> for Map<String, Value> {
    fn get(&self, key: &str) -> Option<&Value> {
        Map::get(self, key)
    }
    fn unknown_key(&self, known: &[&str]) -> Option<&str> {
        self.keys().map(String::as_str).find(|k| !known.contains(k))
    }
}
