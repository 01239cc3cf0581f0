//! The integration tests, one binary: each module is one area (its file's header says what it
//! checks). One binary links the crate once: 37 binaries spent most of a cold `cargo test`
//! linking on 2 cores. Run one area with `cargo test --release --test suite AREA::`.

mod accuracy;
mod angles;
mod approx;
mod architecture;
mod arrows;
mod bench;
mod body;
mod body_si;
mod bounded;
mod chart_labels;
mod cli;
mod common;
mod config;
mod coupling;
mod curve_cells;
mod dop853;
mod explorer;
mod extremes;
mod files;
mod frictionless;
mod fuzz;
mod honest;
mod keys;
mod lessons;
mod link;
mod map_cells;
mod outputs;
mod pages;
mod paper;
mod pins;
mod plain;
mod plot;
mod properties;
mod proptests;
mod prose;
mod readme;
mod reference;
mod replay;
mod rim;
mod rim_times;
mod rod;
#[cfg(feature = "serve")]
mod serve;
#[cfg(feature = "serve")]
mod serve_class;
#[cfg(feature = "serve")]
mod serve_exports;
#[cfg(feature = "serve")]
mod serve_plain;
#[cfg(feature = "serve")]
mod serve_settings;
mod si;
mod spin_explorer;
mod spinup;
mod split;
mod stop_readouts;
mod terminal;
mod terminals;
mod text;
mod tolerance;
mod validation;
mod words;
mod work_precision;
