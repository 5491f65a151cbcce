//! docs/backends.md's recipe reproduces `noslip collide` from C bit for bit: the header from
//! `noslip gen --lang c`, compiled with the system C compiler into `tests/c/collide_recipe.c`
//! (the recipe's steps written out: the normal renormalised as `nu (3 - |nu|^2) / 2` unless
//! its `|nu|^2` is exactly 1, `inv_mass = 1.0 / m` in double, `gamma2` from the inertia key, the
//! 2D and 3D spin shorthands to the upper triangle, the plain kernel, `fixed` reading the
//! immovable body's state), fed the same cases as `noslip collide`, gives every output
//! component with the same bits. Each step is shown to matter: leaving it out (the program's
//! control modes) changes some results.

use crate::support;

use serde_json::{json, Value};
use std::path::Path;
use std::process::Command;
use support::{noslip, run_ok, temp};

/// Cases per dimension.
const CASES: usize = 300;

/// SplitMix64: a small seeded generator (the cases are the same on every run).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * ((self.next() >> 11) as f64 / (1u64 << 53) as f64)
    }

    fn below(&mut self, k: u64) -> u64 {
        self.next() % k
    }
}

/// One body: the JSON `noslip collide` reads and the recipe program's fields.
struct Body {
    json: Value,
    line: String,
}

/// A number as both read it: its shortest round-trip decimal (exactly this double).
fn dec(x: f64) -> String {
    format!("{x:?}")
}

fn body(rng: &mut Rng, n: usize, immovable: bool) -> Body {
    let radius = rng.uniform(0.2, 5.0);
    let mass = if immovable {
        "inf".to_string()
    } else {
        dec(rng.uniform(0.1, 10.0))
    };
    let mut json = json!({"mass": mass, "radius": dec(radius)});
    let shell = 2.0 / n as f64;
    let (key, value) = match rng.below(5) {
        0 => ('u', 0.0),
        1 => {
            json["distribution"] = json!("uniform");
            ('u', 0.0)
        }
        2 => {
            json["distribution"] = json!("shell");
            ('s', 0.0)
        }
        3 => {
            let g = rng.uniform(0.01, 0.99) * shell;
            json["gamma2"] = json!(dec(g));
            ('g', g)
        }
        _ => {
            let l = rng.uniform(0.01, 0.99) * radius * radius / n as f64;
            json["lambda"] = json!(dec(l));
            ('l', l)
        }
    };
    let (form, spin, spin_json) = match (n, rng.below(2)) {
        (2, 0) => {
            let c = rng.uniform(-3.0, 3.0);
            ('c', vec![c], json!(dec(c)))
        }
        (3, 0) => {
            let w: Vec<f64> = (0..3).map(|_| rng.uniform(-3.0, 3.0)).collect();
            (
                'w',
                w.clone(),
                json!(w.iter().map(|x| dec(*x)).collect::<Vec<_>>()),
            )
        }
        _ => {
            let mut m = vec![0.0; n * n];
            for i in 0..n {
                for j in i + 1..n {
                    let x = rng.uniform(-3.0, 3.0);
                    m[i * n + j] = x;
                    m[j * n + i] = -x;
                }
            }
            let rows: Vec<Vec<String>> = m
                .chunks(n)
                .map(|r| r.iter().map(|x| dec(*x)).collect())
                .collect();
            ('m', m, json!(rows))
        }
    };
    json["angular_velocity"] = spin_json;
    let velocity: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
    json["velocity"] = json!(velocity.iter().map(|x| dec(*x)).collect::<Vec<_>>());
    let fields: Vec<String> = [
        mass,
        dec(radius),
        key.to_string(),
        dec(value),
        form.to_string(),
    ]
    .into_iter()
    .chain(spin.iter().chain(&velocity).map(|x| dec(*x)))
    .collect();
    Body {
        json,
        line: fields.join(" "),
    }
}

/// A case of dimension `n` whose bodies approach clearly (`(u_2 - u_1) . nu` below `-0.05`:
/// no grazing adjustment), as JSON and as the recipe program's line; and whether its normal
/// was renormalised (`|nu|^2 != 1` in floats).
fn case(rng: &mut Rng, n: usize) -> (Value, String, bool) {
    loop {
        // Normals as users compute them, d / |d|, and sometimes a unit axis.
        let nu: Vec<f64> = if rng.below(8) == 0 {
            let k = rng.below(n as u64) as usize;
            (0..n).map(|i| if i == k { -1.0 } else { 0.0 }).collect()
        } else {
            let d: Vec<f64> = (0..n).map(|_| rng.uniform(-1.0, 1.0)).collect();
            let norm = d.iter().map(|x| x * x).sum::<f64>().sqrt();
            d.iter().map(|x| x / norm).collect()
        };
        let which = rng.below(4); // 0: body 1 immovable, 1: body 2, else both movable
        let bodies = [body(rng, n, which == 0), body(rng, n, which == 1)];
        let u = |b: &Body| -> Vec<f64> {
            b.json["velocity"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_str().unwrap().parse().unwrap())
                .collect()
        };
        let (u1, u2) = (u(&bodies[0]), u(&bodies[1]));
        let dn: f64 = (0..n).map(|k| nu[k] * (u2[k] - u1[k])).sum();
        if dn > -0.05 {
            continue;
        }
        let norm2 = nu.iter().fold(0.0, |s, x| s + x * x);
        let json = json!({
            "dim": n,
            "normal": nu.iter().map(|x| dec(*x)).collect::<Vec<_>>(),
            "bodies": [bodies[0].json, bodies[1].json],
        });
        let nus: Vec<String> = nu.iter().map(|x| dec(*x)).collect();
        let line = format!(
            "{n} {} {} {}",
            nus.join(" "),
            bodies[0].line,
            bodies[1].line
        );
        return (json, line, norm2 != 1.0);
    }
}

/// Every number of a `noslip collide` output case, in order (angular velocity as given, then
/// velocity, per body), as bits.
fn output_bits(case: &Value) -> Vec<u64> {
    fn flatten(v: &Value, out: &mut Vec<u64>) {
        match v {
            Value::Array(xs) => xs.iter().for_each(|x| flatten(x, out)),
            Value::Number(x) => out.push(x.as_str().parse::<f64>().unwrap().to_bits()),
            other => panic!("not a number: {other}"),
        }
    }
    let mut out = Vec::new();
    for b in case["bodies"].as_array().unwrap() {
        flatten(&b["angular_velocity"], &mut out);
        flatten(&b["velocity"], &mut out);
    }
    out
}

/// The recipe program's results in `mode` on the cases in file `input`, one vector of bits
/// per case.
fn recipe(exe: &Path, mode: &str, input: &Path) -> Vec<Vec<u64>> {
    let out = Command::new(exe)
        .arg(mode)
        .stdin(std::fs::File::open(input).unwrap())
        .output()
        .unwrap();
    assert!(out.status.success(), "collide_recipe {mode} failed");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| {
            l.split_whitespace()
                .map(|h| u64::from_str_radix(h, 16).unwrap())
                .collect()
        })
        .collect()
}

#[test]
fn the_documented_recipe_reproduces_noslip_collide_bit_for_bit() {
    let dir = temp("c-recipe");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    run_ok(noslip().args(["gen", "--lang", "c", "--out"]).arg(&dir));
    let exe = dir.join("collide_recipe");
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/c/collide_recipe.c");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args(["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(&dir)
        .arg(&source)
        .arg("-o")
        .arg(&exe)
        .arg("-lm")
        .status()
        .unwrap();
    assert!(
        status.success(),
        "{cc} could not compile {}",
        source.display()
    );

    let mut rng = Rng(29);
    let (mut cases, mut lines, mut renormalised) = (Vec::new(), Vec::new(), 0);
    for n in 2..=6 {
        for _ in 0..CASES {
            let (json, line, renorm) = case(&mut rng, n);
            cases.push(json);
            lines.push(line);
            renormalised += usize::from(renorm);
        }
    }
    eprintln!(
        "|nu|^2 != 1, renormalised: {renormalised} of {} cases",
        cases.len()
    );
    // Both branches of step 1 are exercised.
    assert!(
        renormalised > cases.len() / 4 && renormalised < cases.len(),
        "{renormalised}"
    );
    let input = dir.join("cases.json");
    std::fs::write(&input, Value::Array(cases.clone()).to_string()).unwrap();
    let out: Value = serde_json::from_str(&run_ok(noslip().arg("collide").arg(&input))).unwrap();
    let expected: Vec<Vec<u64>> = out.as_array().unwrap().iter().map(output_bits).collect();
    let text = dir.join("cases.txt");
    std::fs::write(&text, lines.join("\n") + "\n").unwrap();

    let got = recipe(&exe, "recipe", &text);
    assert_eq!(got.len(), expected.len());
    for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
        assert_eq!(g, e, "case {i}: {}\nrecipe {g:x?}\nnoslip {e:x?}", cases[i]);
    }
    // Each control leaves out one documented step; each changes some results (the cases it
    // concerns), so the agreement above depends on every step.
    for mode in ["no-renormalise", "fma", "still-wall", "spin-sign"] {
        let differ = recipe(&exe, mode, &text)
            .iter()
            .zip(&expected)
            .filter(|(g, e)| g != e)
            .count();
        eprintln!("{mode}: {differ} of {} cases differ", expected.len());
        assert!(
            differ > 0,
            "without its step ({mode}) the recipe still agrees"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
