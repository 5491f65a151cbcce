//! `noslip gen --scene FILE`: print the kernels specialised to a scene, with op counts.

use crate::exit::{self, Exit, Failure};
use crate::out::{outln, print};
use noslip_codegen::specialise::generate;
use noslip_scene::Scene;
use noslip_verify::checks::specialised::check;
use std::path::PathBuf;

pub(crate) const LONG_ABOUT: &str = "\
Print the Rust module of kernels specialised to a scene: only its dimension, only the pair
kinds it can meet (ball-ball per species pair, ball-wall per species and wall, ball-obstacle
per species), each species' mass, radius and gamma2 folded into exact literals, so no
division is left at run time. The header lists every kernel's op count beside the generic
kernel's. The same module is what `noslip_codegen::specialise::Config::compile_scenes`
writes from a build script.

--check K compares every specialised kernel, exactly and at K random points, with the generic
kernel run with the same constants, and exits 1 on any difference.";

/// The arguments of `noslip gen`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file (TOML; see docs/scenes.md).
    #[arg(long)]
    pub scene: PathBuf,
    /// The runtime crate's path where the module is included.
    #[arg(long, default_value = "collision_core")]
    pub crate_path: String,
    /// Print only the op-count table (generic against specialised), not the module.
    #[arg(long)]
    ops: bool,
    /// Check the specialised kernels against the generic map at this many exact points.
    #[arg(long, value_name = "K")]
    pub check: Option<usize>,
}

/// What `gen` can return.
pub const CODES: &[Exit] = &[
    Exit::Success,
    Exit::CheckFailed,
    Exit::OutputFailed,
    Exit::BadInput,
];

/// Print the scene's specialised kernels (or only their op counts), or with `--check` compare
/// them exactly with the generic kernels.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let scene = Scene::from_file(&args.scene).map_err(|e| Failure::bad_input(e.to_string()))?;
    let set = scene.pairs();
    if let Some(points) = args.check {
        let results = collision_core::with_dim!(
            set.dim,
            |N, S| check::<N, S>(&set, points, 2026),
            unreachable!("scene validation keeps dim in {:?}", collision_core::DIMS)
        );
        let mut failed = false;
        for r in &results {
            let ok = r.mismatches == 0;
            failed |= !ok;
            outln!(
                "{} {}: {} of {} exact points equal the generic map",
                if ok { "ok  " } else { "FAIL" },
                r.pair.fn_name(),
                r.points - r.mismatches,
                r.points
            )?;
        }
        return Ok(if failed {
            Exit::CheckFailed
        } else {
            Exit::Success
        });
    }
    let module = generate(&set, &args.crate_path, "noslip_sim")
        .map_err(|e| Failure::bad_input(format!("{}: {e}", args.scene.display())))?;
    if args.ops {
        outln!("| kernel | kind | specialised ops | generic ops |")?;
        outln!("|---|---|---|---|")?;
        for p in &module.pairs {
            outln!(
                "| `{}` | {} | {} | {} (`{}`) |",
                p.pair.fn_name(),
                p.pair.kind(),
                p.ops,
                p.generic_ops,
                noslip_codegen::specialise::variant(p.pair).name()
            )?;
        }
    } else {
        print(&module.source)?;
    }
    Ok(Exit::Success)
}
