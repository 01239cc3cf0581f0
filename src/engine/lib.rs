//! The physics: pure, no UI. Equations, integrators, events, solvers and the paper's analytic
//! approximations.

pub mod approx;
pub mod body;
pub mod dop853;
pub mod doubt;
pub mod error;
pub mod method;
pub mod model;
pub mod par;
pub mod radau;
pub mod rod;
pub mod roots;
pub mod run;
pub mod saddle;
pub mod solve;
pub mod spinup;
pub mod stepper;
pub mod stokes;
pub mod stop;
pub mod sundman;
pub mod track;
pub mod units;
pub mod work;

pub use method::{Coupling, CouplingName, Method, Settings};
pub use model::{Frame, Initial, Release, State};
pub use run::{
    Certificate, Escape, Limit, Outcome, Run, RunError, Status, StepInfo, Stop, closed_form,
};
pub use stepper::Cost;
