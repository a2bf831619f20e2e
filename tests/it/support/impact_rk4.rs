//! A second, independent integration of the impact damper, for the fit tests: a fixed-step
//! classical Runge–Kutta (RK4) of Eqs 25–26 written here from the equations, not thud's solver
//! (no event location, no contact scheme of thud's): the main mass M on its spring K and
//! damper C, the ball m free in the clearance d, and past either wall the Hertz force
//! K_HZ·δ^1.5 + c1·δ' (δ the overlap; with the no-tension clamp, never pulling).

use thud_core::damper::DamperParams;

/// The state `[x, x', y, y']` (m, m/s).
pub type State = [f64; 4];

/// The rates `[x', x'', y', y'']` of design `p` with contact damping `c1` (N·s/m) at `s`.
#[must_use]
pub fn rates(p: &DamperParams, c1: f64, s: State) -> State {
    let [x, v, y, w] = s;
    let z = y - x;
    let delta = z.abs() - 0.5 * p.gap_m;
    // The force on the ball, along −sign(z) while it presses into the wall.
    let f_ball = if delta > 0.0 {
        let sg = z.signum();
        let mut push = p.k_hz * delta.powf(1.5) + c1 * sg * (w - v);
        if p.no_tension {
            push = push.max(0.0);
        }
        -sg * push
    } else {
        0.0
    };
    [v, (-p.stiffness_n_m * x - p.damping_n_s_m * v - f_ball) / p.main_mass_kg, w, f_ball / p.impact_mass_kg]
}

/// Integrates design `p` with contact damping `c1` from the strike (x = 0, x' = `p.v0_m_s`,
/// the ball at rest at `y0`) for `steps` steps of `dt` (s); `visit(i, state, rates)` sees the
/// start (`i = 0`) and the state after each step.
pub fn run(p: &DamperParams, c1: f64, y0: f64, dt: f64, steps: usize, mut visit: impl FnMut(usize, State, State)) {
    let add = |a: State, b: State, h: f64| [a[0] + h * b[0], a[1] + h * b[1], a[2] + h * b[2], a[3] + h * b[3]];
    let mut s = [0.0, p.v0_m_s, y0, 0.0];
    visit(0, s, rates(p, c1, s));
    for i in 1..=steps {
        let k1 = rates(p, c1, s);
        let k2 = rates(p, c1, add(s, k1, 0.5 * dt));
        let k3 = rates(p, c1, add(s, k2, 0.5 * dt));
        let k4 = rates(p, c1, add(s, k3, dt));
        for j in 0..4 {
            s[j] += dt / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]);
        }
        visit(i, s, rates(p, c1, s));
    }
}

/// A small fixed generator (SplitMix64): repeatable draws.
pub struct Draws(pub u64);

impl Draws {
    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub fn between(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform().max(1e-300), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    }
}
