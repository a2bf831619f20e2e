#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The guided tour at the sizes a lecturer uses (80×24 and 120×40): every step shows every
//! gap row of the chart where it shows the chart, every number its caption names, and the
//! field it talks about selected.

use crate::support::explorer::press;
use crossterm::event::KeyCode;
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use thud::tui::app::{App, Panel};
use thud::tui::compute::{Grid, Grids};
use thud::tui::{compute_sync, draw, Palette};

fn full_app() -> App {
    let d = thud::presets::preset("default").unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(16, 12) };
    let mut app = App::with_grids(d, "default", Palette::default(), grids);
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn render(app: &mut App, w: u16, h: u16) -> String {
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, app).unwrap();
    let buf = term.backend().buffer().clone();
    (0..h).map(|y| (0..w).map(|x| buf[(x, y)].symbol().to_string()).collect::<String>()).collect::<Vec<_>>().join("\n")
}

/// The numbers a caption names as values (a reference like "Eq 27" or "Fig 2" is no value).
fn caption_numbers(caption: &str) -> Vec<String> {
    let words: Vec<&str> = caption.split_whitespace().collect();
    let mut out = Vec::new();
    for (i, w) in words.iter().enumerate() {
        let before = if i > 0 { words[i - 1].trim_start_matches('(') } else { "" };
        if ["Eq", "Fig", "Table", "step", "twice", "Press"].contains(&before) {
            continue;
        }
        let num: String = w
            .trim_start_matches(|c: char| !c.is_ascii_digit())
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '.')
            .collect();
        let num = num.trim_end_matches('.').to_string();
        if !num.is_empty() {
            out.push(num);
        }
    }
    out
}

/// True if `num` is on `screen` as a number of its own (not inside a longer one: "4" is not
/// in "14", "0.7" is in "0.700").
fn shows(screen: &str, num: &str) -> bool {
    screen.match_indices(num).any(|(i, _)| {
        let before = screen[..i].chars().next_back();
        !before.is_some_and(|c| c.is_ascii_digit() || c == '.')
    })
}

#[test]
fn every_tour_step_shows_every_gap_row_every_number_it_names_and_its_field() {
    let mut failures = Vec::new();
    for (w, h) in [(80, 24), (120, 40)] {
        let mut app = full_app();
        press(&mut app, KeyCode::Char('T'));
        let n = app.tour.as_ref().unwrap().tour.steps.len();
        for i in 0..n {
            let step = app.tour.as_ref().unwrap().tour.steps[i].clone();
            let screen = render(&mut app, w, h);
            if std::env::var_os("SHOW").is_some() {
                println!("{screen}\n");
            }
            // The screen above the caption box: what the step shows.
            let caption_top = screen.lines().position(|l| l.contains(&format!("tour {}/{n}", i + 1))).unwrap();
            // and the caption box's last line, which shows the selected field.
            let shown: String = screen
                .lines()
                .take(caption_top)
                .chain(screen.lines().nth(h as usize - 2))
                .collect::<Vec<_>>()
                .join("\n");
            let at = format!("{w}x{h} step {}", i + 1);
            if app.param() != step.select {
                failures.push(format!("{at}: {:?} selected, not {:?}", app.param(), step.select));
            }
            let field_line = screen.lines().nth(h as usize - 2).unwrap();
            if !field_line.contains(&format!("{} = ", step.select.label())) {
                failures.push(format!("{at}: the field is not shown\n{screen}"));
            }
            if step.panel == Panel::Chart {
                let geo = app.drawn.geometry.as_ref().expect("the chart is drawn");
                let mut rows = geo.rows.clone();
                rows.sort_unstable();
                if rows != (0..12).collect::<Vec<_>>() {
                    failures.push(format!("{at}: gap rows {rows:?}\n{screen}"));
                }
            }
            for num in caption_numbers(&step.caption) {
                if !shows(&shown, &num) {
                    failures.push(format!("{at}: '{num}' of the caption is not shown\n{screen}"));
                }
            }
            press(&mut app, KeyCode::Right);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The Table 1 step shows the engine's Table 1 whole at both sizes: every
/// row's measured level, the paper's model, the physical model and both differences, and the
/// mean and rms of the differences, each as `thud paper table1 --json` gives it (the engine's
/// `paper::table1`, read here by column key), to 0.1 dB.
#[test]
fn the_table1_step_shows_the_engine_s_table1_at_both_sizes() {
    use thud::paper::Value;
    let t = thud::paper::table1().unwrap();
    let at = |k: &str| t.columns.iter().position(|c| c.key == k).unwrap();
    let num = |v: &Value| match v {
        Value::Num(x) => *x,
        other => panic!("not a number: {other:?}"),
    };
    let diff = |x: f64| format!("{x:+.1}").replace('-', "−");
    let mut want: Vec<String> = Vec::new();
    for row in &t.rows {
        for k in ["spl_experiment_db", "spl_model_db", "spl_physical_db"] {
            want.push(format!("{:.1}", num(&row[at(k)])));
        }
        for k in ["model_minus_experiment_db", "physical_minus_experiment_db"] {
            want.push(diff(num(&row[at(k)])));
        }
    }
    for name in ["mean", "rms"] {
        let row = t.summary.iter().find(|r| r[0] == Value::Text(name.into())).unwrap();
        for k in ["model_minus_experiment_db", "physical_minus_experiment_db"] {
            let x = num(&row[at(k)]);
            // The rms is a magnitude, shown without a sign.
            want.push(if name == "rms" { format!("{x:.1}") } else { diff(x) });
        }
    }
    let mut failures = Vec::new();
    for (w, h) in [(80, 24), (120, 40)] {
        let mut app = full_app();
        press(&mut app, KeyCode::Char('T'));
        let steps = app.tour.as_ref().unwrap().tour.steps.clone();
        let i = steps.iter().position(|s| s.table1).expect("the tour has a Table 1 step");
        for _ in 0..i {
            press(&mut app, KeyCode::Right);
        }
        let screen = render(&mut app, w, h);
        let caption_top = screen.lines().position(|l| l.contains(&format!("tour {}/", i + 1))).unwrap();
        let shown: String = screen.lines().take(caption_top).collect::<Vec<_>>().join("\n");
        assert!(shown.contains("Table 1"), "{w}x{h}:\n{screen}");
        for cell in &want {
            if !shows(&shown, cell) {
                failures.push(format!("{w}x{h}: {cell} is not shown\n{screen}"));
            }
        }
        // `M` closes the view and opens it again, outside the tour too.
        press(&mut app, KeyCode::Esc);
        press(&mut app, KeyCode::Char('M'));
        assert!(app.table1.is_none(), "M closes the view");
        press(&mut app, KeyCode::Char('M'));
        assert!(render(&mut app, w, h).contains("measured"), "M opens it");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// The README, the guide and the built-in tour's own header say how many steps the tour has:
/// the number the tour runs (and the screen shows as "tour i/N").
#[test]
fn the_docs_say_the_tour_s_own_number_of_steps() {
    const WORDS: [&str; 13] =
        ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve"];
    let n = thud::tui::tour::Tour::load(&thud::tui::tour::TourSource::BuiltIn).unwrap().steps.len();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    for file in ["README.md", "docs/guide/the-explorer.md", "assets/tour.toml"] {
        let text = std::fs::read_to_string(root.join(file)).unwrap().replace("\n# ", " ").replace('\n', " ");
        let at = text.find("the paper's story in ").unwrap_or_else(|| panic!("{file}: no \"the paper's story in N\""));
        let said = text[at..].split_whitespace().nth(4).unwrap();
        assert_eq!(said, WORDS[n], "{file} says the tour has {said} steps; it has {n}");
    }
}

/// The tour's animation step at 80×24 plays at a speed where the ball visibly rattles: within
/// 2 s of real time (60 frames of 1/30 s, as the event loop sends them) an impact is flashed and
/// named on screen, and the ball has moved.
#[test]
fn the_tour_s_animation_shows_an_impact_within_2_s_at_80x24() {
    use thud::tui::anim::FRAME_S;
    use thud::tui::app::Msg;
    let mut app = full_app();
    press(&mut app, KeyCode::Char('T'));
    let steps = app.tour.as_ref().unwrap().tour.steps.clone();
    let i = steps.iter().position(|s| s.animate).expect("the tour has an animation step");
    for _ in 0..i {
        press(&mut app, KeyCode::Right);
    }
    let first = render(&mut app, 80, 24);
    assert!(first.contains("playing"), "{first}");
    let picture =
        |s: &str| s.lines().skip(2).take(14).map(|l| l.chars().take(40).collect::<String>()).collect::<Vec<_>>();
    // The impact the flash line names ("impact k at the …"), if any.
    let named = |s: &str| -> Option<usize> {
        s.match_indices("impact ").find_map(|(i, w)| {
            let rest = &s[i + w.len()..];
            let k: String = rest.chars().take_while(char::is_ascii_digit).collect();
            rest[k.len()..].starts_with(" at the ").then(|| k.parse().ok()).flatten()
        })
    };
    let (mut first_seen, mut moved, mut last) = (None, false, 0);
    for frame in 1..=60 {
        app.update(Msg::Frame(FRAME_S));
        let screen = render(&mut app, 80, 24);
        moved |= picture(&screen) != picture(&first);
        if let Some(k) = named(&screen) {
            first_seen.get_or_insert(frame);
            last = last.max(k);
        }
    }
    let shown = render(&mut app, 80, 24);
    let frame = first_seen.unwrap_or_else(|| panic!("no impact flashed within 2 s of real time:\n{shown}"));
    assert!(moved, "the ball moved:\n{shown}");
    let speed = shown.lines().find_map(|l| l.split("speed ").nth(1)?.split_whitespace().next()).unwrap_or_default();
    eprintln!(
        "at speed {speed}: the first impact flashed after {:.2} s of real time, impact {last} by 2 s",
        f64::from(frame) * FRAME_S
    );
    // A few impacts a second: the ball rattles, not one click.
    assert!(last >= 3, "impact {last} by 2 s of real time:\n{shown}");
}

/// The → that would have been the tour's "next" once more, after its last step, changes
/// nothing: it says what → does now; the next one changes the design.
#[test]
fn the_first_arrow_after_the_tour_says_what_it_does_and_changes_nothing() {
    let mut app = full_app();
    press(&mut app, KeyCode::Char('T'));
    let n = app.tour.as_ref().unwrap().tour.steps.len();
    for _ in 0..n {
        press(&mut app, KeyCode::Right);
    }
    assert!(app.tour.is_none(), "the last → finishes the tour");
    let design = app.design.clone();
    press(&mut app, KeyCode::Right);
    assert_eq!(app.design, design, "the first → after the tour changes nothing");
    let status = app.status().unwrap().text.clone();
    assert!(status.contains("the tour is over") && status.contains("again to"), "{status}");
    press(&mut app, KeyCode::Right);
    assert_ne!(app.design, design, "the next → changes the design: {:?}", app.status());
}
