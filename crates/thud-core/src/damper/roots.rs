//! The root finders the integrators share: the Illinois regula falsi on a sign change inside a
//! step (the reference scheme's quintic interpolant, the Newmark scheme's substeps) and Newton
//! kept inside a bracket by bisection (the free flight's events, the Sundman schemes' series).
//! Each caller keeps its own tolerances; the arithmetic is the callers' as it was.

/// When the Illinois search stops: the bracket at most `width` wide, or the function at most
/// `value` in magnitude (both inclusive; a strict bound `b` is `b.next_down()`).
#[derive(Clone, Copy)]
pub(super) struct IllinoisStop {
    pub width: f64,
    pub value: f64,
}

/// A zero of `eval` between `lo` and `hi` where it takes `g_lo` and `g_hi` of opposite signs:
/// the Illinois regula falsi (the secant point, bisection when it leaves the bracket, the
/// retained end's value halved when the same end is kept twice), 60 evaluations at most.
/// `eval(x)` returns the function and whatever the caller wants back with it; returns the last
/// point evaluated and its extra (`first` if none was).
pub(super) fn illinois<T>(
    (mut lo, mut g_lo): (f64, f64),
    (mut hi, mut g_hi): (f64, f64),
    stop: IllinoisStop,
    first: (f64, T),
    mut eval: impl FnMut(f64) -> (f64, T),
) -> (f64, T) {
    let mut best = first;
    let mut side = 0;
    for _ in 0..60 {
        let x = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        let x = if x > lo && x < hi { x } else { 0.5 * (lo + hi) };
        let (g, extra) = eval(x);
        best = (x, extra);
        if g == 0.0 || hi - lo <= stop.width {
            break;
        }
        if (g > 0.0) == (g_lo > 0.0) {
            lo = x;
            g_lo = g;
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            hi = x;
            g_hi = g;
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
        if g.abs() <= stop.value {
            break;
        }
    }
    best
}

/// How a bracketed Newton search ([`newton`]) ends.
#[derive(Clone, Copy)]
pub(super) enum NewtonEnd {
    /// To a few ulp of the root, over at most 100 evaluations: the bracket within 4 ε·|hi| gives
    /// its middle, a Newton step within ε·|x| gives that step kept in the bracket; past the
    /// last evaluation, the bracket's middle. A function `< 0` moves the lower end when it
    /// rises.
    Ulp,
    /// To a few ulp of the span `h`, over at most 80 evaluations: the bracket within 4 ε·h or
    /// a Newton step within 2 ε·h gives that step if strictly inside the bracket, else the last
    /// point; past the last evaluation, the last Newton point. A function `> 0` moves the upper
    /// end when it rises.
    Span(f64),
}

/// The zero of `g` (value and derivative) inside `[lo, hi]`, where it rises if `up` (it has
/// opposite signs at the ends), by Newton from `x`, a point outside the bracket replaced by
/// its middle; `end` says when it stops and what it returns.
pub(super) fn newton(
    (mut lo, mut hi): (f64, f64),
    up: bool,
    mut x: f64,
    end: NewtonEnd,
    g: impl Fn(f64) -> (f64, f64),
) -> f64 {
    let evaluations = match end {
        NewtonEnd::Ulp => 100,
        NewtonEnd::Span(_) => 80,
    };
    for _ in 0..evaluations {
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        let (v, d) = g(x);
        if v == 0.0 {
            return x;
        }
        // The two differ only for a NaN value.
        let lower = match end {
            NewtonEnd::Ulp => (v < 0.0) == up,
            NewtonEnd::Span(_) => (v > 0.0) != up,
        };
        if lower {
            lo = x;
        } else {
            hi = x;
        }
        let next = x - v / d;
        match end {
            NewtonEnd::Ulp => {
                if hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(1e-300) {
                    return 0.5 * (lo + hi);
                }
                // Converged (or stalled); a step that is no number bisects instead.
                if next.is_finite() && (next - x).abs() <= f64::EPSILON * x.abs() {
                    return next.clamp(lo, hi);
                }
            }
            NewtonEnd::Span(h) => {
                if hi - lo <= 4.0 * f64::EPSILON * h || (next - x).abs() <= 2.0 * f64::EPSILON * h {
                    return if next > lo && next < hi { next } else { x };
                }
            }
        }
        x = next;
    }
    match end {
        NewtonEnd::Ulp => 0.5 * (lo + hi),
        NewtonEnd::Span(_) => x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Illinois on a cubic with a known root: the root to the stop's width, and the extra of
    /// the last evaluated point handed back with it.
    #[test]
    fn illinois_finds_a_cubic_root() {
        let f = |x: f64| x * x * x - 2.0;
        let stop = IllinoisStop { width: 1e-15, value: 1e-17 };
        let (x, calls) = illinois((0.0, f(0.0)), (2.0, f(2.0)), stop, (2.0, 0), {
            let mut n = 0;
            move |x| {
                n += 1;
                (f(x), n)
            }
        });
        assert!((x - 2f64.cbrt()).abs() < 1e-14, "{x}");
        assert!(calls > 1 && calls <= 60, "{calls}");
    }

    /// Both Newton endings find a root of `cos` in `[1, 2]` (falling) and of `x² − 2` in `[0, 2]`
    /// (rising) to a few ulp, and a value of 0 at the start is returned as is.
    #[test]
    fn newton_finds_roots_both_ways() {
        let half_pi = std::f64::consts::FRAC_PI_2;
        for end in [NewtonEnd::Ulp, NewtonEnd::Span(1.0)] {
            let r = newton((1.0, 2.0), false, 1.2, end, |x| (x.cos(), -x.sin()));
            assert!((r - half_pi).abs() <= 4.0 * f64::EPSILON, "{r}");
            let r = newton((0.0, 2.0), true, 1.0, end, |x| (x * x - 2.0, 2.0 * x));
            assert!((r - 2f64.sqrt()).abs() <= 8.0 * f64::EPSILON, "{r}");
            let r = newton((0.0, 2.0), true, 1.5, end, |x| (x - 1.5, 1.0));
            assert_eq!(r, 1.5);
        }
    }
}
