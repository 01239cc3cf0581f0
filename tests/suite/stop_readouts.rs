//! The readouts inside a stop's last stretch (issue 42): the state the explorer shows at a τ
//! inside the step that ends in a stop comes from that stop's closed form, not from a cubic
//! through its ends. Case B at the default setting showed |u| 4.1e-6 at τ 2.700 (`2`, space,
//! `.`×54) where the independent reference (`common::sundman`) has 5.8638e-6.

use crate::common::sundman;
use turntable::engine::method::Scheme;
use turntable::engine::{Initial, Run, Settings};

/// The run stepped to `tau` as the explorer does (steps sized by the integrator until one
/// reaches it, `sim::Motion::step`), read there.
fn readout(i: Initial, scheme: Scheme, tau: f64) -> (f64, f64) {
    let mut run = Run::new(
        i,
        Settings {
            scheme,
            ..Settings::default()
        },
    )
    .unwrap();
    while run.goes_on(tau, false) {
        run.step(f64::INFINITY).unwrap();
    }
    let s = run.state_at(tau).unwrap();
    (s.u_lab().length(), s.xi())
}

#[test]
fn the_speed_inside_the_last_step_is_the_reference_s() {
    let b = (0.5, 0.0, 0.6);
    let i = Initial::velocity(b.0, b.1, b.2);
    // B stops at τ 2.70010714; the last step (a closed-form stop) spans the last ~3e-4.
    for tau in [2.6999, 2.69995, 2.7, 2.70005, 2.7001] {
        let (speed, xi) = sundman::at(b.0, b.1, b.2, 1e-12, tau).unwrap();
        for scheme in [Scheme::Dp54 { tol: 1e-10 }, Scheme::Dop853 { tol: 1e-10 }] {
            let (s, x) = readout(i, scheme, tau);
            assert!(
                (s - speed).abs() <= 1e-3 * speed,
                "{scheme:?} τ {tau}: |u| {s:e} against {speed:e}"
            );
            assert!(
                (x - xi).abs() <= 1e-9,
                "{scheme:?} τ {tau}: ξ {x} against {xi}"
            );
        }
    }
    let (s, _) = readout(i, Scheme::Dp54 { tol: 1e-10 }, 2.7);
    assert!((s - 5.8638e-6).abs() < 1e-9, "{s:e}");
}
