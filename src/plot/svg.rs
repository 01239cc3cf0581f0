//! A [`Figure`] as a standalone SVG document: white background, black axes, a colour-blind
//! safe palette (Okabe & Ito) and a dash pattern per curve, so it prints in grey too.
//! Coordinates carry four decimals of a pixel: the data can be read back from them.

use super::sane;
use super::{Chart, Figure, Ink, Mark, Style};
use std::fmt::Write as _;

const WIDTH: f64 = 800.0;
const TITLE_BAND: f64 = 44.0;
/// Left of the plot: y tick values and the y axis name.
const LEFT: f64 = 84.0;
/// Right of the plot: the legend.
const RIGHT: f64 = 200.0;
/// Above each plot: its title; below: x tick values and the x axis name.
const TOP: f64 = 30.0;
const BOTTOM: f64 = 56.0;

const PALETTE: [&str; 7] = [
    "#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9", "#000000",
];
const DASHES: [&str; 5] = ["", "8 4", "2 3", "10 3 2 3", "4 4"];

/// Grey for second things (`Ink::Muted`): pins, the paper's other curves, approximations.
const MUTED: &str = "#999999";

/// Text for an SVG element or attribute: the first of its wordings (see
/// `present::alternatives`), the longest, as a page has room for it.
fn esc(s: &str) -> String {
    let s = s.split(crate::present::OR).next().unwrap_or_default();
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if c.is_control() => {}
            c => out.push(c),
        }
    }
    out
}

/// A coordinate, four decimals, never `-0`.
fn c(v: f64) -> String {
    let s = format!("{v:.4}");
    if s.trim_start_matches('-')
        .chars()
        .all(|ch| ch == '0' || ch == '.')
    {
        "0".into()
    } else {
        s
    }
}

/// The whole figure as an SVG document.
pub fn to_svg(fig: &Figure) -> String {
    let panel_h = if fig.panels.len() > 1 { 250.0 } else { 460.0 };
    let height = TITLE_BAND + panel_h * fig.panels.len().max(1) as f64;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" \
         width=\"{WIDTH}\" height=\"{height}\" viewBox=\"0 0 {WIDTH} {height}\" \
         font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"13\">"
    );
    let _ = writeln!(
        s,
        "<rect width=\"{WIDTH}\" height=\"{height}\" fill=\"white\"/>\n\
         <text class=\"title\" x=\"{}\" y=\"28\" text-anchor=\"middle\" font-size=\"17\">{}</text>",
        WIDTH / 2.0,
        esc(&fig.title)
    );
    for (k, p) in fig.panels.iter().enumerate() {
        panel(&mut s, p, TITLE_BAND + panel_h * k as f64, panel_h);
    }
    s.push_str("</svg>\n");
    s
}

/// Ranges widened so one data unit is as long on both axes, keeping each centre.
fn equalize(x: [f64; 2], y: [f64; 2], w: f64, h: f64) -> ([f64; 2], [f64; 2]) {
    let (sx, sy) = (w / (x[1] - x[0]), h / (y[1] - y[0]));
    let s = sx.min(sy);
    let widen = |r: [f64; 2], len: f64| {
        let (mid, half) = (0.5 * (r[0] + r[1]), 0.5 * len / s);
        [mid - half, mid + half]
    };
    (widen(x, w), widen(y, h))
}

/// Where a panel's plot lies on the page and which data it shows.
struct Axes {
    x0: f64,
    y0: f64,
    w: f64,
    h: f64,
    xr: [f64; 2],
    yr: [f64; 2],
}

impl Axes {
    fn px(&self, v: f64) -> f64 {
        self.x0 + (v - self.xr[0]) / (self.xr[1] - self.xr[0]) * self.w
    }

    fn py(&self, v: f64) -> f64 {
        self.y0 + self.h - (v - self.yr[0]) / (self.yr[1] - self.yr[0]) * self.h
    }

    fn inside(&self, x: f64, y: f64) -> bool {
        let (xr, yr) = (self.xr, self.yr);
        x.is_finite()
            && y.is_finite()
            && (xr[0]..=xr[1]).contains(&x)
            && (yr[0]..=yr[1]).contains(&y)
    }
}

fn panel(s: &mut String, p: &Chart, top: f64, height: f64) {
    let (x0, y0) = (LEFT, top + TOP);
    let (w, h) = (WIDTH - LEFT - RIGHT, height - TOP - BOTTOM);
    let (xr, yr) = match p.equal_aspect {
        true => equalize(sane(p.x), sane(p.y), w, h),
        false => (sane(p.x), sane(p.y)),
    };
    let ax = Axes {
        x0,
        y0,
        w,
        h,
        xr,
        yr,
    };
    axes(s, p, &ax, top);
    let legend = series(s, p, &ax);
    marks(s, p, &ax);
    frame_and_legend(s, &ax, &legend);
}

/// The panel's title, grid, ticks and axis names, and the clip its data are drawn in.
fn axes(s: &mut String, p: &Chart, ax: &Axes, top: f64) {
    let Axes {
        x0,
        y0,
        w,
        h,
        xr,
        yr,
    } = *ax;
    let _ = writeln!(
        s,
        "<g class=\"panel\">\n<text class=\"panel-title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"14\">{}</text>",
        c(x0 + w / 2.0),
        c(top + TOP - 10.0),
        esc(&match p.note.is_empty() {
            true => p.title.clone(),
            false => format!("{} — {}", p.title, p.note),
        })
    );
    // Grid and ticks.
    for v in p.x_scale.ticks(xr[0], xr[1], 8) {
        let x = c(ax.px(v));
        let _ = writeln!(
            s,
            "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" stroke=\"#e4e4e4\"/>\n\
             <text class=\"x-tick\" x=\"{x}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            c(y0),
            c(y0 + h),
            c(y0 + h + 17.0),
            esc(&p.x_scale.label(v))
        );
    }
    for v in p.y_scale.ticks(yr[0], yr[1], 6) {
        let y = c(ax.py(v));
        let _ = writeln!(
            s,
            "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"#e4e4e4\"/>\n\
             <text class=\"y-tick\" x=\"{}\" y=\"{y}\" text-anchor=\"end\" dominant-baseline=\"middle\">{}</text>",
            c(x0),
            c(x0 + w),
            c(x0 - 6.0),
            esc(&p.y_scale.label(v))
        );
    }
    let _ = writeln!(
        s,
        "<text class=\"x-label\" x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>\n\
         <text class=\"y-label\" transform=\"translate({} {}) rotate(-90)\" text-anchor=\"middle\">{}</text>",
        c(x0 + w / 2.0),
        c(y0 + h + 40.0),
        esc(&p.x_label),
        c(LEFT - 58.0),
        c(y0 + h / 2.0),
        esc(&p.y_label)
    );
    let _ = writeln!(
        s,
        "<clipPath id=\"clip{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n\
         <g clip-path=\"url(#clip{})\">",
        c(top),
        c(x0),
        c(y0),
        c(w),
        c(h),
        c(top)
    );
}

/// The series, in the palette's colours and dashes in turn; returns each one's legend entry
/// (its escaped name and a sample of its look).
fn series(s: &mut String, p: &Chart, ax: &Axes) -> Vec<(String, String)> {
    let Axes { w, h, xr, yr, .. } = *ax;
    let mut colours = 0;
    let mut next_colour = |ink: Ink| match ink {
        Ink::Muted => MUTED,
        _ => {
            colours += 1;
            PALETTE[(colours - 1) % PALETTE.len()]
        }
    };
    let mut legend = Vec::new();
    for ser in &p.series {
        let name = esc(&ser.name);
        match ser.style {
            Style::Cells {
                w: cw,
                h: ch,
                shade,
            } => {
                let grey = (255.0 * (1.0 - shade.clamp(0.0, 1.0))).round() as u8;
                let fill = format!("#{grey:02x}{grey:02x}{grey:02x}");
                let _ = writeln!(
                    s,
                    "<g class=\"cells\" data-name=\"{name}\" fill=\"{fill}\">"
                );
                let (rw, rh) = (cw / (xr[1] - xr[0]) * w, ch / (yr[1] - yr[0]) * h);
                for &(x, y) in ser.points.iter().filter(|(x, y)| ax.inside(*x, *y)) {
                    let _ = writeln!(
                        s,
                        "<rect class=\"cell\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
                        c(ax.px(x) - rw / 2.0),
                        c(ax.py(y) - rh / 2.0),
                        c(rw),
                        c(rh)
                    );
                }
                s.push_str("</g>\n");
                legend.push((name, format!("<rect width=\"18\" height=\"10\" y=\"-5\" fill=\"{fill}\" stroke=\"#888\"/>")));
            }
            Style::Dots => {
                let colour = next_colour(ser.ink);
                let _ = writeln!(
                    s,
                    "<g class=\"dots\" data-name=\"{name}\" fill=\"{colour}\">"
                );
                for &(x, y) in ser.points.iter().filter(|(x, y)| ax.inside(*x, *y)) {
                    let _ = writeln!(
                        s,
                        "<circle cx=\"{}\" cy=\"{}\" r=\"3\"/>",
                        c(ax.px(x)),
                        c(ax.py(y))
                    );
                }
                s.push_str("</g>\n");
                legend.push((
                    name,
                    format!("<circle cx=\"9\" r=\"3\" fill=\"{colour}\"/>"),
                ));
            }
            Style::Line { dash } => {
                let colour = next_colour(ser.ink);
                let dash = DASHES[dash % DASHES.len()];
                let dash_attr = match dash {
                    "" => String::new(),
                    d => format!(" stroke-dasharray=\"{d}\""),
                };
                // One polyline per unbroken stretch of finite points.
                for run in ser
                    .points
                    .split(|(x, y)| !(x.is_finite() && y.is_finite()))
                    .filter(|r| !r.is_empty())
                {
                    let pts: Vec<String> = run
                        .iter()
                        .map(|&(x, y)| format!("{},{}", c(ax.px(x)), c(ax.py(y))))
                        .collect();
                    let _ = writeln!(
                        s,
                        "<polyline class=\"series\" data-name=\"{name}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.8\"{dash_attr} points=\"{}\"/>",
                        pts.join(" ")
                    );
                }
                legend.push((
                    name,
                    format!(
                        "<line x2=\"22\" stroke=\"{colour}\" stroke-width=\"1.8\"{dash_attr}/>"
                    ),
                ));
            }
        }
    }
    legend
}

/// The marks: vertical lines and points, labelled on the side with room.
fn marks(s: &mut String, p: &Chart, ax: &Axes) {
    let Axes {
        x0, y0, w, h, yr, ..
    } = *ax;
    for m in &p.marks {
        match m {
            Mark::VLine { x, label, .. } if ax.inside(*x, yr[0]) => {
                let xp = c(ax.px(*x));
                // The label on the side with room for it.
                let (lx, anchor) = match ax.px(*x) > x0 + 0.6 * w {
                    true => (ax.px(*x) - 3.0, "end"),
                    false => (ax.px(*x) + 3.0, "start"),
                };
                let _ = writeln!(
                    s,
                    "<line class=\"mark\" x1=\"{xp}\" y1=\"{}\" x2=\"{xp}\" y2=\"{}\" stroke=\"#444\" stroke-dasharray=\"3 3\"/>\n\
                     <text class=\"mark-label\" x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"{anchor}\">{}</text>",
                    c(y0),
                    c(y0 + h),
                    c(lx),
                    c(y0 + 12.0),
                    esc(label)
                );
            }
            Mark::Text { x, y, label, .. } if ax.inside(*x, *y) => {
                let _ = writeln!(
                    s,
                    "<text class=\"mark-label\" x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>",
                    c(ax.px(*x)),
                    c(ax.py(*y)),
                    esc(label)
                );
            }
            Mark::Arrow {
                from,
                to,
                label,
                ink,
            } => arrow(s, ax, *from, *to, label, *ink),
            Mark::Point { x, y, label, .. } if ax.inside(*x, *y) => {
                // The label on the side where it fits inside the plot (its width estimated
                // at 11 px type), else on the side with more room.
                let px = ax.px(*x);
                let (right, left) = (x0 + w - (px + 7.0), px - 7.0 - x0);
                let need = label_width(label);
                let (lx, anchor) = match right >= need || (left < need && right >= left) {
                    true => (px + 7.0, "start"),
                    false => (px - 7.0, "end"),
                };
                let _ = writeln!(
                    s,
                    "<circle class=\"mark\" cx=\"{}\" cy=\"{}\" r=\"4.5\" fill=\"none\" stroke=\"black\" stroke-width=\"1.5\"/>\n\
                     <text class=\"mark-label\" x=\"{}\" y=\"{}\" font-size=\"11\" text-anchor=\"{anchor}\">{}</text>",
                    c(ax.px(*x)),
                    c(ax.py(*y)),
                    c(lx),
                    c(ax.py(*y) - 7.0),
                    esc(label)
                );
            }
            _ => {}
        }
    }
}

/// About how wide `label` is at 11 px type: 6.2 px a character (what the tests measure by).
pub fn label_width(label: &str) -> f64 {
    6.2 * label.chars().count() as f64
}

/// An arrow from `from` to `to` (data units) with its head and its label beyond it.
fn arrow(s: &mut String, ax: &Axes, from: (f64, f64), to: (f64, f64), label: &str, ink: Ink) {
    let (x0, y0, x1, y1) = (ax.px(from.0), ax.py(from.1), ax.px(to.0), ax.py(to.1));
    let (dx, dy) = (x1 - x0, y1 - y0);
    let len = dx.hypot(dy);
    if !(len.is_finite() && len > 0.0) {
        return;
    }
    let colour = match ink {
        Ink::Muted => MUTED,
        _ => "#000000",
    };
    // The head: two strokes back from the tip, 9 px long, ±25° off the shaft.
    let (ux, uy) = (dx / len, dy / len);
    let head = |a: f64| {
        let (sa, ca) = a.sin_cos();
        (
            x1 - 9.0 * (ux * ca - uy * sa),
            y1 - 9.0 * (uy * ca + ux * sa),
        )
    };
    let ((ax1, ay1), (ax2, ay2)) = (head(0.45), head(-0.45));
    let _ = writeln!(
        s,
        "<g class=\"arrow\" data-name=\"{}\" stroke=\"{colour}\" stroke-width=\"1.5\">\
         <line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>\
         <polyline fill=\"none\" points=\"{},{} {},{} {},{}\"/></g>\n\
         <text class=\"mark-label\" x=\"{}\" y=\"{}\" font-size=\"11\" fill=\"{colour}\">{}</text>",
        esc(label),
        c(x0),
        c(y0),
        c(x1),
        c(y1),
        c(ax1),
        c(ay1),
        c(x1),
        c(y1),
        c(ax2),
        c(ay2),
        c(x1 + 4.0 * ux + 2.0),
        c(y1 + 4.0 * uy),
        esc(label)
    );
}

/// The data's clip closed, the plot's frame and the legend beside it.
fn frame_and_legend(s: &mut String, ax: &Axes, legend: &[(String, String)]) {
    let Axes { x0, y0, w, h, .. } = *ax;
    s.push_str("</g>\n");
    let _ = writeln!(
        s,
        "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"black\"/>",
        c(x0),
        c(y0),
        c(w),
        c(h)
    );
    let _ = writeln!(s, "<g class=\"legend\" font-size=\"12\">");
    for (i, (name, sample)) in legend.iter().filter(|(n, _)| !n.is_empty()).enumerate() {
        let y = y0 + 8.0 + 18.0 * i as f64;
        let _ = writeln!(
            s,
            "<g transform=\"translate({} {})\">{sample}<text x=\"28\" dominant-baseline=\"middle\">{name}</text></g>",
            c(x0 + w + 14.0),
            c(y)
        );
    }
    s.push_str("</g>\n</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::Series;

    #[test]
    fn text_is_escaped_and_coordinates_are_clean() {
        assert_eq!(esc("a<b & \"c\">\u{1b}"), "a&lt;b &amp; &quot;c&quot;&gt;");
        assert_eq!(c(-0.00001), "0");
        assert_eq!(c(12.345678), "12.3457");
    }

    #[test]
    fn a_line_maps_back_to_its_data() {
        let fig = Figure {
            title: "t".into(),
            panels: vec![Chart {
                title: "p".into(),
                x_label: "x".into(),
                y_label: "y".into(),
                x: [0.0, 10.0],
                y: [0.0, 1.0],
                equal_aspect: false,
                series: vec![Series::line(
                    "a",
                    0,
                    vec![(0.0, 0.0), (5.0, f64::NAN), (10.0, 1.0), (2.0, 0.5)],
                )],
                marks: vec![],
                ..Chart::default()
            }],
        };
        let svg = to_svg(&fig);
        // The NaN breaks the line in two.
        assert_eq!(svg.matches("<polyline").count(), 2);
        let (w, h) = (WIDTH - LEFT - RIGHT, 460.0 - TOP - BOTTOM);
        assert!(svg.contains(&format!(
            "points=\"{},{}\"",
            c(LEFT),
            c(TITLE_BAND + TOP + h)
        )));
        assert!(svg.contains(&format!(
            "points=\"{},{} {},{}\"",
            c(LEFT + w),
            c(TITLE_BAND + TOP),
            c(LEFT + 0.2 * w),
            c(TITLE_BAND + TOP + 0.5 * h)
        )));
    }
}
