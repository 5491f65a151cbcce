//! Writes the phase portraits of the shipped tables that docs/tables.md shows, as
//! docs/tables/SCENE-KIND-ID.png (`cargo run --release -p noslip-sim --example
//! table_portraits`); `sim/tests/tables.rs` checks that the shipped files are what this
//! produces.

use noslip_scene::Scene;
use noslip_sim::boundary_map::portrait_points;
use noslip_sim::portrait::{portrait_png, DOCS_EVENTS, DOCS_TABLES};
use noslip_sim::setup::setup;
use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for name in DOCS_TABLES {
        let scene = Scene::from_file(&root.join(format!("scenes/{name}.toml"))).unwrap();
        let points = collision_core::with_dim!(
            scene.dim,
            |N, S| portrait_points::<N, S>(setup::<N, S>(&scene).unwrap(), DOCS_EVENTS).unwrap(),
            unreachable!()
        );
        for (body, points) in points {
            let (kind, id) = body.kind_id();
            let file = root.join(format!("docs/tables/{name}-{kind}-{id}.png"));
            std::fs::write(&file, portrait_png(&points, scene.dim == 2)).unwrap();
            println!("{} ({} points)", file.display(), points.len());
        }
    }
}
