//! The interrupt hooks of the long loops (a front end's Ctrl-C): asked as documented, a
//! "stop" ends the run with the `Interrupted` error at once, and a hook that never says stop
//! gives the uninterrupted result bit for bit.

use noslip_dynamics::lyapunov::{
    qr, qr_interruptible, two_trajectory, two_trajectory_interruptible, LyapunovError, Options,
};
use noslip_dynamics::orbits::search::{search, search_interruptible, Search, SearchError};
use noslip_scene::Scene;
use std::sync::atomic::{AtomicU64, Ordering};

const SINAI: &str = include_str!("../../scenes/sinai.toml");

fn options(events: u64) -> Options {
    Options {
        events,
        k: Some(1),
        blocks: 10,
        seed: 7,
        law: None,
        every: None,
    }
}

fn setup() -> noslip_sim::Setup<2, 1> {
    let scene = Scene::from_toml(SINAI, "sinai.toml").unwrap();
    noslip_sim::setup::setup::<2, 1>(&scene).unwrap()
}

#[test]
fn lyapunov_asks_before_every_contact_and_stops_when_told() {
    for two in [false, true] {
        let asked = AtomicU64::new(0);
        // Stop at the 1000th question: the run of 10^6 contacts ends there.
        let hook = || asked.fetch_add(1, Ordering::Relaxed) + 1 >= 1000;
        let result = if two {
            two_trajectory_interruptible(setup(), &options(1_000_000), &hook)
        } else {
            qr_interruptible(setup(), &options(1_000_000), &hook)
        };
        assert_eq!(result.unwrap_err(), LyapunovError::Interrupted);
        assert_eq!(asked.load(Ordering::Relaxed), 1000);
    }
}

#[test]
fn a_hook_that_never_stops_changes_nothing() {
    let asked = AtomicU64::new(0);
    let hook = || {
        asked.fetch_add(1, Ordering::Relaxed);
        false
    };
    let plain = qr(setup(), &options(2200)).unwrap();
    let hooked = qr_interruptible(setup(), &options(2200), &hook).unwrap();
    assert_eq!(
        plain.per_time[0].value.to_bits(),
        hooked.per_time[0].value.to_bits()
    );
    assert_eq!(plain.time.to_bits(), hooked.time.to_bits());
    // Once before each of the 2200 contacts (no quiet notice on this table).
    assert_eq!(asked.load(Ordering::Relaxed), 2200);
    let plain = two_trajectory(setup(), &options(2200)).unwrap();
    let hooked = two_trajectory_interruptible(setup(), &options(2200), &|| false).unwrap();
    assert_eq!(
        plain.per_time[0].value.to_bits(),
        hooked.per_time[0].value.to_bits()
    );
}

#[test]
fn the_orbit_search_asks_before_each_start() {
    let scene = Scene::from_toml(SINAI, "sinai.toml").unwrap();
    let ask = Search {
        period: 2,
        from: Vec::new(),
        grid: Some(3),
        law: None,
        max_contacts: 50_000_000,
    };
    let asked = AtomicU64::new(0);
    let stop_at_5 = || asked.fetch_add(1, Ordering::Relaxed) + 1 >= 5;
    let err = search_interruptible::<2, 1>(&scene, &ask, &mut |_| {}, &stop_at_5).unwrap_err();
    assert_eq!(err, SearchError::Interrupted);
    assert_eq!(asked.load(Ordering::Relaxed), 5);
    let plain = search::<2, 1>(&scene, &ask).unwrap();
    asked.store(0, Ordering::Relaxed);
    let count = || {
        asked.fetch_add(1, Ordering::Relaxed);
        false
    };
    let hooked = search_interruptible::<2, 1>(&scene, &ask, &mut |_| {}, &count).unwrap();
    assert_eq!(asked.load(Ordering::Relaxed) as usize, plain.starts);
    assert_eq!(plain.orbits.len(), hooked.orbits.len());
    assert_eq!(plain.contacts, hooked.contacts);
}
