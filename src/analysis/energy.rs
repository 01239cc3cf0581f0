//! The energy identity along a path: E − E(0) beside the work friction did, which equal
//! each other since dE/dτ = −|u|.

use crate::engine::State;

/// E − E(0) and −∫|u|dτ (trapezoids on the path's grid): equal, since dE/dτ = −|u|.
pub fn energy_pair(path: &[State]) -> [Vec<(f64, f64)>; 2] {
    energy_pair_drag(path, None)
}

/// [`energy_pair`], or under Stokes drag γ (extends the paper) E − E(0) and −γ∫|u|²dτ, equal
/// since there dE/dτ = −γ|u|².
pub fn energy_pair_drag(path: &[State], drag: Option<f64>) -> [Vec<(f64, f64)>; 2] {
    let power = |s: &State| {
        let u = s.u_lab().length();
        drag.map_or(u, |g| g * u * u)
    };
    let e0 = path.first().map_or(0.0, State::energy);
    let mut work = 0.0;
    let mut w = Vec::with_capacity(path.len());
    for (i, s) in path.iter().enumerate() {
        if i > 0 {
            let p = &path[i - 1];
            work -= 0.5 * (s.tau - p.tau) * (power(s) + power(p));
        }
        w.push((s.tau, work));
    }
    let e = path.iter().map(|s| (s.tau, s.energy() - e0)).collect();
    [e, w]
}
