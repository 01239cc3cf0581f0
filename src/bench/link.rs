//! The explorer over a slow link, simulated in link time (no clock): frames paced as the
//! terminal loop paces them (the next is drawn when the last has arrived, with every tick due
//! by then), each measured through the real crossterm backend; and, for comparison, the
//! backlog of drawing every tick regardless (the explorer before issue 19).

use super::bytes::{counted, draw};
use crate::app::App;
use crate::app::TICKS_PER_SECOND;
use crate::engine::body::Body;
use crate::error::Error;
use crate::scene::Scene;
use crate::terminal::pace::Clock;
use crate::theme::{Depth, Theme};
use serde::Serialize;
use std::time::{Duration, Instant};

/// Link speeds measured, in bytes/s (4 and 16 KB/s).
pub const RATES: [f64; 2] = [4096.0, 16384.0];

/// One link speed and scene: playing at 120×40 (dark theme, 256 colours).
#[derive(Clone, Debug, Serialize)]
pub struct Link {
    /// The scene played: the default (`C`), or with a body ([`body_scene`]).
    pub scene: String,
    pub rate_kb_per_s: f64,
    pub seconds: f64,
    /// Paced: frames drawn, and after the first screen their mean size and rate.
    pub frames: usize,
    pub bytes_per_frame: f64,
    pub frames_per_s: f64,
    /// Paced: the most frames written and not yet delivered.
    pub in_flight: usize,
    /// Paced, after the first screen: the longest a key can wait to show (the frame in
    /// flight, then its own).
    pub worst_key_s: f64,
    /// Paced: sim time shown against wall time × speed (1: time kept).
    pub time_kept: f64,
    /// Unpaced (a frame every tick): frames written and not yet delivered at the end.
    pub unpaced_in_flight: usize,
}

/// The default scene with a body, as `turntable --body-length 0.1 --body-height 0.01` opens
/// it: the bar, its centre's path and the panel's body lines change as it plays.
pub fn body_scene() -> Scene {
    let mut scene = Scene::default_scene();
    scene.body = Some(Body {
        length: 0.1,
        height: Some(0.01),
        angle: 0.0,
    });
    scene
}

/// `scene` playing for `seconds` of link time at `rate` bytes/s.
pub fn simulate_scene(scene: &Scene, rate: f64, seconds: f64) -> Result<Link, Error> {
    let theme = Theme::builtin("dark")
        .ok_or_else(|| Error::invalid("no dark theme"))?
        .with_depth(Depth::Ansi256);
    let size = (120, 40);
    let (mut term, count) = counted(size)?;
    let mut app = App::new(scene.clone());
    let t0 = Instant::now();
    let mut clock = Clock::new(t0);
    let (mut now, mut ticks, mut frames) = (0.0, 0u64, 0usize);
    let (mut last_trip, mut arrived, mut in_flight) = (0.0f64, 0.0f64, 0);
    let mut worst_key_s = 0.0f64;
    let gap = 1.0 / f64::from(TICKS_PER_SECOND);
    // The first screen (the whole of it, ~15 KB) is drawn once; what follows is what playing costs.
    let (mut first_bytes, mut first_s) = (0, 0.0);
    while now < seconds {
        for _ in 0..clock.due(t0 + Duration::from_secs_f64(now)) {
            app.tick();
            ticks += 1;
        }
        let before = count.get();
        draw(&mut term, &mut app, &theme)?;
        let trip = (count.get() - before) as f64 / rate;
        in_flight = in_flight.max(1 + usize::from(arrived > now));
        arrived = now + trip;
        if frames > 1 {
            worst_key_s = worst_key_s.max(last_trip + trip);
        }
        last_trip = trip;
        frames += 1;
        // The next frame once this one has arrived, and no sooner than the next tick.
        now += trip.max(gap);
        if frames == 1 {
            (first_bytes, first_s) = (count.get(), now);
        }
    }
    let paced_bytes = count.get() - first_bytes;
    // Unpaced: every tick drawn at once, the link carrying what it can.
    let (mut term, count) = counted(size)?;
    let mut app = App::new(scene.clone());
    let mut ends = Vec::new();
    draw(&mut term, &mut app, &theme)?;
    ends.push(count.get());
    for _ in 0..(seconds * f64::from(TICKS_PER_SECOND)) as usize {
        app.tick();
        draw(&mut term, &mut app, &theme)?;
        ends.push(count.get());
    }
    let carried = (rate * seconds) as usize;
    Ok(Link {
        scene: match scene.body {
            Some(b) => format!("{} with a body L {}", scene.name, b.length),
            None => scene.name.to_string(),
        },
        rate_kb_per_s: rate / 1024.0,
        seconds,
        frames,
        bytes_per_frame: paced_bytes as f64 / (frames - 1).max(1) as f64,
        frames_per_s: (frames - 1) as f64 / (now - first_s),
        in_flight,
        worst_key_s,
        time_kept: ticks as f64 / (now * f64::from(TICKS_PER_SECOND)),
        unpaced_in_flight: ends.iter().filter(|&&e| e > carried).count(),
    })
}
