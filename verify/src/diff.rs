//! A line diff in the unified format (`diff -u`), for golden-copy comparisons a reviewer
//! can read: Myers' O((N+M) D) shortest edit script, hunks with context lines.

/// One line of an edit script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edit {
    Keep,
    Delete,
    Insert,
}

/// Beyond this many edits the middle is shown as one deletion and one insertion (the Myers
/// trace takes O(D^2) memory).
const MAX_EDITS: usize = 4000;

/// The shortest edit script from `a` to `b` (Myers 1986), as a sequence of edits.
fn edits(a: &[&str], b: &[&str]) -> Vec<Edit> {
    let prefix = a.iter().zip(b).take_while(|(x, y)| x == y).count();
    let suffix = a[prefix..]
        .iter()
        .rev()
        .zip(b[prefix..].iter().rev())
        .take_while(|(x, y)| x == y)
        .count();
    let (ma, mb) = (&a[prefix..a.len() - suffix], &b[prefix..b.len() - suffix]);
    let mut script = vec![Edit::Keep; prefix];
    script.extend(middle(ma, mb));
    script.extend(vec![Edit::Keep; suffix]);
    script
}

fn middle(a: &[&str], b: &[&str]) -> Vec<Edit> {
    let (n, m) = (a.len() as isize, b.len() as isize);
    let max = (n + m) as usize;
    let offset = max as isize + 1;
    let mut v = vec![0isize; 2 * max + 3];
    let mut trace: Vec<Vec<isize>> = Vec::new();
    let mut found = false;
    for d in 0..=max.min(MAX_EDITS) as isize {
        trace.push(v.clone());
        for k in (-d..=d).step_by(2) {
            let i = (k + offset) as usize;
            let mut x = if k == -d || (k != d && v[i - 1] < v[i + 1]) {
                v[i + 1]
            } else {
                v[i - 1] + 1
            };
            let mut y = x - k;
            while x < n && y < m && a[x as usize] == b[y as usize] {
                x += 1;
                y += 1;
            }
            v[i] = x;
            if x >= n && y >= m {
                found = true;
                break;
            }
        }
        if found {
            break;
        }
    }
    if !found {
        let mut s = vec![Edit::Delete; a.len()];
        s.extend(vec![Edit::Insert; b.len()]);
        return s;
    }
    // Walk the trace back from (n, m).
    let mut script = Vec::new();
    let (mut x, mut y) = (n, m);
    for (d, v) in trace.iter().enumerate().rev() {
        let d = d as isize;
        let k = x - y;
        let i = |k: isize| (k + offset) as usize;
        let prev_k = if k == -d || (k != d && v[i(k - 1)] < v[i(k + 1)]) {
            k + 1
        } else {
            k - 1
        };
        let prev_x = v[i(prev_k)];
        let prev_y = prev_x - prev_k;
        while x > prev_x && y > prev_y {
            script.push(Edit::Keep);
            x -= 1;
            y -= 1;
        }
        if d > 0 {
            script.push(if x == prev_x {
                Edit::Insert
            } else {
                Edit::Delete
            });
        }
        (x, y) = (prev_x, prev_y);
    }
    script.reverse();
    script
}

/// The unified diff of `old` and `new` with `context` lines around each change, under the
/// headers `--- old_name` and `+++ new_name`; `None` if the texts are equal.
pub fn unified(
    old_name: &str,
    new_name: &str,
    old: &str,
    new: &str,
    context: usize,
) -> Option<String> {
    if old == new {
        return None;
    }
    let (a, b): (Vec<&str>, Vec<&str>) = (old.lines().collect(), new.lines().collect());
    let script = edits(&a, &b);
    // Positions (in a and in b) before each edit.
    let mut at = Vec::with_capacity(script.len() + 1);
    let (mut i, mut j) = (0, 0);
    for e in &script {
        at.push((i, j));
        match e {
            Edit::Keep => (i, j) = (i + 1, j + 1),
            Edit::Delete => i += 1,
            Edit::Insert => j += 1,
        }
    }
    at.push((i, j));
    let changed: Vec<usize> = (0..script.len())
        .filter(|&s| script[s] != Edit::Keep)
        .collect();
    let mut out = format!("--- {old_name}\n+++ {new_name}\n");
    let mut c = 0;
    while c < changed.len() {
        // A hunk: changes closer than 2 context blocks merge.
        let start = changed[c].saturating_sub(context);
        let mut end = changed[c] + 1;
        while c + 1 < changed.len() && changed[c + 1] <= end + 2 * context {
            c += 1;
            end = changed[c] + 1;
        }
        let end = (end + context).min(script.len());
        c += 1;
        let (a0, b0) = at[start];
        let (a1, b1) = at[end];
        let range = |first: usize, len: usize| {
            if len == 0 {
                format!("{first},0")
            } else if len == 1 {
                format!("{}", first + 1)
            } else {
                format!("{},{len}", first + 1)
            }
        };
        out.push_str(&format!(
            "@@ -{} +{} @@\n",
            range(a0, a1 - a0),
            range(b0, b1 - b0)
        ));
        for s in start..end {
            let (x, y) = at[s];
            match script[s] {
                Edit::Keep => out.push_str(&format!(" {}\n", a[x])),
                Edit::Delete => out.push_str(&format!("-{}\n", a[x])),
                Edit::Insert => out.push_str(&format!("+{}\n", b[y])),
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Apply a unified diff's hunks to `old`: the check that a diff says what changed.
    fn patch(old: &str, diff: &str) -> String {
        let a: Vec<&str> = old.lines().collect();
        let mut out: Vec<String> = Vec::new();
        let mut next = 0;
        for line in diff.lines().skip(2) {
            if let Some(h) = line.strip_prefix("@@ -") {
                let first: usize = h.split([',', ' ']).next().unwrap().parse().unwrap();
                let len_zero = h.split(' ').next().unwrap().ends_with(",0");
                let start = if len_zero { first } else { first - 1 };
                out.extend(a[next..start].iter().map(|s| s.to_string()));
                next = start;
            } else if let Some(l) = line.strip_prefix(' ') {
                assert_eq!(a[next], l, "context matches");
                out.push(l.to_string());
                next += 1;
            } else if let Some(l) = line.strip_prefix('-') {
                assert_eq!(a[next], l, "deleted line matches");
                next += 1;
            } else if let Some(l) = line.strip_prefix('+') {
                out.push(l.to_string());
            }
        }
        out.extend(a[next..].iter().map(|s| s.to_string()));
        out.iter().map(|l| format!("{l}\n")).collect()
    }

    #[test]
    fn equal_texts_have_no_diff() {
        assert_eq!(unified("a", "b", "x\ny\n", "x\ny\n", 3), None);
    }

    #[test]
    fn a_changed_line_is_one_hunk_with_context() {
        let old = "1\n2\n3\n4\n5\n6\n7\n8\n9\n";
        let new = "1\n2\n3\n4\nfive\n6\n7\n8\n9\n";
        assert_eq!(
            unified("golden", "run", old, new, 2).unwrap(),
            "--- golden\n+++ run\n@@ -3,5 +3,5 @@\n 3\n 4\n-5\n+five\n 6\n 7\n"
        );
    }

    #[test]
    fn the_diff_is_minimal_and_patches_old_into_new() {
        // Deterministic pseudo-random edits of a 300-line text.
        let old: String = (0..300).map(|i| format!("line {i}\n")).collect();
        let mut state = 12345u64;
        let mut rand = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 33) as usize
        };
        for _ in 0..50 {
            let mut lines: Vec<String> = old.lines().map(String::from).collect();
            let mut edits = 0;
            for _ in 0..rand() % 12 {
                let at = rand() % (lines.len() + 1);
                match rand() % 3 {
                    0 if at < lines.len() => {
                        lines.remove(at);
                        edits += 1;
                    }
                    1 => {
                        lines.insert(at, format!("new {}", rand()));
                        edits += 1;
                    }
                    _ if at < lines.len() => {
                        lines[at] = format!("changed {}", rand());
                        edits += 2;
                    }
                    _ => {}
                }
            }
            let new: String = lines.iter().map(|l| format!("{l}\n")).collect();
            let Some(d) = unified("a", "b", &old, &new, 3) else {
                assert_eq!(old, new);
                continue;
            };
            assert_eq!(patch(&old, &d), new, "{d}");
            let changes = d
                .lines()
                .skip(2)
                .filter(|l| l.starts_with('+') || l.starts_with('-'))
                .count();
            assert!(changes <= edits, "{changes} > {edits} edits:\n{d}");
        }
    }
}
