#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The stability of Masri & Caughey's symmetric two-impact orbit (docs/model.md
//! §12). The published derivation (Masri & Caughey 1966) was not available to
//! this project, so the linearised impact-to-impact map is derived numerically from the
//! closed-form impact map: from the state just after an upper-wall impact (its time, the main
//! mass's position and velocity, the particle's velocity), the analytic flight (the steady
//! particular motion plus the free decay of the rest, the particle in a straight line) runs to
//! the next impact on the lower wall (the first root of z = −d/2, bracketed on a fine scan and
//! bisected), the impact law (momentum, restitution r) is applied, and the result is reflected
//! (x, x', y' → −x, −x', −y', t → t − T/2): the symmetric orbit is this map's fixed point, and
//! it is stable when every eigenvalue of the map's Jacobian (central differences) lies inside
//! the unit circle.

use std::f64::consts::PI;

use thud::damper::{simulate, single_contact, DamperParams, RunOptions, Solver};

use super::masri_caughey::{free, masri_caughey, Orbit};

/// The system of one closed-form orbit: masses (kg), spring (N/m), damping (N·s/m), clearance
/// (m), Ω (rad/s), restitution, and the steady particular motion `X·cos(Ωt + β)`.
struct Sys {
    mm: f64,
    k: f64,
    c: f64,
    m: f64,
    d: f64,
    omega: f64,
    r: f64,
    big_x: f64,
    beta: f64,
}

impl Sys {
    fn main_mass(&self, t0: f64, (x0, v0): (f64, f64), t: f64) -> (f64, f64) {
        let xp = |t: f64| self.big_x * (self.omega * t + self.beta).cos();
        let vp = |t: f64| -self.big_x * self.omega * (self.omega * t + self.beta).sin();
        let h = free(self.mm, self.k, self.c, (x0 - xp(t0), v0 - vp(t0)), t - t0);
        (xp(t) + h.0, vp(t) + h.1)
    }

    /// The symmetric half of the impact map: `(t0, x0, v0, w0)` just after an upper-wall impact
    /// → the same just after the next (lower-wall) impact, reflected.
    fn map(&self, s: [f64; 4]) -> [f64; 4] {
        let [t0, x0, v0, w0] = s;
        let half = PI / self.omega;
        let g = |t: f64| {
            let y = x0 + 0.5 * self.d + w0 * (t - t0);
            y - self.main_mass(t0, (x0, v0), t).0 + 0.5 * self.d
        };
        let dt = half / 4000.0;
        let mut a = t0 + 1e-9 * half;
        let mut b = a + dt;
        while g(b) > 0.0 {
            a = b;
            b += dt;
            assert!(b < t0 + 3.0 * half, "no lower-wall impact");
        }
        for _ in 0..200 {
            let mid = 0.5 * (a + b);
            if g(mid) > 0.0 {
                a = mid;
            } else {
                b = mid;
            }
        }
        let t1 = 0.5 * (a + b);
        let (x1, v) = self.main_mass(t0, (x0, v0), t1);
        let w = w0;
        let (mm, m, r) = (self.mm, self.m, self.r);
        let v_after = (mm * v + m * w + m * r * (w - v)) / (mm + m);
        let w_after = (mm * v + m * w - mm * r * (w - v)) / (mm + m);
        [t1 - half, -x1, -v_after, -w_after]
    }
}

/// A complex number (re, im).
type C = (f64, f64);

/// Eigenvalues (re, im) of a 4×4 matrix: the characteristic polynomial by Faddeev–LeVerrier,
/// its roots by Durand–Kerner.
fn eigenvalues(a: [[f64; 4]; 4]) -> Vec<(f64, f64)> {
    let mul = |x: &[[f64; 4]; 4], y: &[[f64; 4]; 4]| {
        let mut z = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                z[i][j] = (0..4).map(|k| x[i][k] * y[k][j]).sum();
            }
        }
        z
    };
    // p(λ) = λ⁴ + c1 λ³ + c2 λ² + c3 λ + c4.
    let mut coef = [1.0, 0.0, 0.0, 0.0, 0.0];
    let mut mk = [[0.0; 4]; 4];
    for k in 1..=4 {
        let mut am = mul(&a, &mk);
        for (i, row) in am.iter_mut().enumerate() {
            row[i] += coef[k - 1];
        }
        mk = am;
        let tr: f64 = (0..4).map(|i| mul(&a, &mk)[i][i]).sum();
        coef[k] = -tr / k as f64;
    }
    let cm = |a: C, b: C| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let cd = |a: C, b: C| {
        let n = b.0 * b.0 + b.1 * b.1;
        ((a.0 * b.0 + a.1 * b.1) / n, (a.1 * b.0 - a.0 * b.1) / n)
    };
    let p = |z: C| {
        coef.iter().fold((0.0, 0.0), |acc, &c| {
            let m = cm(acc, z);
            (m.0 + c, m.1)
        })
    };
    let mut roots: Vec<C> = (0..4)
        .map(|i| {
            let ang = 0.4 + 2.0 * PI * f64::from(i) / 4.0;
            (0.9 * ang.cos(), 0.9 * ang.sin())
        })
        .collect();
    for _ in 0..2000 {
        for i in 0..4 {
            let mut den = (1.0, 0.0);
            for j in 0..4 {
                if i != j {
                    den = cm(den, (roots[i].0 - roots[j].0, roots[i].1 - roots[j].1));
                }
            }
            let step = cd(p(roots[i]), den);
            roots[i] = (roots[i].0 - step.0, roots[i].1 - step.1);
        }
    }
    roots
}

/// The moduli of the eigenvalues of the linearised symmetric impact map about `o`, largest
/// first, and how far `o` is from being the map's fixed point (relative).
pub(crate) fn stability(p: &DamperParams, o: &Orbit, r: f64) -> (Vec<f64>, f64) {
    let sys = Sys {
        mm: p.main_mass_kg,
        k: p.stiffness_n_m,
        c: p.damping_n_s_m,
        m: p.impact_mass_kg,
        d: p.gap_m,
        omega: 2.0 * PI * p.freq_hz,
        r,
        big_x: o.big_x,
        beta: o.beta,
    };
    let s0 = [0.0, o.x0, o.v_after, o.w_after];
    let scale = [1.0 / p.freq_hz, o.amplitude, o.u, o.u];
    let image = sys.map(s0);
    let miss = (0..4).map(|i| ((image[i] - s0[i]) / scale[i]).abs()).fold(0.0, f64::max);
    let mut jac = [[0.0; 4]; 4];
    for j in 0..4 {
        let h = 1e-6 * scale[j];
        let (mut a, mut b) = (s0, s0);
        a[j] += h;
        b[j] -= h;
        let (fa, fb) = (sys.map(a), sys.map(b));
        for i in 0..4 {
            jac[i][j] = (fa[i] - fb[i]) / (2.0 * h);
        }
    }
    let mut mods: Vec<f64> = eigenvalues(jac).iter().map(|z| z.0.hypot(z.1)).collect();
    mods.sort_by(|a, b| b.total_cmp(a));
    (mods, miss)
}

/// The forced Table 2 design (C 0.5 N·s/m) of the agreement tests with clearance `gap` (m),
/// force `f0` (N) at `f` (Hz), Hertz stiffness `khz` and `duration` (s).
pub(crate) fn design(gap: f64, f0: f64, f: f64, khz: f64, duration: f64) -> DamperParams {
    DamperParams {
        gap_m: gap,
        force_n: f0,
        freq_hz: f,
        v0_m_s: 0.0,
        duration_s: duration,
        settle: true,
        damping_n_s_m: 0.5,
        k_hz: khz,
        ..DamperParams::table2()
    }
}

/// thud's run of `p`: steady amplitude (m), last impact speed (m/s), relative difference of the
/// last two impacts' speeds, impacts a period; and r of thud's contact at that speed.
fn thud(p: &DamperParams) -> (f64, f64, f64, f64, f64) {
    let run = simulate(p, Solver::Event, &RunOptions::default()).unwrap();
    let s = run.steady.unwrap();
    let last: Vec<_> = run.impacts.iter().rev().take(2).collect();
    let u = last[0].u_in_m_s;
    let asym = (last[0].u_in_m_s / last[1].u_in_m_s - 1.0).abs();
    let r = single_contact(p.impact_mass_kg, p.main_mass_kg, p.k_hz, p.c1_n_s_m, false, u).u_out_m_s / u;
    (s.amplitude_m, u, asym, s.impacts_per_period, r)
}

pub(crate) fn orbits(p: &DamperParams, r: f64) -> Vec<Orbit> {
    masri_caughey(
        p.main_mass_kg,
        p.stiffness_n_m,
        p.damping_n_s_m,
        p.impact_mass_kg,
        p.gap_m,
        p.force_n,
        2.0 * PI * p.freq_hz,
        r,
    )
}

/// The orbit of `orbits` nearest in impact speed to `u`, and the other one.
fn nearest(os: Vec<Orbit>, u: f64) -> (Orbit, Option<Orbit>) {
    let mut os = os;
    os.sort_by(|a, b| (a.u - u).abs().total_cmp(&(b.u - u).abs()));
    (os[0], os.get(1).copied())
}

/// (a) Where the closed form's orbit is stable thud stays on it; (b) where it is unstable
/// thud is not there. d 3 cm, F0 1 N at 5.5 Hz, K_HZ 5.6e8: the orbit thud settles to is the
/// stable root (|λ| 0.957, 0.906; amplitude within 2 %); the quadratic's other root (|λ| 26.6)
/// is a saddle thud never reaches (its amplitude is 74 % away). thud's run cannot start at a
/// given x (its main mass starts at x = 0), so "stays" is "settles to".
#[test]
fn the_stable_root_is_where_thud_settles_and_the_unstable_root_is_not() {
    let p = design(0.03, 1.0, 5.5, 5.6e8, 20.0);
    let (amp, u, _, ipp, r) = thud(&p);
    assert!((ipp - 2.0).abs() < 1e-3);
    let (stable, other) = nearest(orbits(&p, r), u);
    let (mods, miss) = stability(&p, &stable, r);
    assert!(miss < 1e-9, "not a fixed point: {miss}");
    assert!(mods[0] < 1.0, "{mods:?}");
    assert!((amp / stable.amplitude - 1.0).abs() < 0.02);
    let other = other.expect("two roots");
    let (mods, _) = stability(&p, &other, r);
    assert!(mods[0] > 1.0, "{mods:?}");
    assert!((amp / other.amplitude - 1.0).abs() > 0.02);
}

/// The case that disagreed by 4.5 % (d 2 cm, F0 2 N at 6 Hz, K_HZ 5.6e8) is explained by
/// stability, not by the contact's duration: the closed form's symmetric orbit there is
/// unstable (largest |λ| 1.36, real), and thud settles to a nearby two-impact orbit that is not
/// symmetric (its two walls' speeds differ by 2e-4). A 100× stiffer contact (shorter, r 0.985)
/// does not close the gap (|λ| 1.46; 5.5 %); a 100× softer one (r 0.53) makes the symmetric
/// orbit stable (|λ| 0.97) and thud lands on it within 2 %.
#[test]
fn the_4_5_percent_case_is_an_unstable_symmetric_orbit() {
    let p = design(0.02, 2.0, 6.0, 5.6e8, 20.0);
    let (amp, u, asym, _, r) = thud(&p);
    let (o, _) = nearest(orbits(&p, r), u);
    let (mods, _) = stability(&p, &o, r);
    assert!(mods[0] > 1.0, "{mods:?}");
    assert!(asym > 1e-5, "{asym}");
    let gap = (amp / o.amplitude - 1.0).abs();
    assert!(gap > 0.02, "{gap}");
    let stiff = design(0.02, 2.0, 6.0, 5.6e10, 20.0);
    let (amp_s, u_s, _, _, r_s) = thud(&stiff);
    let (o_s, _) = nearest(orbits(&stiff, r_s), u_s);
    assert!(stability(&stiff, &o_s, r_s).0[0] > 1.0);
    assert!((amp_s / o_s.amplitude - 1.0).abs() >= gap);
    let soft = design(0.02, 2.0, 6.0, 5.6e6, 20.0);
    let (amp_f, u_f, _, _, r_f) = thud(&soft);
    let (o_f, _) = nearest(orbits(&soft, r_f), u_f);
    assert!(stability(&soft, &o_f, r_f).0[0] < 1.0);
    assert!((amp_f / o_f.amplitude - 1.0).abs() < 0.02);
}
