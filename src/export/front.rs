//! The figure of a design search (`thud design --svg/--pdf`): the Pareto front among every
//! design evaluated, in the space of the two objectives, and (with two numeric variables)
//! the same designs in the space of the variables, below it, over the zone chart of those two
//! variables when it was computed.

use super::figures::{cells, edges, zone_color, zone_legend};
use super::svg::{self, Axis, Frame, Look, Series, Shape, Style, Svg};
use crate::design::{Thresholds, Zone};

/// Grey of the designs evaluated (behind the front): light enough to stay apart from the zone
/// chart's green for red–green colour-blind readers (ΔE00 ≥ 10, tests/it/figure_checks.rs).
const EVALUATED: &str = "#A8A8A8";
/// The front's colour.
const FRONT: &str = "#0072B2";

/// One panel: its axes' labels, every feasible design evaluated and the front's designs (in
/// the front's order), as (x, y) in the axes' units.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    pub x_label: String,
    pub y_label: String,
    pub evaluated: Vec<(f64, f64)>,
    pub front: Vec<(f64, f64)>,
}

/// What the figure shows: the objectives' panel, and the variables' if there are two numeric
/// ones.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontFigure {
    pub title: String,
    pub objectives: Panel,
    pub variables: Option<Panel>,
    /// The zones' borders in the objectives' panel, when its axes are SPLmax and e: the
    /// design's thresholds as (x, y) in the axes' units, drawn as dashed lines.
    pub zone_borders: Option<(f64, f64)>,
    /// The zone chart drawn behind the variables' panel, if computed.
    pub zones: Option<ZoneChart>,
}

/// A zone chart over the two variables: the zone of each cell of a grid (the engine's study of
/// those two axes), drawn as the design chart draws its cells, behind the designs.
#[derive(Debug, Clone, PartialEq)]
pub struct ZoneChart {
    /// The grid's values on each axis, in the panel's units.
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// The zone of cell (i, j) at `zones[j * xs.len() + i]`; None: no impact (or not run).
    pub zones: Vec<Option<Zone>>,
    /// The thresholds that set the zones.
    pub thresholds: Thresholds,
}

/// The colour of the zones' borders.
const BORDER: &str = "#555555";

/// The figure as SVG.
#[must_use]
pub fn front_svg(f: &FrontFigure, look: &Look) -> String {
    let panels: Vec<(&Panel, &str, Style)> = std::iter::once((&f.objectives, "front-objectives", Style::LineMarkers))
        .chain(f.variables.as_ref().map(|p| (p, "front-variables", Style::Markers)))
        .collect();
    let height = if panels.len() == 2 { 760.0 } else { svg::HEIGHT };
    let mut svg = Svg::figure(look, (svg::WIDTH, height), &f.title);
    let k = svg.scale();
    let top_margin = Frame::top_margin(&svg);
    let (left, right, gap) = (85.0 * k, 200.0 * k, 70.0 * k);
    let h = (svg.height() - top_margin - gap * panels.len() as f64) / panels.len() as f64;
    for (i, (p, clip, style)) in panels.iter().enumerate() {
        let all = || p.evaluated.iter().chain(&p.front);
        let borders = f.zone_borders.filter(|_| i == 0);
        let chart = f.zones.as_ref().filter(|z| i == 1 && z.xs.len() >= 2 && z.ys.len() >= 2);
        let (x, y) = match chart {
            // The axes span the chart's cells.
            Some(z) => {
                let (ex, ey) = (edges(&z.xs), edges(&z.ys));
                (Axis::fixed(&p.x_label, ex[0], ex[ex.len() - 1]), Axis::fixed(&p.y_label, ey[0], ey[ey.len() - 1]))
            }
            None => (
                Axis::fit(&p.x_label, all().map(|q| q.0).chain(borders.map(|b| b.0))),
                Axis::fit(&p.y_label, all().map(|q| q.1).chain(borders.map(|b| b.1))),
            ),
        };
        let top = top_margin + i as f64 * (h + gap);
        let frame = Frame { left, top, width: svg.width() - left - right, height: h, x, y };
        match chart {
            Some(z) => {
                frame.grid(&mut svg);
                cells(&mut svg, &frame, &z.xs, &z.ys, |a, b| {
                    let zone = z.zones.get(b * z.xs.len() + a).copied().flatten();
                    (zone_color(zone).into(), zone.map_or(String::new(), |z| z.number().to_string()))
                });
                frame.axes(&mut svg, None, clip);
            }
            None => frame.draw_panel(&mut svg, (i == 0).then_some(f.title.as_str()), clip),
        }
        if let Some((bx, by)) = borders {
            frame.vline(&mut svg, bx, "zone border", BORDER);
            frame.hline(&mut svg, by, "zone border", BORDER);
        }
        let series = [
            Series::new("designs evaluated", p.evaluated.clone(), Style::Markers)
                .colored(EVALUATED.into())
                .shaped(Shape::Circle),
            Series::new("Pareto front", p.front.clone(), *style)
                .colored(FRONT.into())
                .shaped(Shape::Square)
                .dashed(None),
        ];
        svg::draw_series_clipped(&mut svg, &frame, &series, clip);
        if let Some(z) = chart {
            // The zones' swatches and thresholds under the designs' legend.
            let below = Frame { top: frame.top + 50.0 * svg.scale(), ..frame.clone() };
            zone_legend(&mut svg, &below, &z.thresholds, false);
        }
    }
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn panel() -> Panel {
        Panel {
            x_label: "SPLmax (dB)".into(),
            y_label: "e (cm/s)".into(),
            evaluated: vec![(100.0, 1.0), (102.0, 2.5), (104.0, 2.0)],
            front: vec![(100.0, 1.0), (102.0, 2.5)],
        }
    }

    #[test]
    fn the_front_is_drawn_over_the_designs_evaluated_with_a_legend_of_both() {
        let f = FrontFigure {
            title: "front".into(),
            objectives: panel(),
            variables: None,
            zone_borders: None,
            zones: None,
        };
        let doc = front_svg(&f, &Look::default());
        assert!(doc.contains(">designs evaluated<") && doc.contains(">Pareto front<"));
        assert!(doc.contains(FRONT) && doc.contains(EVALUATED));
        // One panel: one clip path; two numeric variables: a second panel below it.
        assert!(doc.contains("front-objectives") && !doc.contains("front-variables"));
        let two = FrontFigure { variables: Some(panel()), ..f.clone() };
        assert!(front_svg(&two, &Look::default()).contains("front-variables"));
        assert!(!doc.contains("zone border"));
        let zoned = front_svg(&FrontFigure { zone_borders: Some((103.0, 0.9)), ..f }, &Look::default());
        assert_eq!(zoned.matches(">zone border<").count(), 2);
    }
}
