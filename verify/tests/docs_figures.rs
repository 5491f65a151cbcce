//! The figures docs/verification.md quotes from the golden report are the golden report's: the
//! least and largest degree bound `d` of the identity checks and the largest Schwartz-Zippel
//! bound. A regenerated golden copy with other figures fails here until the page is updated.

use serde_json::Value;
use std::path::Path;

fn read(path: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The number after `before` in `text`.
fn number_after(text: &str, before: &str) -> f64 {
    let rest = &text[text
        .find(before)
        .unwrap_or_else(|| panic!("{before:?} not in the page"))
        + before.len()..];
    let end = rest
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(rest.len());
    rest[..end].parse().unwrap()
}

#[test]
fn verification_page_quotes_the_golden_degrees_and_bound() {
    let golden: Value = serde_json::from_str(&read("docs/reports/verify.json")).unwrap();
    let identities: Vec<&Value> = golden["results"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["proof"]["kind"] == "identity")
        .collect();
    assert!(!identities.is_empty());
    let degree = |r: &Value| r["proof"]["degree"].as_u64().unwrap();
    let least = identities.iter().map(|r| degree(r)).min().unwrap();
    let most = identities.iter().map(|r| degree(r)).max().unwrap();
    let bound = identities
        .iter()
        .map(|r| r["proof"]["bound"].as_f64().unwrap())
        .fold(0.0, f64::max);
    let points = golden["points"].as_u64().unwrap();

    let page = read("docs/verification.md");
    assert_eq!(number_after(&page, "$d$ ranges from ") as u64, least);
    assert_eq!(
        number_after(&page, "(the smooth member,\n`rough free`, $n = 2$) to ") as u64,
        most
    );
    assert_eq!(number_after(&page, "is\n$(") as u64, most);
    assert_eq!(number_after(&page, "/2^{20})^{") as u64, points);
    assert_eq!(number_after(&page, "$k = ") as u64, points);
    // The bound to the two digits quoted: m x 10^-e.
    let mantissa = number_after(&page, "\\approx ");
    let exponent = number_after(&page, "\\times10^{-");
    let quoted = mantissa * 10f64.powi(-(exponent as i32));
    assert!(
        (quoted - bound).abs() <= 0.05 * 10f64.powi(-(exponent as i32)),
        "the page says {quoted:e}, the golden report {bound:e}"
    );
}
