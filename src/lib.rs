#![cfg_attr(not(test), deny(clippy::unwrap_used))]
//! turntable: a particle sliding with dry friction on a rotating table
//! (Agha, Gupta & Joseph, Am. J. Phys. 83, 126 (2015)).

pub mod analysis;
pub mod app;
pub mod asciicast;
pub mod bench;
pub(crate) mod check;
pub mod cli;
pub use turntable_engine as engine;
pub mod error;
pub mod files;
pub mod film;
pub mod kept;
pub mod lesson;
pub mod pin;
pub mod plot;
pub mod present;
pub mod replay;
pub mod rng;
pub mod scene;
pub mod script;
#[cfg(feature = "serve")]
pub mod serve;
pub mod session;
pub mod sim;
pub mod terminal;
pub mod text;
pub mod theme;
pub mod ui;
