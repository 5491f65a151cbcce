//! The publishing rules, with kills simulated in process: at an injected fault the commit
//! stops and skips every cleanup, as `kill -9` would (the process-level version, with real
//! aborts and kills, is `verify/tests/cli_outputs.rs`).

use super::*;

/// A fresh empty directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("noslip-publish-{test}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// The files of `dir` (name, contents), sorted.
fn files(dir: &Path) -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().into_string().unwrap();
            (name, fs::read_to_string(e.path()).unwrap())
        })
        .collect();
    v.sort();
    v
}

/// The set of run `tag`: the marker, `a.md` and `b.json`, both naming the run.
fn set(tag: &str) -> Vec<(String, String)> {
    vec![
        (MARKER.to_string(), MARKER_TEXT.to_string()),
        ("a.md".to_string(), format!("run {tag}\n")),
        ("b.json".to_string(), format!("{{\"run\": \"{tag}\"}}\n")),
    ]
}

fn stage(target: &Path, tag: &str, fault: Option<Fault>) -> Result<Staging, PublishError> {
    let mut s = Staging::with_fault(target, fault, true)?;
    s.write("a.md", format!("run {tag}\n").as_bytes())?;
    s.write("b.json", format!("{{\"run\": \"{tag}\"}}\n").as_bytes())?;
    Ok(s)
}

/// Entries of `parent` other than `target`: temporaries left behind.
fn leftovers(parent: &Path, target: &Path) -> Vec<PathBuf> {
    fs::read_dir(parent)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p != target)
        .collect()
}

#[test]
fn a_set_is_created_then_replaced_whole() {
    let parent = scratch("whole");
    let target = parent.join("out");
    stage(&target, "1", None).unwrap().commit().unwrap();
    assert_eq!(files(&target), set("1"));
    let mut s = Staging::new(&target).unwrap();
    s.write("c.svg", b"<svg/>").unwrap();
    s.commit().unwrap();
    // The old set's files do not survive into the new one.
    assert_eq!(
        files(&target),
        vec![
            (MARKER.to_string(), MARKER_TEXT.to_string()),
            ("c.svg".to_string(), "<svg/>".to_string())
        ]
    );
    assert_eq!(leftovers(&parent, &target), Vec::<PathBuf>::new());
    fs::remove_dir_all(parent).unwrap();
}

/// `--out .`, `..` or `/` names no directory the set could replace by name: a usage error
/// (exit 2 through `publish_failure`), not a write failure, and nothing is touched.
#[test]
fn an_output_path_without_a_name_is_refused() {
    for target in [".", "..", "/"] {
        let e = Staging::new(Path::new(target)).unwrap_err();
        assert!(matches!(e, PublishError::NoName(_)), "{target}: {e}");
        assert!(
            e.to_string().contains("names no directory of its own"),
            "{e}"
        );
        let f = crate::exit::publish_failure(&e);
        assert_eq!(f.exit, crate::exit::Exit::BadInput, "{target}");
    }
}

#[test]
fn a_directory_noslip_did_not_make_is_never_replaced() {
    let parent = scratch("not-ours");
    let target = parent.join("out");
    fs::create_dir(&target).unwrap();
    fs::write(target.join("thesis.tex"), "years of work").unwrap();
    let e = Staging::new(&target).unwrap_err();
    assert!(matches!(e, PublishError::NotOurs(_)), "{e}");
    assert!(e.to_string().contains("refusing to replace"), "{e}");
    assert_eq!(
        files(&target),
        vec![("thesis.tex".to_string(), "years of work".to_string())]
    );
    assert_eq!(leftovers(&parent, &target), Vec::<PathBuf>::new());
    // A file in the way is refused too; an empty directory is replaced.
    let file = parent.join("file");
    fs::write(&file, "x").unwrap();
    assert!(matches!(
        Staging::new(&file).unwrap_err(),
        PublishError::NotOurs(_)
    ));
    let empty = parent.join("empty");
    fs::create_dir(&empty).unwrap();
    stage(&empty, "1", None).unwrap().commit().unwrap();
    assert_eq!(files(&empty), set("1"));
    fs::remove_dir_all(parent).unwrap();
}

/// Kill a publish of set 2 over set 1 at `fault`, with `switch`; then check what a reader
/// sees, recover with the next run's preparation, and publish set 3.
fn kill_and_recover(switch: Switch, fault: Fault) {
    let parent = scratch(&format!("kill-{switch:?}-{fault:?}"));
    let target = parent.join("out");
    stage(&target, "1", None).unwrap().commit().unwrap();
    stage(&target, "2", Some(fault))
        .unwrap()
        .commit_with(switch)
        .unwrap();
    let seen = if target.exists() {
        Some(files(&target))
    } else {
        None
    };
    match (switch, fault) {
        // Between the two renames of the fallback there is no output directory; the next
        // run restores the old set.
        (Switch::Renames, Fault::Aside) => assert_eq!(seen, None),
        (_, Fault::Staged) => assert_eq!(seen, Some(set("1"))),
        (_, Fault::Switched) => assert_eq!(seen, Some(set("2"))),
        _ => unreachable!(),
    }
    assert!(
        !leftovers(&parent, &target).is_empty(),
        "a killed run leaves its temporaries"
    );
    let next = Staging::new(&target).unwrap();
    let expected = if fault == Fault::Switched { "2" } else { "1" };
    assert_eq!(files(&target), set(expected), "after recovery");
    drop(next);
    assert_eq!(leftovers(&parent, &target), Vec::<PathBuf>::new());
    stage(&target, "3", None)
        .unwrap()
        .commit_with(switch)
        .unwrap();
    assert_eq!(files(&target), set("3"));
    assert_eq!(leftovers(&parent, &target), Vec::<PathBuf>::new());
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn a_kill_at_any_step_leaves_the_old_set_or_the_new_one() {
    for fault in [Fault::Staged, Fault::Switched] {
        kill_and_recover(Switch::Exchange, fault);
    }
    for fault in [Fault::Staged, Fault::Aside, Fault::Switched] {
        kill_and_recover(Switch::Renames, fault);
    }
}

#[cfg(target_os = "linux")]
#[test]
fn linux_switches_by_exchange_without_a_moment_of_absence() {
    // Exchange swaps the two directories: the staging name then holds the old set.
    let parent = scratch("exchange");
    let (a, b) = (parent.join("a"), parent.join("b"));
    fs::create_dir(&a).unwrap();
    fs::create_dir(&b).unwrap();
    fs::write(a.join("x"), "in a").unwrap();
    exchange(&a, &b).unwrap();
    assert_eq!(fs::read_to_string(b.join("x")).unwrap(), "in a");
    assert!(fs::read_dir(&a).unwrap().next().is_none());
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn a_full_disk_keeps_the_old_set_and_leaves_no_partial_file() {
    let parent = scratch("full");
    let target = parent.join("out");
    stage(&target, "1", None).unwrap().commit().unwrap();
    let e = stage(&target, "2", Some(Fault::FullDisk)).unwrap_err();
    assert!(e.to_string().contains("No space left on device"), "{e}");
    assert_eq!(files(&target), set("1"));
    assert_eq!(leftovers(&parent, &target), Vec::<PathBuf>::new());
    fs::remove_dir_all(parent).unwrap();
}

#[test]
fn atomic_writes_replace_whole_files_and_clean_up_on_failure() {
    let dir = scratch("atomic");
    let path = dir.join("r.md");
    write_atomic(&path, "one").unwrap();
    write_atomic(&path, "two").unwrap();
    assert_eq!(fs::read_to_string(&path).unwrap(), "two");
    // A directory in the way: the rename fails, the temporary goes.
    let blocked = dir.join("blocked");
    fs::create_dir(&blocked).unwrap();
    fs::write(blocked.join("x"), "x").unwrap();
    assert!(write_atomic(&blocked, "three").is_err());
    let mut names: Vec<String> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(names, ["blocked", "r.md"]);
    fs::remove_dir_all(dir).unwrap();
}
