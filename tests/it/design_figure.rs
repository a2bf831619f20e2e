#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The front's figure with the zone chart behind the variables' panel (`thud design --svg`
//! with two numeric variables): every zone drawn in its colour under the designs, named in the
//! legend with the thresholds; no chart, no cells. (The command's figure is checked for its
//! legend and its colours with the gallery's in tests/it/figure_checks.rs.)

use thud::design::{Thresholds, Zone};
use thud::export::figures::zone_color;
use thud::export::front::{front_svg, FrontFigure, Panel, ZoneChart};
use thud::export::svg::Look;

fn panel() -> Panel {
    Panel {
        x_label: "mass_kg".into(),
        y_label: "gap_m".into(),
        evaluated: vec![(0.03, 0.02), (0.05, 0.03), (0.09, 0.05)],
        front: vec![(0.03, 0.02), (0.05, 0.03)],
    }
}

#[test]
fn the_zone_chart_lies_behind_the_variables_designs_with_its_legend() {
    let zones = ZoneChart {
        xs: vec![0.02, 0.06, 0.1],
        ys: vec![0.01, 0.035, 0.06],
        zones: vec![
            Some(Zone::QuietStrong),
            Some(Zone::NoisyStrong),
            None,
            Some(Zone::QuietWeak),
            Some(Zone::NoisyWeak),
            None,
            Some(Zone::QuietStrong),
            Some(Zone::QuietStrong),
            None,
        ],
        thresholds: Thresholds::default(),
    };
    let f = FrontFigure {
        title: "front".into(),
        objectives: panel(),
        variables: Some(panel()),
        zone_borders: None,
        zones: Some(zones),
    };
    let doc = front_svg(&f, &Look::default());
    for z in [Zone::NoisyWeak, Zone::NoisyStrong, Zone::QuietStrong, Zone::QuietWeak] {
        assert!(doc.contains(zone_color(Some(z))), "zone {} drawn", z.number());
        assert!(doc.contains(&format!(">{} {}<", z.number(), z.describe())), "zone {} in the legend", z.number());
    }
    assert!(doc.contains(">no impact<"));
    // The cells come before the front's designs: the front is drawn over them.
    let first_cell = doc.find(zone_color(Some(Zone::NoisyWeak))).unwrap();
    let last_front = doc.rfind(">Pareto front<").unwrap();
    assert!(first_cell < last_front);
    // Without a chart: no cell colour.
    let plain = front_svg(&FrontFigure { zones: None, ..f }, &Look::default());
    assert!(!plain.contains(zone_color(Some(Zone::NoisyWeak))));
}
