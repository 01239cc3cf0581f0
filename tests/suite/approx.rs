//! Figs. 1 and 2: the Sec. III approximations agree with converged runs inside their validity
//! windows and depart outside them.

use turntable::engine::approx::{TABLE_REST_WINDOW, lab_rest, lab_rest_window, table_rest};
use turntable::engine::{Initial, Release, Run, Settings, State};

fn states(i: Initial, taus: &[f64]) -> Vec<State> {
    let mut run = Run::new(i, Settings::dp54(1e-12)).unwrap();
    taus.iter()
        .map(|&t| {
            run.run(t, false).unwrap();
            run.state()
        })
        .collect()
}

#[test]
fn fig1_lab_rest_at_500() {
    let xi0 = 500.0;
    let w = lab_rest_window(xi0);
    assert!((w - 500f64.sqrt()).abs() < 1e-12);
    let taus = [0.25 * w, 0.5 * w, w, 2.0 * w];
    let s = states(Initial::at_rest(xi0, Release::LabRest), &taus);
    let err = |k: usize| {
        let (xi, theta) = lab_rest(xi0, taus[k]);
        let th = s[k].r.y.atan2(s[k].r.x);
        ((s[k].xi() - xi) / (xi - xi0), (th - theta) / theta)
    };
    // Relative errors of ξ − ξ0 and of θ.
    let (e_xi, e_th) = err(0);
    assert!(e_xi.abs() < 3e-3 && e_th.abs() < 2e-4, "{e_xi} {e_th}");
    let (e_xi, e_th) = err(1);
    assert!(e_xi.abs() < 1e-2 && e_th.abs() < 5e-3, "{e_xi} {e_th}");
    let (e_xi, e_th) = err(2);
    assert!(e_xi.abs() < 0.07 && e_th.abs() < 0.06, "{e_xi} {e_th}");
    let (e_xi, e_th) = err(3);
    assert!(e_xi.abs() > 0.3 && e_th.abs() > 0.3, "{e_xi} {e_th}");
}

#[test]
fn fig2_table_rest_just_outside_xi_1() {
    for (xi0, inside, outside) in [(1.1, 0.02, 0.25), (1.5, 0.05, 0.5)] {
        let taus = [0.5, TABLE_REST_WINDOW, 3.0];
        let s = states(Initial::at_rest(xi0, Release::TableRest), &taus);
        let rel = |k: usize| {
            let (xi, _, _) = table_rest(xi0, taus[k]);
            (s[k].xi() - xi) / (xi - 1.0)
        };
        assert!(rel(0).abs() < inside / 4.0, "xi0 {xi0}: {}", rel(0));
        assert!(rel(1).abs() < inside, "xi0 {xi0}: {}", rel(1));
        assert!(rel(2).abs() > outside, "xi0 {xi0}: {}", rel(2));
    }
}

/// Eq. 20 for the table-frame angle drops the friction term that dominates right after a
/// release from rest: it overstates how far the particle falls behind the table.
#[test]
fn fig2_eq25_overstates_the_lag() {
    let s = states(Initial::at_rest(1.1, Release::TableRest), &[0.25])[0];
    let q = s.q();
    let (_, _, theta) = table_rest(1.1, 0.25);
    let num = q.y.atan2(q.x);
    assert!(num < 0.0 && theta < 0.0);
    assert!(theta / num > 5.0, "Eq. 20 gives {theta}, converged {num}");
}
