//! The integration tests, one binary: each module is one area (its file's header says what it
//! checks). One binary links the crate once: 37 binaries spent most of a cold `cargo test`
//! linking on 2 cores. Run one area with `cargo test --release --test suite AREA::`.

mod angles;
mod approx;
mod architecture;
mod arrows;
mod bench;
mod body;
mod body_si;
mod bounded;
mod cli;
mod common;
mod config;
mod coupling;
mod dop853;
mod explorer;
mod extremes;
mod files;
mod frictionless;
mod fuzz;
mod honest;
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
mod readme;
mod reference;
mod replay;
mod rim;
mod rim_times;
mod rod;
mod serve;
mod si;
mod spinup;
mod split;
mod terminal;
mod terminals;
mod text;
mod validation;
