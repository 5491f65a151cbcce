//! The key path of the value (or key) at a byte offset of a TOML document, such as
//! `contact.balls.e`, `obstacle[0].contact.beta0` or `ball[2].position[1]`: the parser's
//! errors (a NaN, a non-number, an unknown key) carry a byte span and no key, and a scene
//! error names the field ([`crate::SceneError`]). Tables of an array of tables and elements
//! of an array are numbered from 0, as validation numbers them.

use std::ops::Range;
use toml_edit::{ImDocument, InlineTable, Item, Table, Value};

/// The path of the innermost key or value of `text` whose span holds byte `offset`; `None`
/// when `text` is not TOML or nothing there holds it (a table header, a comment).
pub(crate) fn key_path(text: &str, offset: usize) -> Option<String> {
    let document = ImDocument::parse(text).ok()?;
    in_table(document.as_table(), "", offset)
}

/// The key path of the `key = value` line holding byte `offset`, read from the text alone:
/// for a document the TOML parser refuses (an integer beyond 64 bits, a syntax error), where
/// [`key_path`] has no tree to walk. The line's bare or dotted key, under the last table
/// header above it (`[[name]]` headers numbered from 0); `None` when the line holds no `=`.
pub(crate) fn line_key(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = text[start..].lines().next().unwrap_or("");
    let key = line.split_once('=')?.0.trim();
    let key_like = |k: &str| {
        !k.is_empty()
            && k.chars()
                .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | ' '))
    };
    // A key too long to quote (hundreds of dotted parts) is not named.
    if !key_like(key) || key.len() > 64 {
        return None;
    }
    let mut table = String::new();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for header in text[..start].lines().map(str::trim) {
        if let Some(name) = header.strip_prefix("[[").and_then(|h| h.split_once("]]")) {
            let name = name.0.trim().to_string();
            let k = match counts.iter_mut().find(|(n, _)| *n == name) {
                Some((_, k)) => {
                    *k += 1;
                    *k
                }
                None => {
                    counts.push((name.clone(), 0));
                    0
                }
            };
            table = format!("{name}[{k}]");
        } else if let Some(name) = header.strip_prefix('[').and_then(|h| h.split_once(']')) {
            table = name.0.trim().to_string();
        }
    }
    Some(child(&table, &key.replace(' ', "")))
}

/// The path of the table of `text` whose span is `span`, as a missing key's error gives it
/// (the table the key is missing from): `species[1]`, `box`, `contact.balls`, or `""` for
/// the document's top level; `None` when `text` is not TOML.
pub(crate) fn table_path(text: &str, span: &Range<usize>) -> Option<String> {
    let document = ImDocument::parse(text).ok()?;
    Some(table_in(document.as_table(), "", span).unwrap_or_default())
}

/// [`table_path`] among the tables under `table` (whose own path is `prefix`).
fn table_in(table: &Table, prefix: &str, span: &Range<usize>) -> Option<String> {
    let this = |t: &Table, path: String| {
        table_in(t, &path, span).or_else(|| (t.span().as_ref() == Some(span)).then_some(path))
    };
    table.iter().find_map(|(key, item)| {
        let path = child(prefix, key);
        match item {
            Item::Table(t) => this(t, path),
            Item::ArrayOfTables(tables) => tables
                .iter()
                .enumerate()
                .find_map(|(i, t)| this(t, format!("{path}[{i}]"))),
            _ => None,
        }
    })
}

fn holds(span: Option<Range<usize>>, offset: usize) -> bool {
    span.is_some_and(|s| s.contains(&offset))
}

fn child(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

fn in_table(table: &Table, prefix: &str, offset: usize) -> Option<String> {
    table.iter().find_map(|(key, item)| {
        let path = child(prefix, key);
        in_item(item, &path, offset)
            .or_else(|| holds(table.key(key).and_then(|k| k.span()), offset).then_some(path))
    })
}

fn in_inline_table(table: &InlineTable, prefix: &str, offset: usize) -> Option<String> {
    table.iter().find_map(|(key, value)| {
        let path = child(prefix, key);
        in_value(value, &path, offset)
            .or_else(|| holds(table.key(key).and_then(|k| k.span()), offset).then_some(path))
    })
}

fn in_item(item: &Item, path: &str, offset: usize) -> Option<String> {
    match item {
        Item::None => None,
        Item::Value(value) => in_value(value, path, offset),
        Item::Table(table) => in_table(table, path, offset),
        Item::ArrayOfTables(tables) => tables
            .iter()
            .enumerate()
            .find_map(|(i, t)| in_table(t, &format!("{path}[{i}]"), offset)),
    }
}

fn in_value(value: &Value, path: &str, offset: usize) -> Option<String> {
    let inner = match value {
        Value::InlineTable(table) => in_inline_table(table, path, offset),
        Value::Array(array) => array
            .iter()
            .enumerate()
            .find_map(|(i, v)| in_value(v, &format!("{path}[{i}]"), offset)),
        _ => None,
    };
    inner.or_else(|| holds(value.span(), offset).then(|| path.to_string()))
}

#[cfg(test)]
mod tests {
    use super::key_path;

    fn at(text: &str, needle: &str) -> Option<String> {
        key_path(text, text.find(needle).unwrap())
    }

    #[test]
    fn paths_name_tables_arrays_and_inline_tables() {
        let text = "dim = 2\n[contact]\nballs = { e = nan, beta = 0 }\n\
                    [[obstacle]]\nradius = 1\n[[obstacle]]\nposition = [5, inf]\n\
                    contact = { e = 1, mu = 0.5, beta0 = -nan }\n\
                    [box]\ncontact.e = 7\n";
        assert_eq!(at(text, "nan,").as_deref(), Some("contact.balls.e"));
        assert_eq!(at(text, "beta = 0").as_deref(), Some("contact.balls.beta"));
        assert_eq!(at(text, "inf").as_deref(), Some("obstacle[1].position[1]"));
        assert_eq!(
            at(text, "-nan").as_deref(),
            Some("obstacle[1].contact.beta0")
        );
        assert_eq!(at(text, "7").as_deref(), Some("box.contact.e"));
        assert_eq!(at(text, "dim").as_deref(), Some("dim"));
        // A table header holds no value; text that is not TOML has no paths.
        assert_eq!(at(text, "[box]"), None);
        assert_eq!(key_path("a = [", 4), None);
    }

    /// An integer the parser refuses still gets its key, from the text.
    #[test]
    fn a_line_the_parser_refuses_is_named_from_the_text() {
        let text = "dim = 2\n[[species]]\nname = \"a\"\n[[species]]\nname = \"b\"\n\
                    count = 99999999999999999999\n[box]\nsize = [1, 1]\n";
        let e = toml::from_str::<crate::raw::RawScene>(text).unwrap_err();
        let at = e.span().unwrap().start;
        assert_eq!(key_path(text, at), None, "the parser has no tree here");
        assert_eq!(
            super::line_key(text, at).as_deref(),
            Some("species[1].count")
        );
        assert_eq!(
            super::line_key(text, text.find("size").unwrap()).as_deref(),
            Some("box.size")
        );
        assert_eq!(super::line_key(text, 0).as_deref(), Some("dim"));
        assert_eq!(super::line_key(text, text.find("[box]").unwrap()), None);
    }

    /// A missing key's error points at its table: the path is the table's, not the first
    /// key's of the document (a review saw `dim: missing field \`species\``).
    #[test]
    fn a_missing_key_is_placed_in_its_table() {
        let text = "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"wall\", \"wall\"]\n[[species]]\nname = \"a\"\n\n\
                    [[species]]\nname = \"b\"\nradius = 1\n[contact.balls]\ne = 1\n";
        let missing = |text: &str| {
            let e = toml::from_str::<crate::raw::RawScene>(text).unwrap_err();
            assert!(e.message().starts_with("missing field"), "{e}");
            super::table_path(text, &e.span().unwrap())
        };
        assert_eq!(missing(text).as_deref(), Some("species[0]"));
        assert_eq!(missing("dim = 2\n").as_deref(), Some(""));
        let boxed = "dim = 2\n[box]\nsize = [1, 1]\nboundary = [\"wall\", \"wall\"]\n";
        assert_eq!(missing(boxed).as_deref(), Some(""));
        let no_size = "dim = 2\n[[species]]\nname = \"a\"\nmass = 1\nradius = 1\n[box]\n";
        assert_eq!(missing(no_size).as_deref(), Some("box"));
    }
}
