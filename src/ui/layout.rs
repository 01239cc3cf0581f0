//! Where every part of the screen goes, from the terminal's size alone: drawing, the outcome
//! map's grid and the mouse all read this one function, so they can never disagree.

use ratatui::layout::{Constraint, Layout, Rect};

/// Below this the explorer shows a "too small" notice instead.
pub const MIN_SIZE: (u16, u16) = (40, 12);
/// Width of the readout panel beside the picture (wide terminals).
pub const PANEL_W: u16 = 30;
/// Below this width the panel goes under the picture rather than beside it.
pub const WIDE: u16 = 60;
/// Rows of the panel under the picture on a narrow terminal at most (every readout of a
/// plain run; `panel::lines_in` keeps the most important when fewer fit).
const NARROW_PANEL_ROWS: u16 = 16;

/// The screen's regions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Regions {
    pub title: Rect,
    /// The picture or page and the panel together.
    pub body: Rect,
    /// The picture or the page.
    pub canvas: Rect,
    pub panel: Rect,
    pub lesson: Rect,
    pub status: Rect,
    /// The help overlay: the body and the two lines below it.
    pub help: Rect,
}

/// The regions of a `width` × `height` terminal (None below [`MIN_SIZE`]). Wide: the panel
/// beside the picture; narrow: under it, at most half the body.
pub fn regions(width: u16, height: u16) -> Option<Regions> {
    if width < MIN_SIZE.0 || height < MIN_SIZE.1 {
        return None;
    }
    let area = Rect::new(0, 0, width, height);
    let [title, body, lesson, status] = Layout::vertical([
        Constraint::Length(1),
        Constraint::Min(1),
        Constraint::Length(1),
        Constraint::Length(1),
    ])
    .areas(area);
    let (canvas, panel) = if width >= WIDE {
        let [c, p] =
            Layout::horizontal([Constraint::Min(10), Constraint::Length(PANEL_W)]).areas(body);
        (c, p)
    } else {
        // At least status, ξ and τ (see panel::lines_in), however short the screen.
        let ph = (body.height / 2).clamp(5, NARROW_PANEL_ROWS);
        let [c, p] = Layout::vertical([Constraint::Min(3), Constraint::Length(ph)]).areas(body);
        (c, p)
    };
    let help = Rect {
        height: body.height + lesson.height + status.height,
        ..body
    };
    Some(Regions {
        title,
        body,
        canvas,
        panel,
        lesson,
        status,
        help,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_tile_the_screen_at_every_size() {
        assert_eq!(regions(39, 30), None);
        assert_eq!(regions(80, 11), None);
        for (w, h) in [(40, 12), (56, 30), (59, 24), (60, 20), (80, 24), (200, 60)] {
            let r = regions(w, h).unwrap();
            assert_eq!(r.title, Rect::new(0, 0, w, 1));
            assert_eq!((r.lesson.y, r.status.y), (h - 2, h - 1));
            assert_eq!(r.body, Rect::new(0, 1, w, h - 3));
            assert_eq!(r.help, Rect::new(0, 1, w, h - 1));
            let cells = |r: Rect| u32::from(r.width) * u32::from(r.height);
            assert_eq!(cells(r.canvas) + cells(r.panel), cells(r.body), "{w}×{h}");
            if w >= WIDE {
                assert_eq!((r.panel.width, r.canvas.width), (PANEL_W, w - PANEL_W));
            } else {
                assert_eq!(r.canvas.width, w);
                assert!(r.panel.height >= 5 && r.canvas.height >= 3, "{w}×{h}");
            }
        }
        assert_eq!(regions(59, 24).unwrap().canvas, Rect::new(0, 1, 59, 11));
        assert_eq!(regions(56, 30).unwrap().canvas, Rect::new(0, 1, 56, 14));
    }
}
