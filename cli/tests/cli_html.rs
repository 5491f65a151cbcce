//! `noslip simulate --html FILE`: the animation page is published with the set (a member,
//! or a link to `animation.html` from outside `--out`), holds its data and names nothing
//! outside itself; bad `--html` paths are refused with exit 2 before any run. (The page
//! itself is played in a real browser by python/tests/test_animation_browser.py.)

use crate::support;

use std::path::Path;
use support::{noslip, run_ok, temp};

fn simulate(scene: &str, out: &Path, html: &Path) -> std::process::Output {
    noslip()
        .args(["simulate", scene, "--quiet", "--events", "500"])
        .arg("--out")
        .arg(out)
        .arg("--html")
        .arg(html)
        .output()
        .unwrap()
}

fn check_page(page: &str, title: &str) {
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert!(page.contains(&format!("<h1>{title}</h1>")));
    assert!(page.contains("<script id=\"noslip-data\" type=\"application/json\">{"));
    assert!(page.contains("\"pos\":\""), "the frames are embedded");
    for outside in ["http:", "https:", "src=", "<link", "url("] {
        assert!(!page.contains(outside), "the page names {outside}");
    }
}

#[test]
fn the_page_is_a_member_of_the_set_or_a_link_to_it() {
    let dir = temp("html");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // Directly in --out: the member under its own name.
    let out = dir.join("sinai");
    let o = simulate("scenes/sinai.toml", &out, &out.join("play.html"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = std::fs::read_to_string(out.join("play.html")).unwrap();
    check_page(&page, "sinai.toml");
    assert!(
        page.contains("id=\"portrait\""),
        "a one-ball table has its portrait"
    );
    // Outside --out: a link to the set's animation.html; a 3D gas, no portrait.
    let out3 = dir.join("gas3d");
    let outside = dir.join("gas3d.html");
    run_ok(
        noslip()
            .args([
                "simulate",
                "scenes/gas3d.toml",
                "--quiet",
                "--events",
                "300",
            ])
            .arg("--out")
            .arg(&out3)
            .arg("--html")
            .arg(&outside),
    );
    let member = std::fs::read_to_string(out3.join("animation.html")).unwrap();
    assert_eq!(std::fs::read_to_string(&outside).unwrap(), member);
    assert!(std::fs::symlink_metadata(&outside)
        .unwrap()
        .file_type()
        .is_symlink());
    check_page(&member, "gas3d.toml");
    assert!(!member.contains("id=\"portrait\""));
    assert!(member.contains("\"channels\":5"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_html_paths_are_refused_naming_the_option() {
    let dir = temp("html-bad");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("set");
    let existing = dir.join("a-directory");
    std::fs::create_dir_all(&existing).unwrap();
    let cases: [(&Path, &[&str]); 6] = [
        (&out.join("deeper/a.html"), &[]),
        (&out.join("summary.json"), &[]),
        (Path::new("scenes/sinai.toml"), &[]),
        (&dir.join("log.jsonl"), &["--log"]),
        // A directory names no file: --out itself, or one that exists.
        (&out, &[]),
        (&existing, &[]),
    ];
    for (html, extra) in cases {
        let mut c = noslip();
        c.args(["simulate", "scenes/sinai.toml", "--quiet", "--events", "10"])
            .arg("--out")
            .arg(&out)
            .arg("--html")
            .arg(html);
        for option in extra.iter() {
            c.arg(option).arg(html);
        }
        let o = c.output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{html:?}: {err}");
        assert!(err.contains("--html"), "{html:?}: {err}");
        assert!(
            !out.exists(),
            "a refused path costs no run and writes nothing"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_page_that_cannot_be_written_keeps_the_run_and_its_summary() {
    let dir = temp("html-full");
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.join("set");
    // /dev/full: the stream takes no byte. The set and the summary are published, the
    // failure is one error line and exit 1, as for --log.
    let o = simulate("scenes/sinai.toml", &out, Path::new("/dev/full"));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: cannot write the animation /dev/full"),
        "{err}"
    );
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("500 contacts ("));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"events\": 500"), "{summary}");
    std::fs::remove_dir_all(&dir).unwrap();
}
