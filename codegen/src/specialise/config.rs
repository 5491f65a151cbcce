//! The build-script API, in the style of `prost_build::Config`:
//!
//! ```no_run
//! // build.rs of a crate that depends on collision-core (with only the `d2` feature, say)
//! noslip_codegen::specialise::Config::new()
//!     .compile_scenes(&["scenes/gas2d.toml"])
//!     .expect("generate the scene kernels");
//! // src/lib.rs: pub mod gas2d { include!(concat!(env!("OUT_DIR"), "/gas2d.rs")); }
//! ```
//!
//! Each scene (or explicit [`PairSet`]) becomes `OUT_DIR/{name}.rs` (name: the file stem as
//! an identifier), written only when it changed; each scene file is announced with
//! `cargo:rerun-if-changed`.

use super::{generate, SceneModule};
use crate::write_if_changed;
use noslip_scene::{PairSet, Scene};
use std::io;
use std::path::{Path, PathBuf};

/// Configuration of a specialised-kernel generation run.
#[derive(Clone, Debug)]
pub struct Config {
    crate_path: String,
    sim_path: String,
    out_dir: Option<PathBuf>,
    sets: Vec<PairSet>,
    announce: bool,
}

impl Default for Config {
    fn default() -> Self {
        Config {
            crate_path: "collision_core".into(),
            sim_path: "noslip_sim".into(),
            out_dir: None,
            sets: Vec::new(),
            announce: true,
        }
    }
}

impl Config {
    /// The defaults: paths `collision_core` and `noslip_sim`, `$OUT_DIR`, no scenes yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The runtime crate's path where the files are included (default `collision_core`).
    pub fn crate_path(&mut self, path: impl Into<String>) -> &mut Self {
        self.crate_path = path.into();
        self
    }

    /// The simulator crate's path where the files are included (default `noslip_sim`).
    pub fn sim_path(&mut self, path: impl Into<String>) -> &mut Self {
        self.sim_path = path.into();
        self
    }

    /// Where to write (default: `$OUT_DIR`).
    pub fn out_dir(&mut self, dir: impl Into<PathBuf>) -> &mut Self {
        self.out_dir = Some(dir.into());
        self
    }

    /// Also generate an explicit list of dimension, species and pairs.
    pub fn pairs(&mut self, set: PairSet) -> &mut Self {
        self.sets.push(set);
        self
    }

    /// Print `cargo:rerun-if-changed` lines (default: yes; off outside build scripts).
    pub fn announce(&mut self, yes: bool) -> &mut Self {
        self.announce = yes;
        self
    }

    /// Read and validate `scenes`, then generate every scene and explicit pair set.
    /// A bad scene, a bad crate path or a scene whose constants overflow `f32` or `f64`
    /// ([`super::check_ranges`]) is an `InvalidData` error naming the file and place.
    pub fn compile_scenes(&mut self, scenes: &[impl AsRef<Path>]) -> io::Result<Vec<SceneModule>> {
        let mut sets = Vec::new();
        for path in scenes {
            let path = path.as_ref();
            if self.announce {
                println!("cargo:rerun-if-changed={}", path.display());
            }
            let scene = Scene::from_file(path)
                .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e.to_string()))?;
            sets.push(scene.pairs());
        }
        sets.extend(self.sets.iter().cloned());
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => PathBuf::from(std::env::var_os("OUT_DIR").ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::NotFound,
                    "OUT_DIR is not set: not in a build script? use out_dir()",
                )
            })?),
        };
        sets.iter()
            .map(|set| {
                let module = generate(set, &self.crate_path, &self.sim_path).map_err(|e| {
                    io::Error::new(
                        io::ErrorKind::InvalidData,
                        format!("scene {}: {e}", set.name),
                    )
                })?;
                write_if_changed(&out_dir.join(format!("{}.rs", module.name)), &module.source)?;
                Ok(module)
            })
            .collect()
    }
}

/// [`Config::compile_scenes`] with the defaults.
pub fn compile_scenes(scenes: &[impl AsRef<Path>]) -> io::Result<Vec<SceneModule>> {
    Config::new().compile_scenes(scenes)
}
