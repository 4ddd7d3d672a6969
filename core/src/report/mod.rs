//! Report: Table I and the extraction as one serde type ([`summary`]), the
//! paper's presets ([`presets`]), gain sets compared side by side
//! ([`compare`]), and their renderings for terminals, spreadsheets and
//! documents ([`table_text`], [`text`]); the landscape's and the
//! extraction's documents as the CLI and the Python package write them
//! ([`extraction`]).
//!
//! May use: generalise, extract, landscape, prepare, load.

pub mod compare;
pub mod compare_text;
pub mod extraction;
pub mod presets;
pub mod summary;
pub mod table;
pub mod table_text;
pub mod text;
