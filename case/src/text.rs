//! The fast path of reading an input: one pass over the text into a tree that borrows its
//! strings and numbers from the text ([`Json`]), with no `Value`, no number copied and no
//! second pass for repeated keys.
//!
//! [`parse`] reads only what it is sure of: valid JSON (RFC 8259: the four whitespace
//! bytes, `-? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?` numbers, nothing after the
//! value) whose strings hold no escape, whose objects give each key once and whose nesting
//! is at most [`MAX_DEPTH`] deep. It returns `None` for anything else, valid or not; the
//! caller then reads the input with serde_json, which reports every error as before. So on
//! the inputs it reads, the tree has the values, the keys and the structure serde_json's
//! `Value` has (a number's text is the literal, which serde_json spells with `e` and a signed
//! exponent: the same number), and on the others nothing changes.

use crate::node::{Members, Node};

/// The deepest nesting read (a case nests 5 deep in an array of cases); deeper inputs go
/// to serde_json (whose limit is 128).
pub const MAX_DEPTH: usize = 16;

/// A JSON value whose strings and number literals are slices of the text.
#[derive(Debug, PartialEq)]
pub enum Json<'a> {
    /// `null`.
    Null,
    /// `true` or `false`.
    Bool(bool),
    /// A number, its literal text.
    Number(&'a str),
    /// A string without escapes, its contents.
    String(&'a str),
    /// An array.
    Array(Vec<Json<'a>>),
    /// An object.
    Object(Object<'a>),
}

/// An object's members in the order given, their keys distinct.
#[derive(Debug, PartialEq)]
pub struct Object<'a>(Vec<(&'a str, Json<'a>)>);

/// The value `text` holds, if [`parse`] can read it (see the module documentation).
pub fn parse(text: &str) -> Option<Json<'_>> {
    let mut p = Parser::new(text);
    let value = p.value(0)?;
    p.end()?;
    Some(value)
}

/// A reader of JSON text from a position on; its pieces (whitespace, strings without
/// escapes, number literals, expected bytes) are also those of the direct path's reader
/// ([`crate::plain`]).
pub(crate) struct Parser<'a> {
    text: &'a str,
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Parser<'a> {
    /// A reader at the start of `text`.
    pub(crate) fn new(text: &'a str) -> Self {
        Parser {
            text,
            bytes: text.as_bytes(),
            at: 0,
        }
    }

    /// The next byte, not consumed.
    pub(crate) fn peek(&self) -> Option<u8> {
        self.bytes.get(self.at).copied()
    }

    /// Skip the next byte (after a [`Parser::peek`] that saw it).
    pub(crate) fn skip(&mut self) {
        self.at += 1;
    }

    pub(crate) fn skip_whitespace(&mut self) {
        while let Some(b' ' | b'\n' | b'\t' | b'\r') = self.peek() {
            self.at += 1;
        }
    }

    /// Skip whitespace, then `byte`.
    pub(crate) fn expect(&mut self, byte: u8) -> Option<()> {
        self.skip_whitespace();
        (self.peek()? == byte).then(|| self.at += 1)
    }

    /// Skip whitespace; `Some` if the text ends there.
    pub(crate) fn end(&mut self) -> Option<()> {
        self.skip_whitespace();
        (self.at == self.bytes.len()).then_some(())
    }

    fn value(&mut self, depth: usize) -> Option<Json<'a>> {
        self.skip_whitespace();
        match self.peek()? {
            b'{' if depth < MAX_DEPTH => self.object(depth + 1).map(Json::Object),
            b'[' if depth < MAX_DEPTH => self.array(depth + 1).map(Json::Array),
            b'"' => self.string().map(Json::String),
            b'-' | b'0'..=b'9' => self.number().map(Json::Number),
            b't' => self.word("true", Json::Bool(true)),
            b'f' => self.word("false", Json::Bool(false)),
            b'n' => self.word("null", Json::Null),
            _ => None,
        }
    }

    fn word(&mut self, word: &str, value: Json<'a>) -> Option<Json<'a>> {
        self.bytes[self.at..].starts_with(word.as_bytes()).then(|| {
            self.at += word.len();
            value
        })
    }

    /// A string at `"`: its contents, if they hold no escape and no control character.
    pub(crate) fn string(&mut self) -> Option<&'a str> {
        let start = self.at + 1;
        let len = self.bytes[start..]
            .iter()
            .position(|&b| b == b'"' || b == b'\\' || b < 0x20)?;
        let end = start + len;
        // Stopped at a quote: both ends are ASCII, so char boundaries.
        (self.bytes[end] == b'"').then(|| {
            self.at = end + 1;
            &self.text[start..end]
        })
    }

    /// The digits from here on; `None` if there is none.
    fn digits(&mut self) -> Option<()> {
        let start = self.at;
        while let Some(b'0'..=b'9') = self.peek() {
            self.at += 1;
        }
        (self.at > start).then_some(())
    }

    /// A number literal (RFC 8259) here: its text.
    pub(crate) fn number(&mut self) -> Option<&'a str> {
        let start = self.at;
        if self.peek() == Some(b'-') {
            self.at += 1;
        }
        match self.peek()? {
            b'0' => self.at += 1,
            b'1'..=b'9' => self.digits()?,
            _ => return None,
        }
        if self.peek() == Some(b'.') {
            self.at += 1;
            self.digits()?;
        }
        if let Some(b'e' | b'E') = self.peek() {
            self.at += 1;
            if let Some(b'+' | b'-') = self.peek() {
                self.at += 1;
            }
            self.digits()?;
        }
        Some(&self.text[start..self.at])
    }

    /// An array at `[`.
    fn array(&mut self, depth: usize) -> Option<Vec<Json<'a>>> {
        self.at += 1;
        let mut items = Vec::new();
        self.skip_whitespace();
        if self.peek()? == b']' {
            self.at += 1;
            return Some(items);
        }
        loop {
            items.push(self.value(depth)?);
            self.skip_whitespace();
            match self.peek()? {
                b',' => self.at += 1,
                b']' => {
                    self.at += 1;
                    return Some(items);
                }
                _ => return None,
            }
        }
    }

    /// An object at `{`; `None` if a key is given twice.
    fn object(&mut self, depth: usize) -> Option<Object<'a>> {
        self.at += 1;
        let mut members: Vec<(&'a str, Json<'a>)> = Vec::new();
        self.skip_whitespace();
        if self.peek()? == b'}' {
            self.at += 1;
            return Some(Object(members));
        }
        loop {
            self.skip_whitespace();
            if self.peek()? != b'"' {
                return None;
            }
            let key = self.string()?;
            if members.iter().any(|(k, _)| *k == key) {
                return None;
            }
            self.expect(b':')?;
            members.push((key, self.value(depth)?));
            self.skip_whitespace();
            match self.peek()? {
                b',' => self.at += 1,
                b'}' => {
                    self.at += 1;
                    return Some(Object(members));
                }
                _ => return None,
            }
        }
    }
}

impl<'a> Node for Json<'a> {
    type Object = Object<'a>;
    fn kind(&self) -> &'static str {
        match self {
            Json::Null => "null",
            Json::Bool(_) => "a boolean",
            Json::Number(_) => "a number",
            Json::String(_) => "a string",
            Json::Array(_) => "an array",
            Json::Object(_) => "an object",
        }
    }
    fn as_object(&self) -> Option<&Object<'a>> {
        match self {
            Json::Object(o) => Some(o),
            _ => None,
        }
    }
    fn as_array(&self) -> Option<&[Self]> {
        match self {
            Json::Array(items) => Some(items),
            _ => None,
        }
    }
    fn as_number(&self) -> Option<&str> {
        match self {
            Json::Number(n) => Some(n),
            _ => None,
        }
    }
    fn as_str(&self) -> Option<&str> {
        match self {
            Json::String(s) => Some(s),
            _ => None,
        }
    }
}

impl<'a> Members<Json<'a>> for Object<'a> {
    fn get(&self, key: &str) -> Option<&Json<'a>> {
        self.0.iter().find(|(k, _)| *k == key).map(|(_, v)| v)
    }
    /// The least unknown key, as serde_json's objects (in key order) give it.
    fn unknown_key(&self, known: &[&str]) -> Option<&str> {
        self.0
            .iter()
            .map(|(k, _)| *k)
            .filter(|k| !known.contains(k))
            .min()
    }
}
