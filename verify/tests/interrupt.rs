//! `suite::run_interruptible`: the hook is asked before each point of each identity check,
//! and once it says stop every identity check left ends at once, failed with "interrupted"
//! (the caller discards such a run); a hook that never says stop changes nothing.

use noslip_verify::suite::{run, run_interruptible, Options};
use std::sync::atomic::{AtomicU64, Ordering};

#[test]
fn the_hook_is_asked_per_point_and_stops_the_identity_checks() {
    let opts = Options {
        points: 3,
        ..Options::default()
    };
    let asked = AtomicU64::new(0);
    let count = || {
        asked.fetch_add(1, Ordering::Relaxed);
        false
    };
    let plain = run(&[2], &opts, &mut |_| {});
    let hooked = run_interruptible(&[2], &opts, &mut |_| {}, &count);
    assert!(plain.iter().all(|r| r.passed));
    let identities = plain.iter().filter(|r| r.points == 3).count();
    assert!(identities > 10, "{identities} identity checks");
    assert_eq!(asked.load(Ordering::Relaxed), 3 * identities as u64);
    let names = |rs: &[noslip_verify::report::CheckResult]| {
        rs.iter()
            .map(|r| (r.check.clone(), r.passed))
            .collect::<Vec<_>>()
    };
    assert_eq!(names(&plain), names(&hooked));

    let stopped = run_interruptible(&[2], &opts, &mut |_| {}, &|| true);
    let failed: Vec<_> = stopped.iter().filter(|r| !r.passed).collect();
    assert_eq!(failed.len(), identities);
    assert!(failed.iter().all(|r| r.detail == "interrupted at point 0"));
}
