//! `noslip gen --scene FILE`: print the kernels specialised to a scene, with op counts;
//! `noslip gen --lang c|opencl --out DIR`: write the kernels in another language.

use crate::dims::{parse_dims, Dims};
use crate::exit::{self, Exit, Failure};
use crate::out::{outln, print};
use crate::publish::write_atomic;
use noslip_codegen::backend::{self, Lang};
use noslip_codegen::specialise::generate;
use noslip_scene::Scene;
use noslip_verify::checks::specialised::check;
use noslip_verify::suite::check_points;
use std::path::{Path, PathBuf};

pub(crate) const LONG_ABOUT: &str = "\
Print the Rust module of kernels specialised to a scene: only its dimension, only the pair
kinds it can meet (ball-ball per species pair, ball-wall per species and wall, ball-obstacle
per species), each species' mass, radius and gamma2 folded into exact literals, so no
division is left at run time. The header lists every kernel's op count beside the generic
kernel's. The same module is what `noslip_codegen::specialise::Config::compile_scenes`
writes from a build script.

--check K compares every specialised kernel, exactly and at K random points, with the generic
kernel run with the same constants, and exits 1 on any difference.

--lang c or --lang opencl writes the kernels, from the same scheduled DAG and in the same
operation order as the Rust kernels, into --out DIR: noslip_kernels.h (C99, usable from C++)
or noslip_kernels.cl (OpenCL C: device functions and batch kernels) with the free and fixed
kernels of every dimension of --dims, in double and float, plain and FMA, and their certified
companions (each output with a rigorous error bound), then the energy-conserving correction
(noslip_conserve_fixed_dN, noslip_conserve_free_dN: the bits of --conserve-energy), in OpenCL
each with its batch kernel too; with --scene also the scene's specialised kernels (noslip_scene_NAME.h or .cl). Each file is written
atomically. The ABI, the preconditions and the compiler flags: docs/backends.md.";

/// The arguments of `noslip gen`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file (TOML; see docs/scenes.md). Required for --lang rust.
    #[arg(long)]
    pub scene: Option<PathBuf>,
    /// The language: rust (print the scene's module), c or opencl (write files into --out).
    #[arg(long, default_value = "rust", value_parser = parse_lang)]
    pub lang: Language,
    /// With --lang c or opencl: the dimensions of the generic kernels, `2..6` or `2,3`.
    #[arg(long, default_value = "2..6", value_parser = parse_dims)]
    pub dims: Dims,
    /// With --lang c or opencl: the directory the files are written into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// The runtime crate's path where the module is included.
    #[arg(long, default_value = "collision_core")]
    pub crate_path: String,
    /// Print only the op-count table (generic against specialised), not the module.
    #[arg(long)]
    ops: bool,
    /// Check the specialised kernels against the generic map at this many exact points
    /// (1 to 1024).
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

/// The value of `--lang`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Language {
    /// `rust`: the scene's Rust module, printed.
    Rust,
    /// A language with a back end in `noslip_codegen::backend`.
    Backend(Lang),
}

/// Parse `--lang`: `rust`, `c` or `opencl`.
fn parse_lang(s: &str) -> Result<Language, String> {
    if s == "rust" {
        return Ok(Language::Rust);
    }
    Lang::ALL
        .into_iter()
        .find(|l| l.name() == s)
        .map(Language::Backend)
        .ok_or_else(|| format!("unknown language {s:?}: expected rust, c or opencl"))
}

/// Print the scene's specialised kernels (or only their op counts), or with `--check` compare
/// them exactly with the generic kernels; with `--lang c|opencl`, write the kernels' files.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    if let Language::Backend(lang) = args.lang {
        return write_language(args, lang);
    }
    let Some(scene_path) = &args.scene else {
        return Err(Failure::bad_input(
            "--scene: required with --lang rust (the Rust module of a scene's kernels)",
        ));
    };
    if args.out.is_some() {
        return Err(Failure::bad_input(
            "--out: only with --lang c or opencl (--lang rust prints the module)",
        ));
    }
    if let Some(points) = args.check {
        check_points(points).map_err(|m| Failure::bad_input(format!("--check: {m}")))?;
    }
    let scene = Scene::from_file(scene_path).map_err(|e| Failure::bad_input(e.to_string()))?;
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
    let module = generate(&set, &args.crate_path, "noslip_sim").map_err(|e| {
        // A bad crate path is the option's fault, not the scene's.
        let whose = match e {
            noslip_codegen::specialise::GenerateError::CratePath(_) => "--crate-path".to_string(),
            _ => scene_path.display().to_string(),
        };
        Failure::bad_input(format!("{whose}: {e}"))
    })?;
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
                noslip_codegen::specialise::generic_name(&set, p.pair)
            )?;
        }
    } else {
        print(&module.source)?;
    }
    Ok(Exit::Success)
}

/// `--lang c|opencl`: write the generic kernels of `--dims` (and with `--scene` the scene's)
/// into `--out`, each file atomically, then list what was written.
fn write_language(args: &Args, lang: Lang) -> Result<Exit, Failure> {
    let Some(out) = &args.out else {
        return Err(Failure::bad_input(format!(
            "--out: required with --lang {} (the directory to write the files into)",
            lang.name()
        )));
    };
    if args.check.is_some() || args.ops {
        return Err(Failure::bad_input(format!(
            "--check and --ops: only with --lang rust, not --lang {}",
            lang.name()
        )));
    }
    let mut files = vec![(
        backend::file_name(lang),
        backend::generate(lang, &args.dims.0),
    )];
    if let Some(path) = &args.scene {
        let set = Scene::from_file(path)
            .map_err(|e| Failure::bad_input(e.to_string()))?
            .pairs();
        let source = backend::generate_scene(lang, &set)
            .map_err(|e| Failure::bad_input(format!("{}: {e}", path.display())))?;
        files.push((backend::scene_file_name(lang, &set), source));
    }
    if out.is_file() {
        return Err(Failure::bad_input(format!(
            "--out: {} is a file, not a directory",
            out.display()
        )));
    }
    std::fs::create_dir_all(out)
        .map_err(|e| Failure::output(format!("--out: {}: {e}", out.display())))?;
    for (name, source) in &files {
        let path = Path::new(out).join(name);
        write_atomic(&path, source)
            .map_err(|e| Failure::output(format!("{}: {e}", path.display())))?;
    }
    for (name, _) in &files {
        outln!("wrote {}", Path::new(out).join(name).display())?;
    }
    Ok(Exit::Success)
}
