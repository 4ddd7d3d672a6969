//! Report: Table I and the extraction as one serde type ([`summary`]), the
//! paper's presets ([`presets`]), and their renderings for terminals,
//! spreadsheets and documents ([`table_text`], [`text`]).
//!
//! May use: extract, landscape, prepare, load.

pub mod presets;
pub mod summary;
pub mod table;
pub mod table_text;
pub mod text;
