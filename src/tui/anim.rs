//! The animation view (`a`): the live design's run played in slow motion. The main mass on its
//! spring, the enclosure and the ball drawn to scale (one length scale for all, in cm), the
//! same structure without the ball as a faint ghost, each impact flashed at its wall with its
//! speed and level, and beside it x(t) with a time cursor.
//!
//! No physics per frame: every position is the engine's own recorded run, interpolated. The
//! main mass and the ball come from the run's history samples (x and y), the ghost from the
//! free structure's samples the history panel draws, and each impact from the run's events: at
//! its onset the ball is placed on the wall it struck (z = ±d/2), so an impact between two
//! samples is drawn where and when the engine found it. An impact's level is the one the worker
//! computed with the run's readout (the engine's level of each impact, as `thud simulate
//! --json` lists them): nothing heavier than interpolation runs on the UI thread per frame.
//!
//! With a design pinned, its run plays below the live one, to the same scale and clock.
//!
//! Bytes over SSH (under 30 KB per second of playback at 80×24, 1×): ratatui sends
//! only the cells that change, so the picture is drawn so that few do. The spring's zigzag
//! keeps its corners fixed in space (only its end moves), the ghost is its frame's top and
//! bottom edges (horizontal lines change only at their ends), the time cursor on x(t) is a dot
//! on the curve and a tick on the axis (not a full-height line), and the line naming the
//! flashed impact holds each impact at least [`NAME_HOLD_S`] of real time.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::style::Color;
use ratatui::style::{Modifier, Style};
use ratatui::widgets::canvas::{Circle, Line as CLine, Rectangle};
use ratatui::widgets::{Block, Widget};

use super::plot::{fit_bounds, stamp, Curve, LinePlot};
use super::theme::{Palette, Role};
use crate::damper::{HistoryPoint, ImpactEvent, Wall};
use crate::units::sig;

/// The playback speeds (simulated seconds per real second): 1/1000× to 1×.
pub const SPEEDS: [f64; 7] = [1.0 / 1000.0, 1.0 / 300.0, 1.0 / 100.0, 1.0 / 30.0, 1.0 / 10.0, 1.0 / 3.0, 1.0];
/// The speed the animation opens at (an index into [`SPEEDS`]): 1/10×, where the default
/// design's ball strikes a few times a second of real time from the start (its first impact
/// after 0.1 s) and the mass's swing takes about 2 s; `[` slows it down to watch one contact.
pub const DEFAULT_SPEED: usize = 4;
/// One frame of real time (s): the view is drawn 30 times a second while it plays.
pub const FRAME_S: f64 = 1.0 / 30.0;
/// How long an impact stays flashed, in real time (s), whatever the speed.
pub const FLASH_S: f64 = 0.5;
/// The least real time (s) the flash line names one impact while playing: at 1× impacts come
/// every few frames, faster than anyone reads, and each new text resends the line.
pub const NAME_HOLD_S: f64 = 0.25;

/// The animation's state: the time shown, the speed, playing or paused.
#[derive(Debug, Clone, PartialEq)]
pub struct Anim {
    /// The run's time shown (s).
    pub t_s: f64,
    /// Index into [`SPEEDS`].
    pub speed: usize,
    pub playing: bool,
    /// The impact the flash line names (its index in the run's impacts) and the real time (s)
    /// it has named it.
    pub named: Option<(usize, f64)>,
}

impl Default for Anim {
    /// From the start, at [`DEFAULT_SPEED`], playing.
    fn default() -> Self {
        Self::at_speed(DEFAULT_SPEED)
    }
}

/// A speed as shown: "1/1000×", "1/3×", "1×".
pub fn rate_text(r: f64) -> String {
    if r >= 1.0 {
        "1×".into()
    } else {
        format!("1/{}×", (1.0 / r).round())
    }
}

impl Anim {
    /// From the start, at speed `speed` (an index into [`SPEEDS`]), playing.
    pub fn at_speed(speed: usize) -> Self {
        Self { t_s: 0.0, speed: speed.min(SPEEDS.len() - 1), playing: true, named: None }
    }

    /// Simulated seconds per real second.
    pub fn rate(&self) -> f64 {
        SPEEDS[self.speed.min(SPEEDS.len() - 1)]
    }

    /// The speed as shown: "1/1000×", "1/3×", "1×".
    pub fn speed_text(&self) -> String {
        rate_text(self.rate())
    }

    /// `real_s` of real time on, up to the run's end `end_s` (where it pauses).
    pub fn advance(&mut self, real_s: f64, end_s: f64) {
        self.t_s = (self.t_s + real_s.max(0.0) * self.rate()).min(end_s);
        if self.t_s >= end_s {
            self.playing = false;
        }
    }

    /// One frame on (or back), paused.
    pub fn step(&mut self, back: bool, end_s: f64) {
        let dt = FRAME_S * self.rate();
        self.t_s = if back { (self.t_s - dt).max(0.0) } else { (self.t_s + dt).min(end_s) };
        self.playing = false;
    }

    /// The impact flashed at the time shown: the last one that began within the last
    /// [`FLASH_S`] of real time (its index).
    pub fn flashed(&self, impacts: &[ImpactEvent]) -> Option<usize> {
        let since = FLASH_S * self.rate();
        let i = impacts.partition_point(|e| e.t_s <= self.t_s);
        (i > 0 && self.t_s - impacts[i - 1].t_s <= since).then(|| i - 1)
    }

    /// Updates the impact the flash line names after the time shown moved: the one flashed
    /// now, but while playing (`played_s`: the real time of the frame) a named impact is kept
    /// until it has shown [`NAME_HOLD_S`]. Stepping and restarts name the flashed one at once.
    pub fn name_flash(&mut self, impacts: &[ImpactEvent], played_s: Option<f64>) {
        let now = self.flashed(impacts);
        self.named = match (now, self.named, played_s) {
            (None, ..) => None,
            (Some(i), Some((j, age)), Some(dt)) if i == j || age + dt < NAME_HOLD_S => Some((j, age + dt)),
            (Some(i), ..) => Some((i, 0.0)),
        };
    }
}

/// Where everything is at one time (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// The main mass's displacement x.
    pub x_m: f64,
    /// The ball's displacement y.
    pub y_m: f64,
}

/// Linear interpolation of `(t, v)` pairs at `t`.
fn lerp(a: (f64, f64), b: (f64, f64), t: f64) -> f64 {
    if b.0 <= a.0 {
        return b.1;
    }
    a.1 + (b.1 - a.1) * ((t - a.0) / (b.0 - a.0)).clamp(0.0, 1.0)
}

/// The pose at `t_s` from the run's history samples and impacts (`half_gap_m` = d/2): x
/// interpolated between the samples; the ball's z = y − x likewise, through the wall (z = ±d/2)
/// at each impact's onset between them.
pub fn pose_at(history: &[HistoryPoint], impacts: &[ImpactEvent], half_gap_m: f64, t_s: f64) -> Option<Pose> {
    let (first, last) = (history.first()?, history.last()?);
    let t = t_s.clamp(first.t_s, last.t_s);
    let j = history.partition_point(|h| h.t_s <= t).clamp(1, history.len().max(2) - 1).min(history.len() - 1);
    let (a, b) = (&history[j.saturating_sub(1)], &history[j]);
    let x = lerp((a.t_s, a.x_m), (b.t_s, b.x_m), t);
    // The keyframes of z in [a, b]: the samples and the impacts' onsets on their walls.
    let mut keys = vec![(a.t_s, a.y_m - a.x_m)];
    let from = impacts.partition_point(|e| e.t_s <= a.t_s);
    for e in impacts[from..].iter().take_while(|e| e.t_s < b.t_s) {
        let wall = match e.wall {
            Wall::Upper => half_gap_m,
            Wall::Lower => -half_gap_m,
        };
        keys.push((e.t_s, wall));
    }
    keys.push((b.t_s, b.y_m - b.x_m));
    let k = keys.partition_point(|p| p.0 <= t).clamp(1, keys.len() - 1);
    let z = lerp(keys[k - 1], keys[k], t);
    Some(Pose { x_m: x, y_m: x + z })
}

/// `samples` (t, v) interpolated at `t`.
pub fn sample_at(samples: &[(f64, f64)], t: f64) -> Option<f64> {
    let j = samples.partition_point(|p| p.0 <= t);
    match (j.checked_sub(1).and_then(|i| samples.get(i)), samples.get(j)) {
        (Some(&a), Some(&b)) => Some(lerp(a, b, t)),
        (Some(&a), None) => Some(a.1),
        (None, Some(&b)) => Some(b.1),
        (None, None) => None,
    }
}

/// One run as the animation draws it.
#[derive(Clone, Copy)]
pub struct Track<'a> {
    pub history: &'a [HistoryPoint],
    pub impacts: &'a [ImpactEvent],
    /// x(t) (t in s, x in cm).
    pub history_cm: &'a [(f64, f64)],
    pub gap_m: f64,
    pub ball_radius_m: f64,
    /// The level (dB) of each impact (index as `impacts`), as the worker computed it; empty
    /// while it computes.
    pub levels_db: &'a [Option<f64>],
}

/// The view's data.
pub struct AnimView<'a> {
    pub block: Block<'a>,
    pub anim: &'a Anim,
    /// The live design's run.
    pub live: Track<'a>,
    /// x(t) of the live structure without the damper (t in s, x in cm): the ghost.
    pub free_cm: &'a [(f64, f64)],
    /// The pinned design's run, played below the live one.
    pub pinned: Option<Track<'a>>,
    pub end_s: f64,
    pub theme: Palette,
}

/// A run's enclosure in cm: the inner half-width (the ball's centre reaches ±d/2), the outer
/// half-width and half-height.
fn enclosure_cm(t: &Track) -> (f64, f64, f64) {
    let (r, hg) = (100.0 * t.ball_radius_m, 100.0 * 0.5 * t.gap_m);
    let inner = hg + r;
    (inner, inner + 0.15 * inner.max(1.0), r + 0.15 * inner.max(1.0))
}

/// The picture's x bounds (cm): the spring's anchor at the left, the mass's widest swing.
fn scene_bounds(swing_cm: f64, box_half_cm: f64) -> [f64; 2] {
    let right = swing_cm + box_half_cm + 1.0;
    [-(right + 0.6 * right), right]
}

impl AnimView<'_> {
    /// The picture of `track` over `area` with x bounds `xb` (cm, shared by every run shown):
    /// anchor, spring, ghost, mass with its enclosure, ball, the flashed wall.
    fn scene(&self, buf: &mut Buffer, area: Rect, xb: [f64; 2], track: &Track, ghost_m: Option<f64>, pinned: bool) {
        let th = &self.theme;
        let Some(pose) = pose_at(track.history, track.impacts, 0.5 * track.gap_m, self.anim.t_s) else { return };
        let flash = self.anim.flashed(track.impacts).and_then(|i| track.impacts.get(i));
        let cm = |m: f64| 100.0 * m;
        let r = cm(track.ball_radius_m);
        let (inner, box_half, box_h) = enclosure_cm(track);
        // Cells are about twice as tall as wide: the y span matches so circles look round.
        let h_span = (xb[1] - xb[0]) * 2.0 * f64::from(area.height.max(1)) / f64::from(area.width.max(1)) / 2.0;
        let yb = [-h_span, h_span];
        let dot_y = (yb[1] - yb[0]) / (4.0 * f64::from(area.height.max(1)));
        let cell_x = (xb[1] - xb[0]) / f64::from(area.width.max(1));
        let anchor = xb[0] + 0.5;
        let spring = |ctx: &mut ratatui::widgets::canvas::Context, to: f64| {
            // A flat zigzag one line of cells tall (±1.5 Braille dots) with its corners fixed
            // in space, one a cell: as the mass moves only the cells at its end change.
            let amp = 1.5 * dot_y;
            let mut prev = (anchor, 0.0);
            let mut k = 1.0;
            while anchor + k * cell_x < to - 0.5 * cell_x {
                let px = anchor + k * cell_x;
                let py = if k as u32 % 2 == 1 { amp } else { -amp };
                ctx.draw(&CLine { x1: prev.0, y1: prev.1, x2: px, y2: py, color: Color::Reset });
                prev = (px, py);
                k += 1.0;
            }
            ctx.draw(&CLine { x1: prev.0, y1: prev.1, x2: to, y2: 0.0, color: Color::Reset });
        };
        let frame = |ctx: &mut ratatui::widgets::canvas::Context, x: f64| {
            ctx.draw(&Rectangle {
                x: x - box_half,
                y: -box_h,
                width: 2.0 * box_half,
                height: 2.0 * box_h,
                color: Color::Reset,
            });
            ctx.draw(&CLine { x1: x - inner, y1: -r, x2: x - inner, y2: r, color: Color::Reset });
            ctx.draw(&CLine { x1: x + inner, y1: -r, x2: x + inner, y2: r, color: Color::Reset });
        };
        // The ground the spring hangs from.
        stamp(buf, area, xb, yb, th.line_marker(), th.style(Role::Grid), |ctx| {
            ctx.draw(&CLine { x1: anchor, y1: -2.0 * box_h, x2: anchor, y2: 2.0 * box_h, color: Color::Reset });
        });
        if let Some(g) = ghost_m {
            let g = cm(g);
            // The ghost's top and bottom edges, a dot outside the frame's: enough to read its
            // swing, and a horizontal line changes only at its ends as it moves.
            stamp(buf, area, xb, yb, th.line_marker_faint(), th.behind(th.ink(Role::Alone)), |ctx| {
                for y in [-box_h - dot_y, box_h + dot_y] {
                    ctx.draw(&CLine { x1: g - box_half, y1: y, x2: g + box_half, y2: y, color: Color::Reset });
                }
            });
        }
        let x = cm(pose.x_m);
        let (body, ball) =
            if pinned { (th.pinned(), th.pinned()) } else { (th.style(Role::Damper), th.style(Role::Live)) };
        stamp(buf, area, xb, yb, th.line_marker(), body, |ctx| {
            spring(ctx, x - box_half);
            frame(ctx, x);
        });
        stamp(buf, area, xb, yb, th.line_marker(), ball, |ctx| {
            ctx.draw(&Circle { x: cm(pose.y_m), y: 0.0, radius: r, color: Color::Reset });
        });
        if let Some(e) = flash {
            let wx = match e.wall {
                Wall::Upper => x + inner,
                Wall::Lower => x - inner,
            };
            let style = Style::default().add_modifier(Modifier::BOLD | Modifier::REVERSED);
            stamp(buf, area, xb, yb, th.mark('█', '#'), style, |ctx| {
                ctx.draw(&CLine { x1: wx, y1: -box_h, x2: wx, y2: box_h, color: Color::Reset });
            });
        }
        if pinned {
            buf.set_stringn(area.x, area.y, "pinned", area.width.into(), th.pinned());
        }
    }
}

impl Widget for AnimView<'_> {
    // Over 80 lines: the frame drawn back to front: enclosure, spring, masses, ghost, x(t), names.
    fn render(self, area: Rect, buf: &mut Buffer) {
        let inner = self.block.inner(area);
        (&self.block).render(area, buf);
        let th = self.theme;
        let a = self.anim;
        if self.live.history.is_empty() {
            buf.set_stringn(inner.x, inner.y, th.text("no run to play yet"), inner.width.into(), Style::default());
            return;
        }
        let [top, status, flash_line] =
            Layout::vertical([Constraint::Min(1), Constraint::Length(1), Constraint::Length(1)]).areas(inner);
        let [picture, plot] = if top.width >= 60 {
            Layout::horizontal([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(top)
        } else {
            Layout::vertical([Constraint::Percentage(55), Constraint::Percentage(45)]).areas(top)
        };
        // One length scale for every run shown: the widest swing and the widest enclosure.
        let tracks: Vec<&Track> = std::iter::once(&self.live).chain(self.pinned.as_ref()).collect();
        let swing =
            tracks.iter().flat_map(|t| t.history_cm.iter()).chain(self.free_cm).map(|p| p.1.abs()).fold(0.0, f64::max);
        let box_half = tracks.iter().map(|t| enclosure_cm(t).1).fold(0.0, f64::max);
        let xb = scene_bounds(swing, box_half);
        let ghost = sample_at(self.free_cm, a.t_s).map(|x| x / 100.0);
        match &self.pinned {
            Some(p) => {
                let [up, down] =
                    Layout::vertical([Constraint::Percentage(50), Constraint::Percentage(50)]).areas(picture);
                self.scene(buf, up, xb, &self.live, ghost, false);
                self.scene(buf, down, xb, p, None, true);
            }
            None => self.scene(buf, picture, xb, &self.live, ghost, false),
        }
        let state = if a.playing { th.sym("▶ playing", "> playing") } else { th.sym("❚❚ paused", "|| paused") };
        let text = format!("t {} s of {} s   speed {}   {state}", sig(a.t_s, 4), sig(self.end_s, 3), a.speed_text());
        buf.set_stringn(
            status.x,
            status.y,
            th.fit(&th.text(&text), status.width.into()),
            status.width.into(),
            th.label(),
        );
        let named = a.named.and_then(|(i, _)| self.live.impacts.get(i).map(|e| (i, e)));
        let text = match named {
            Some((i, e)) => {
                let side = match e.wall {
                    Wall::Upper => "upper wall (right)",
                    Wall::Lower => "lower wall (left)",
                };
                let spl = match self.live.levels_db.get(i) {
                    Some(Some(db)) => format!(", SPL {} dB", sig(*db, 4)),
                    _ => String::new(),
                };
                format!("impact {} at the {side}: {} m/s{spl}", i + 1, sig(e.u_in_m_s, 4))
            }
            None => {
                format!("{} impacts in the run; the ghost: the structure without the ball", self.live.impacts.len())
            }
        };
        let style = if named.is_some() { Style::default().add_modifier(Modifier::BOLD) } else { th.label() };
        buf.set_stringn(
            flash_line.x,
            flash_line.y,
            th.fit(&th.text(&text), flash_line.width.into()),
            flash_line.width.into(),
            style,
        );
        let yb = fit_bounds(tracks.iter().flat_map(|t| t.history_cm.iter()).chain(self.free_cm).map(|p| p.1), 0.05);
        // The time cursor: a dot on x(t) and a tick on the time axis (a full-height line
        // would resend a column of cells every time it moves).
        let now = sample_at(self.live.history_cm, a.t_s).map_or_else(Vec::new, |x| vec![(a.t_s, x)]);
        let tick = [(a.t_s, yb[0])];
        let pinned_cm: &[(f64, f64)] = self.pinned.as_ref().map_or(&[], |p| p.history_cm);
        let mut series =
            vec![Curve::line("none", self.free_cm, th.behind(th.ink(Role::Alone)), th.line_marker_faint())];
        if !pinned_cm.is_empty() {
            series.push(Curve::line("pinned", pinned_cm, th.pinned(), th.line_marker_faint()));
        }
        series.push(Curve::line("damper", self.live.history_cm, th.style(Role::Damper), th.line_marker()));
        let bold = Style::default().add_modifier(Modifier::BOLD);
        series.push(Curve::points("now", &now, bold, th.mark('●', 'o')));
        series.push(Curve::points("", &tick, bold, th.mark('▲', '^')));
        LinePlot {
            block: Block::default(),
            x_title: "t (s)",
            y_title: "x (cm)",
            series,
            empty: "no history",
            theme: th,
            y_zero: true,
            x_bounds: Some([0.0, self.end_s.max(1e-9)]),
            y_bounds: Some(yb),
            legend: true,
        }
        .render(plot, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hp(t_s: f64, x_m: f64, y_m: f64) -> HistoryPoint {
        HistoryPoint { t_s, x_m, y_m }
    }

    #[test]
    fn the_ball_is_on_the_wall_at_an_impact_between_two_samples() {
        let history = [hp(0.0, 0.0, 0.0), hp(1.0, 0.0, 0.0)];
        let e = ImpactEvent {
            t_s: 0.5,
            wall: Wall::Upper,
            u_in_m_s: 1.0,
            u_out_m_s: 0.9,
            t_end_s: 0.5002,
            penetration_max_m: 1e-5,
        };
        let p = pose_at(&history, &[e], 0.02, 0.5).unwrap();
        assert!((p.y_m - 0.02).abs() < 1e-12, "{p:?}");
        let p = pose_at(&history, &[e], 0.02, 0.25).unwrap();
        assert!((p.y_m - 0.01).abs() < 1e-12, "half way to the wall: {p:?}");
    }

    #[test]
    fn speeds_run_from_a_thousandth_to_one_and_playback_stops_at_the_end() {
        let mut a = Anim::at_speed(0);
        assert_eq!(a.speed_text(), "1/1000×");
        let shown: Vec<String> = SPEEDS.iter().map(|&r| rate_text(r)).collect();
        assert_eq!(shown, ["1/1000×", "1/300×", "1/100×", "1/30×", "1/10×", "1/3×", "1×"]);
        a.advance(3.0, 2.0);
        assert!((a.t_s - 0.003).abs() < 1e-15 && a.playing);
        a.speed = SPEEDS.len() - 1;
        assert_eq!(a.speed_text(), "1×");
        a.advance(5.0, 2.0);
        assert_eq!((a.t_s, a.playing), (2.0, false));
        a.step(true, 2.0);
        assert!((a.t_s - (2.0 - FRAME_S)).abs() < 1e-12);
    }
}
