//! Writes the phase portraits of the shipped tables that docs/tables.md shows, as
//! docs/tables/SCENE-KIND-ID.png (`cargo run --release -p noslip-sim --example
//! table_portraits`); `sim/tests/tables.rs` checks that the shipped files are what this
//! produces.

use noslip_scene::Scene;
use noslip_sim::boundary_map::portraits;
use noslip_sim::portrait::{DOCS_EVENTS, DOCS_TABLES};
use noslip_sim::setup::setup;
use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for name in DOCS_TABLES {
        let scene = Scene::from_file(&root.join(format!("scenes/{name}.toml"))).unwrap();
        let portraits = collision_core::with_dim!(
            scene.dim,
            |N, S| portraits::<N, S>(setup::<N, S>(&scene).unwrap(), DOCS_EVENTS).unwrap(),
            unreachable!()
        );
        for portrait in portraits {
            let (kind, id) = portrait.body.kind_id();
            let file = root.join(format!("docs/tables/{name}-{kind}-{id}.png"));
            std::fs::write(&file, portrait.png(&format!("{name}.toml"))).unwrap();
            println!("{} ({} points)", file.display(), portrait.points.len());
        }
    }
}
