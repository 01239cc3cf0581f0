//! The words a student reads are right (issue 44 item 12): the circle inside which friction
//! holds is drawn where it is (R_max on the paper's table, μs/μk with static friction above
//! kinetic, shrinking on a table spinning up, none under Stokes drag), Stokes drag is not
//! called friction, the toppling risk is the run's largest, E, τ and Eq. 22's μ are said for
//! what they are.

use super::common::{render, sync};
use turntable::app::App;
use turntable::app::pages::Page;
use turntable::engine::{Coupling, Frame};
use turntable::plot::page::table::{Picture, RING_LABEL};
use turntable::scene::Scene;
use turntable::theme::Theme;

fn panel_of(app: &App) -> Vec<String> {
    turntable::ui::panel::lines(app, &Theme::builtin("dark").unwrap())
        .iter()
        .map(|l| l.to_string())
        .collect()
}

fn with_coupling(preset: &str, coupling: Coupling) -> App {
    let mut scene = Scene::preset(preset).unwrap();
    scene.settings.coupling = coupling;
    App::new(scene)
}

/// On the paper's table the ring is ξ = 1, R_max; with μs/μk = 1.5 a particle can rest out to
/// ξ = 1.5, and the ring is there, not labelled R_max.
#[test]
fn the_ring_is_where_friction_holds_on_a_steady_table() {
    let app = App::new(Scene::preset("A").unwrap());
    let ring = Picture::in_frame(&app, Frame::Lab).table.ring.unwrap();
    assert_eq!((ring.r, ring.label.as_str()), (1.0, RING_LABEL));
    let app = with_coupling("A", Coupling::Coulomb { hold: 1.5 });
    for frame in [Frame::Lab, Frame::Table] {
        let ring = Picture::in_frame(&app, frame).table.ring.unwrap();
        assert_eq!(ring.r, 1.5);
        assert_eq!(ring.label, "friction holds ξ≤1.500");
        assert!(!ring.label.contains("R_max"));
    }
}

/// On a table spinning up the ring is where friction can hold a coin at rest now,
/// (μs/μk)/√(Ω⁴ + Ω̇²): it shrinks as the table speeds up, and the coin rides while inside it
/// and slips as the ring passes it — at μs/μk = 1 and at 1.5.
#[test]
fn the_spin_ups_ring_shrinks_and_the_coin_slips_as_it_passes() {
    for hold in [1.0, 1.5] {
        let mut app = with_coupling("spin", Coupling::Coulomb { hold });
        let ramp = app.scene().spin.unwrap();
        let xi0 = app.initial().xi0;
        let (mut last, mut rode, mut slid) = (f64::INFINITY, 0, 0);
        while app.sim().now().tau < 20.0 && slid < 5 {
            app.tick();
            let now = app.sim().now();
            let ring = Picture::in_frame(&app, Frame::Table).table.ring.unwrap();
            let w = ramp.omega(now.tau);
            let want = hold / (w.powi(4) + ramp.rate * ramp.rate).sqrt();
            assert!((ring.r - want).abs() <= 1e-12 * want, "τ {}", now.tau);
            assert!(ring.r < last, "the ring only shrinks");
            assert!(!ring.label.contains("R_max"), "{}", ring.label);
            last = ring.r;
            if app.sim().motion().riding(&now) {
                assert!(xi0 <= ring.r * (1.0 + 1e-9), "riding outside the ring");
                rode += 1;
            } else {
                assert!(xi0 >= ring.r * (1.0 - 1e-9), "slipped inside the ring");
                slid += 1;
            }
        }
        assert!(rode > 50 && slid == 5, "{rode} {slid}");
    }
}

/// Under Stokes drag nothing is held: no ring, and the force opposing u is drag, not friction
/// (in both frames, on the canvas and in the legend).
#[test]
fn stokes_drag_holds_nothing_and_is_not_friction() {
    let mut app = with_coupling("A", Coupling::Stokes { gamma: 0.4 });
    let _ = turntable::app::update(&mut app, turntable::app::Action::ToggleForces);
    assert!(app.view().forces);
    for frame in [Frame::Lab, Frame::Table] {
        if app.view().frame != frame {
            let _ = turntable::app::update(&mut app, turntable::app::Action::ToggleFrame);
        }
        let pic = Picture::in_frame(&app, frame);
        assert!(pic.table.ring.is_none());
        let labels: Vec<_> = pic.point.unwrap().arrows.iter().map(|a| a.label).collect();
        assert!(
            labels.contains(&"dr") && !labels.contains(&"fr"),
            "{labels:?}"
        );
        let panel = panel_of(&app).join("\n");
        assert!(
            panel.contains("Stokes drag") && !panel.contains("friction"),
            "{panel}"
        );
    }
    // μ = 0: nothing holds either.
    let mut app = App::new(Scene::preset("A").unwrap());
    app.press(turntable::app::Chord::new(
        crossterm::event::KeyCode::Char('F'),
        crossterm::event::KeyModifiers::NONE,
    ));
    assert!(app.initial().frictionless);
    assert!(Picture::in_frame(&app, Frame::Lab).table.ring.is_none());
}

/// E is said where it is shown (the energy certificate, the time plots' energy panel), τ of
/// the spin-up is t·Ω_ref, and Eq. 22's μ is μ_k, the spin-up's μ_s.
#[test]
fn e_tau_and_mu_are_said_for_what_they_are() {
    // fig2: at rest on the table at ξ0 = 1.1, E = −0.605 < −½ at once.
    let app = App::new(Scene::preset("fig2").unwrap());
    let panel = panel_of(&app).join("\n");
    assert!(panel.contains("E < −½: cannot rest"), "{panel}");
    assert!(panel.contains("E = ½|u|²−½ξ² (table)"), "{panel}");
    let s = app.sim().now();
    assert!(s.energy() < -0.5 && (s.energy() + 0.5 * 1.1 * 1.1).abs() < 1e-12);
    let mut app = App::new(Scene::preset("C").unwrap());
    super::common::turn_to(&mut app, Page::TimePlots);
    let screen = render(&mut app, 120, 40);
    assert!(
        screen.contains("E = ½|u|² − ½ξ² (table frame), dE/dτ = −|u|:"),
        "{screen}"
    );
    let app = App::new(Scene::preset("spin").unwrap());
    let panel = panel_of(&app);
    assert!(
        panel.iter().any(|l| l == "τ      0.000 = t·Ω_ref"),
        "{panel:?}"
    );
    let mut app = App::new(Scene::preset("A").unwrap());
    super::common::turn_to(&mut app, Page::RestRadius);
    sync(&mut app);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains("μ_k = 0.1"), "{screen}");
    assert!(
        screen.contains("Eq. 22: μ_k = Ω² r0c / (g ξ0c)"),
        "{screen}"
    );
    assert!(screen.contains("a spin-up (7) measures μ_s"), "{screen}");
}
