//! The interface both solvers run under: a run that starts from a [`Start`] and can be
//! advanced stretch by stretch ([`Stepper`]), so that one driver (`steady::run`) takes either
//! solver to its duration, on through steady-state windows, and hands its end state to the
//! next point of a continuation.

use super::record::Recorder;
use super::{DamperParams, ImpactEvent, Run};

/// The state a run starts from (m, m/s) and the phase of its force at `t = 0` (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Start {
    pub x: f64,
    pub v: f64,
    pub y: f64,
    pub w: f64,
    pub phase: f64,
}

impl Start {
    /// The design's own start: `x = 0`, `x' = v0`, `y = y0`, `y' = w0`, force in phase 0.
    pub fn of(p: &DamperParams) -> Self {
        Start { x: 0.0, v: p.v0_m_s, y: p.ball_position_m, w: p.ball_velocity_m_s, phase: 0.0 }
    }
}

/// A run in progress that can be advanced stretch by stretch: both solvers.
pub(crate) trait Stepper {
    /// Runs on to time `t` (s), or until a work cap or cancellation stops the run.
    fn advance_to(&mut self, t: f64);
    /// Whether a work cap or cancellation has stopped the run.
    fn halted(&self) -> bool;
    fn recorder(&mut self) -> &mut Recorder;
    /// The completed impacts so far.
    fn impacts(&self) -> &[ImpactEvent];
    /// The onset time (s) of a contact the run stands inside, if it stands inside one.
    fn open_onset(&self) -> Option<f64>;
    /// The run as it stands (the stepper is spent for recording afterwards).
    fn finish(&mut self) -> Run;
    /// The state at the end of the run, off the record: a contact still open is carried on to
    /// its end first. `phase_at(t)` is the force's phase at time `t`.
    fn end_state(&mut self, phase_at: impl Fn(f64) -> f64) -> Start;
}
