//! From command-line paths to a fitted model: folders expanded to their
//! `*.mcap` files, demos pooled in command-line order then topic name,
//! preprocessing and DMP settings shared by every subcommand.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, bail};
use dmpscope_core::dmp::DmpSettings;
use dmpscope_core::io::load_path;
use dmpscope_core::{Model, PrepSettings, RawDemo, prepare};

/// Input files and the settings that turn them into a model.
#[derive(Debug, clap::Args)]
pub struct InputArgs {
    /// MCAP files, or folders (every `*.mcap` in them, sorted by name).
    #[arg(required = true, value_name = "FILES")]
    pub files: Vec<PathBuf>,
    /// Savitzky-Golay window (samples, odd).
    #[arg(long, default_value_t = 21)]
    pub sg_window: usize,
    /// Savitzky-Golay polynomial order.
    #[arg(long, default_value_t = 3)]
    pub sg_order: usize,
    /// Number of DMP basis functions.
    #[arg(long, default_value_t = 100)]
    pub basis: usize,
}

impl InputArgs {
    fn prep(&self) -> PrepSettings {
        PrepSettings {
            sg_window: self.sg_window,
            sg_order: self.sg_order,
            ..PrepSettings::default()
        }
    }

    fn dmp(&self) -> DmpSettings {
        DmpSettings {
            basis_functions: self.basis,
            ..DmpSettings::default()
        }
    }
}

/// The files named, folders expanded.
pub fn expand(paths: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for path in paths {
        if path.is_dir() {
            let mut found: Vec<PathBuf> = std::fs::read_dir(path)
                .with_context(|| format!("{}: cannot list folder", path.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    p.extension()
                        .is_some_and(|e| e.eq_ignore_ascii_case("mcap"))
                })
                .collect();
            found.sort();
            if found.is_empty() {
                bail!("{}: folder holds no .mcap file", path.display());
            }
            out.extend(found);
        } else {
            out.push(path.clone());
        }
    }
    Ok(out)
}

/// Every demo in the files, in command-line order then topic name; skipped
/// topics are reported on stderr.
pub fn load_demos(paths: &[PathBuf]) -> anyhow::Result<Vec<RawDemo>> {
    let mut demos = Vec::new();
    for path in expand(paths)? {
        let loaded = load_path(Path::new(&path))?;
        for (topic, schema) in &loaded.skipped {
            eprintln!("note: {}: skipped topic {topic} ({schema})", path.display());
        }
        demos.extend(loaded.demos);
    }
    Ok(demos)
}

/// The model of every demo in the inputs.
pub fn load_model(args: &InputArgs) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    load_model_with(&args.files, &args.prep(), args.dmp())
}

/// The model of every demo in `files` with explicit settings.
pub fn load_model_with(
    files: &[PathBuf],
    prep: &PrepSettings,
    dmp: DmpSettings,
) -> anyhow::Result<(Vec<RawDemo>, Arc<Model>)> {
    let raw = load_demos(files)?;
    let prepared = raw
        .iter()
        .map(|r| prepare(r, prep))
        .collect::<Result<Vec<_>, _>>()?;
    if prepared.len() < 2 {
        eprintln!(
            "note: only {} demonstration: S needs two or more and is 0 here",
            prepared.len()
        );
    }
    let model = Model::new(prepared, dmp)?;
    Ok((raw, Arc::new(model)))
}
