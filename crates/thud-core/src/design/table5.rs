//! Table 5: the spread of SPLmax among designs banded by damping inclination.

use serde::{Deserialize, Serialize};

use super::{Chart, ZoneBy};

/// One band of Table 5: the spread of SPLmax among designs with e in [e_lo, e_hi).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    pub e_lo_cm_s: f64,
    pub e_hi_cm_s: f64,
    pub count: usize,
    pub spl_min_db: f64,
    pub spl_max_db: f64,
}

/// The smallest and largest inclination (cm/s, by `zone_by`) among the cells Table 5 bands:
/// those with both that inclination and an SPLmax. None when there are none.
pub fn inclination_span(chart: &Chart, zone_by: ZoneBy) -> Option<(f64, f64)> {
    let es: Vec<f64> = chart
        .cells
        .iter()
        .flatten()
        .filter(|c| c.metrics.spl_max_db.is_some())
        .filter_map(|c| c.metrics.inclination_by(zone_by))
        .collect();
    let lo = es.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = es.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (!es.is_empty()).then_some((lo, hi))
}

/// Table 5: the range of SPLmax per band of the inclination (cm/s) of width `width_cm_s`.
pub fn spl_range_by_inclination(chart: &Chart, width_cm_s: f64, zone_by: ZoneBy) -> Vec<Band> {
    let pts: Vec<(f64, f64)> = chart
        .cells
        .iter()
        .flatten()
        .filter_map(|c| Some((c.metrics.inclination_by(zone_by)?, c.metrics.spl_max_db?)))
        .collect();
    if pts.is_empty() || width_cm_s.is_nan() || width_cm_s <= 0.0 {
        return vec![];
    }
    let lo = (pts.iter().map(|p| p.0).fold(f64::INFINITY, f64::min) / width_cm_s).floor() as i64;
    let hi = (pts.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max) / width_cm_s).floor() as i64;
    // Only the bands a point can fall in (its k = ⌊e/w⌋ and the neighbours rounding may put it
    // in) are visited, each by bisection, so the work is O(n log n) in the points however wide
    // the span (a forced chart's e spans 1e7 cm/s; a merge under --no-limit must not hang):
    // the same bands, in the same order, as scanning every k from lo to hi.
    let mut candidates: Vec<i64> = pts
        .iter()
        .flat_map(|p| {
            let k = (p.0 / width_cm_s).floor() as i64;
            [k.saturating_sub(1), k, k.saturating_add(1)]
        })
        .filter(|k| (lo..=hi).contains(k))
        .collect();
    candidates.sort_unstable();
    candidates.dedup();
    let mut sorted = pts;
    sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
    candidates
        .into_iter()
        .filter_map(|k| {
            let (a, b) = (k as f64 * width_cm_s, (k + 1) as f64 * width_cm_s);
            // The points with a ≤ e < b, found by bisection in the sorted points.
            let (from, to) = (sorted.partition_point(|p| p.0 < a), sorted.partition_point(|p| p.0 < b));
            let in_band: Vec<f64> = sorted[from..to.max(from)].iter().map(|p| p.1).collect();
            (!in_band.is_empty()).then(|| Band {
                e_lo_cm_s: a,
                e_hi_cm_s: b,
                count: in_band.len(),
                spl_min_db: in_band.iter().copied().fold(f64::INFINITY, f64::min),
                spl_max_db: in_band.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            })
        })
        .collect()
}
