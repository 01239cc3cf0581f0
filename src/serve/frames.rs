//! A class's frames drawn once for all its followers of one size: followers handed the class
//! at one place and given every lead since are in one state, but for their own notices and
//! answers, so all of a frame but its status line ([`crate::ui::draw_common`]) is the same for
//! each of one size and theme. The first to draw it leaves it here; the others copy its cells
//! and draw their own line over them ([`crate::session::Explorer::draw_sharing`]).

use super::class::Place;
use crate::app::App;
use crate::app::pages::Page;
use crate::kept::Kept;
use crate::session::Common;
use crate::theme::Theme;
use std::sync::{Arc, OnceLock};

/// What a frame but its status line is a function of, for a follower.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    pub at: Place,
    pub size: (u16, u16),
    pub theme: Theme,
    /// Its own answer to the question on screen: its caption says it.
    pub own: Option<bool>,
}

impl Key {
    /// A follower's key at `at`, if its page is drawn from its state alone: the analysis
    /// pages are drawn from the pieces its own session computed, each follower's own.
    pub fn of(at: Place, app: &App, theme: &Theme) -> Option<Key> {
        if !matches!(app.view().page, Page::Turntable | Page::TimePlots) {
            return None;
        }
        Some(Key {
            at,
            size: app.screen(),
            theme: theme.clone(),
            own: app.lesson().question.as_ref().and_then(|q| q.own),
        })
    }
}

/// Frames kept at most: a class's sizes and themes, its followers' answers, and the places
/// the slower followers are still at.
const KEPT: usize = 32;
/// Cells kept at most, all frames together (four of the largest screen `serve` draws by
/// default): what the frames hold is bounded however large the screens.
const CELLS: usize = 4 * 400 * 150;

/// The frames the class's followers share, newest last.
pub struct Frames {
    kept: Kept<Key, OnceLock<Common>>,
}

fn cells(k: &Key) -> usize {
    usize::from(k.size.0) * usize::from(k.size.1)
}

impl Default for Frames {
    fn default() -> Frames {
        Frames {
            kept: Kept::weighed(KEPT, cells, CELLS),
        }
    }
}

impl Frames {
    /// The frame for `key`: drawn, being drawn by another follower, or to be drawn by the
    /// caller (see `Explorer::draw_sharing`). The oldest go past [`KEPT`] or [`CELLS`].
    pub fn at(&self, key: &Key) -> Arc<OnceLock<Common>> {
        self.kept.slot(key, |_| OnceLock::new())
    }

    /// `presenter` left (None: everyone did): its class's frames go, none being drawn at
    /// its places again.
    pub fn forget(&self, presenter: Option<u64>) {
        self.kept
            .retain(|k| presenter.is_some_and(|p| k.at.presenter != p));
    }

    /// Frames kept now.
    #[cfg(test)]
    fn kept(&self) -> usize {
        self.kept.kept()
    }
}

#[cfg(test)]
mod tests {
    use super::super::screen::Screen;
    use super::*;
    use crate::app::Chord;
    use crate::app::state::InClass;
    use crate::session::Explorer;
    use crossterm::event::{KeyCode, KeyModifiers};
    use proptest::prelude::*;

    fn press(s: &mut Explorer<Screen>, code: KeyCode) {
        s.press(Chord::new(code, KeyModifiers::NONE));
    }

    /// A follower's bytes for the frame it draws now.
    fn bytes(s: &mut Explorer<Screen>) -> Vec<u8> {
        s.term
            .backend_mut()
            .take(&mut Vec::new())
            .unwrap_or_default()
    }

    /// The class as a follower of `w` × `h` holds it: playing, on the `page`th page,
    /// its help open or not, a question asked or not.
    fn class(w: u16, h: u16, ascii: bool, page: usize, help: bool, asked: bool) -> App {
        let mut app = App::new(crate::scene::Scene::default_scene());
        crate::session::tell_size(&mut app, w, h);
        app.tell_class(InClass::Following);
        let marker = if ascii {
            ratatui::symbols::Marker::Dot
        } else {
            ratatui::symbols::Marker::Braille
        };
        let theme = Theme::builtin("dark").unwrap().with_marker(marker);
        let mut s = Explorer::new(app, theme, Screen::new(w, h), None).unwrap();
        s.app.play(None);
        for _ in 0..page {
            press(&mut s, KeyCode::Tab);
        }
        if asked {
            s.app.ask(crate::text::Clean::new("Will it escape? (y/n)"));
        }
        if help {
            press(&mut s, KeyCode::Char('?'));
        }
        s.app
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// What a follower sees with the frame another follower drew (its notice another,
        /// its answer the same) is, byte for byte, what it sees drawing alone, frame after
        /// frame as the class plays: at any size (80×24 and 60×20 always among them, and
        /// those too small to draw), on the turntable and the time plots, the help open or
        /// not, a question on screen with this follower's own answer or none, ASCII or not.
        #[test]
        fn a_followers_screen_from_the_shared_frame_is_the_one_it_draws_alone(
            size in prop_oneof![
                Just((80u16, 24u16)),
                Just((60, 20)),
                (30u16..140, 8u16..50),
            ],
            ascii in any::<bool>(),
            page in 0usize..2,
            help in any::<bool>(),
            own in prop_oneof![Just(None), Just(Some(true)), Just(Some(false))],
            ticks in proptest::collection::vec(1usize..40, 3),
        ) {
            let (w, h) = size;
            let app = class(w, h, ascii, page, help, own.is_some());
            let theme = Theme::builtin("dark").unwrap().with_marker(if ascii {
                ratatui::symbols::Marker::Dot
            } else {
                ratatui::symbols::Marker::Braille
            });
            let session = |notice: &str| {
                let mut s = Explorer::new(app.clone(), theme.clone(), Screen::new(w, h), None)
                    .unwrap();
                if let Some(yes) = own {
                    prop_assert!(s.app.answer_apart(yes));
                }
                s.app.report(notice.into());
                Ok(s)
            };
            let mut first = session("stepped out of the class: F2 rejoins it")?;
            let mut shared = session("following the class: F2 steps out to explore")?;
            let mut alone = session("following the class: F2 steps out to explore")?;
            for (frame, n) in ticks.into_iter().enumerate() {
                let common = OnceLock::new();
                prop_assert!(!first.draw_sharing(&common).unwrap(), "the first draws it");
                prop_assert!(shared.draw_sharing(&common).unwrap(), "the next takes it");
                alone.draw().unwrap();
                let (got, want) = (bytes(&mut shared), bytes(&mut alone));
                prop_assert!(got == want, "frame {frame} differs at {w}×{h}");
                prop_assert_eq!(&shared.app.geom, &alone.app.geom);
                bytes(&mut first);
                for s in [&mut first, &mut shared, &mut alone] {
                    for _ in 0..n {
                        s.tick();
                    }
                }
                // The notice, a follower's own, goes after the first frame.
                if frame == 0 {
                    shared.app.report("a notice of its own".into());
                    alone.app.report("a notice of its own".into());
                }
            }
        }
    }

    /// A frame is kept for a key: the same frame for the same key, another for another place,
    /// size or answer; the class's frames go when its presenter leaves; however many keys
    /// come, at most [`KEPT`] frames are kept.
    #[test]
    fn a_frame_is_kept_by_its_key_and_bounded() {
        let app = App::new(crate::scene::Scene::default_scene());
        let theme = Theme::builtin("dark").unwrap();
        let at = Place {
            presenter: 7,
            led: 40,
        };
        let key = Key::of(at, &app, &theme).unwrap();
        let frames = Frames::default();
        assert!(Arc::ptr_eq(&frames.at(&key), &frames.at(&key)));
        let others = [
            Key {
                at: Place { led: 41, ..at },
                ..key.clone()
            },
            Key {
                size: (60, 20),
                ..key.clone()
            },
            Key {
                own: Some(true),
                ..key.clone()
            },
            Key {
                theme: theme.clone().with_marker(ratatui::symbols::Marker::Dot),
                ..key.clone()
            },
        ];
        for other in &others {
            assert!(!Arc::ptr_eq(&frames.at(&key), &frames.at(other)));
        }
        assert_eq!(frames.kept(), 5);
        frames.forget(Some(8));
        assert_eq!(frames.kept(), 5, "another presenter's leaving");
        frames.forget(Some(7));
        assert_eq!(frames.kept(), 0);
        for led in 0..100 {
            frames.at(&Key {
                at: Place { led, ..at },
                ..key.clone()
            });
        }
        assert_eq!(frames.kept(), KEPT);
        frames.forget(None);
        assert_eq!(frames.kept(), 0);
    }

    /// An analysis page is drawn from the pieces each follower's own session computed: no key.
    #[test]
    fn an_analysis_page_is_each_followers_own() {
        let mut app = App::new(crate::scene::Scene::default_scene());
        let theme = Theme::builtin("dark").unwrap();
        let at = Place {
            presenter: 1,
            led: 0,
        };
        assert!(Key::of(at, &app, &theme).is_some());
        crate::app::update(&mut app, crate::app::Action::NextPage);
        assert!(Key::of(at, &app, &theme).is_some(), "the time plots");
        crate::app::update(&mut app, crate::app::Action::NextPage);
        assert_eq!(app.view().page, Page::EscapeSpeed);
        assert!(Key::of(at, &app, &theme).is_none());
    }
}
