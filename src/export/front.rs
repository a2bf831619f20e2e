//! The figure of a design search (`thud design --svg/--pdf`): the Pareto front among every
//! design evaluated, in the space of the two objectives, and (with two numeric variables)
//! the same designs in the space of the variables, below it.

use super::svg::{self, Axis, Frame, Look, Series, Shape, Style, Svg};

/// Grey of the designs evaluated (behind the front).
const EVALUATED: &str = "#8C8C8C";
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
        let x = Axis::fit(&p.x_label, all().map(|q| q.0).chain(borders.map(|b| b.0)));
        let y = Axis::fit(&p.y_label, all().map(|q| q.1).chain(borders.map(|b| b.1)));
        let top = top_margin + i as f64 * (h + gap);
        let frame = Frame { left, top, width: svg.width() - left - right, height: h, x, y };
        frame.draw_panel(&mut svg, (i == 0).then_some(f.title.as_str()), clip);
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
        let f = FrontFigure { title: "front".into(), objectives: panel(), variables: None, zone_borders: None };
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
