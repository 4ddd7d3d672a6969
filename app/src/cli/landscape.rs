//! `dmpscope landscape`: sum d, S and J over a gain grid, as JSON.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use dmpscope_core::extract::optimum::map_and_extract;
use dmpscope_core::landscape::grid::{Axis, AxisScale, Grid, Landscape};
use dmpscope_core::report::extraction::landscape_document;
use dmpscope_core::{Extraction, Model};

use super::inputs::{InputArgs, load_model};
use super::output::{print_notices, progress_bar, write_text};

/// The gain grid on the command line.
#[derive(Debug, clap::Args)]
pub struct GridArgs {
    /// Points per axis.
    #[arg(long, default_value_t = Grid::default().dm.n)]
    pub grid: usize,
    /// D/M range.
    #[arg(long, num_args = 2, value_names = ["LO", "HI"],
          default_values_t = [Grid::default().dm.lo, Grid::default().dm.hi])]
    pub dm_range: Vec<f64>,
    /// K/M range.
    #[arg(long, num_args = 2, value_names = ["LO", "HI"],
          default_values_t = [Grid::default().km.lo, Grid::default().km.hi])]
    pub km_range: Vec<f64>,
    /// Space the axes evenly instead of geometrically.
    #[arg(long)]
    pub linear: bool,
    /// Weight of sum d in J = S + k sum d.
    #[arg(long, default_value_t = dmpscope_core::DEFAULT_K)]
    pub k: f64,
}

impl GridArgs {
    /// The grid these arguments describe.
    pub fn grid(&self) -> Grid {
        let scale = if self.linear {
            AxisScale::Linear
        } else {
            AxisScale::Log
        };
        let axis = |r: &[f64]| Axis {
            lo: r[0],
            hi: r[1],
            n: self.grid,
            scale,
        };
        Grid {
            dm: axis(&self.dm_range),
            km: axis(&self.km_range),
        }
    }
}

/// Arguments of `landscape`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    grid: GridArgs,
    /// Write the JSON here instead of stdout.
    #[arg(long, short)]
    out: Option<PathBuf>,
}

/// The landscape and extraction of the inputs.
pub fn landscape_and_optimum(
    input: &InputArgs,
    grid: &GridArgs,
) -> anyhow::Result<(
    Vec<dmpscope_core::RawDemo>,
    Arc<Model>,
    Landscape,
    Extraction,
)> {
    if !grid.k.is_finite() || grid.k < 0.0 {
        anyhow::bail!("--k must be finite and >= 0, got {}", grid.k);
    }
    let (raw, model) = load_model(input)?;
    let grid_of = grid.grid();
    grid_of.validate()?;
    let bar = progress_bar(grid_of.len() as u64, "landscape");
    let cancel = AtomicBool::new(false);
    let result = map_and_extract(&model, grid_of, grid.k, &cancel, &mut |done, _| {
        bar.set_position(done as u64);
    });
    bar.finish_and_clear();
    let (land, optimum, notices) = result?;
    print_notices(&notices);
    Ok((raw, model, land, optimum))
}

/// Writes the landscape JSON
/// ([`dmpscope_core::report::extraction::landscape_document`]): the report
/// of `dmpscope_core::report` (keys `k`, `demos`, `optimum`, `table`) plus
/// the grid's axes `dm`, `km`, every quantity of the landscape's table by
/// its key (`d_sum`, `s`, `a_peak`, `e_sum`) and `j`, as rows over D/M.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (_, model, land, optimum) = landscape_and_optimum(&args.input, &args.grid)?;
    let doc = landscape_document(&model, &land, &optimum, args.grid.k)?;
    let mut text = serde_json::to_string(&doc)?;
    text.push('\n');
    write_text(args.out.as_deref(), &text)
}
