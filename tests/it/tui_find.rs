#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Any parameter in two keys: the `/` filter over the fields, the direct keys of the headline
//! inputs (m, g, r, t), a digit that starts typing, a click on a field and a click or drag on
//! the polar that sets θ.

use crate::support::explorer::render;
use crossterm::event::{Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind};
use thud::design::Design;
use thud::tui::app::{App, Mode, Msg};
use thud::tui::compute::{Grid, Grids};
use thud::tui::fields::Knob;
use thud::tui::{compute_sync, Palette};

fn computed_app() -> App {
    let grids = Grids { coarse: None, fine: Grid::standard(6, 5) };
    let mut app = App::with_grids(Design::default(), "default", Palette::default(), grids);
    app.mouse = true;
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    app
}

fn send(app: &mut App, msg: Msg) {
    let reqs = app.update(msg);
    compute_sync(app, reqs);
}

fn press(app: &mut App, code: KeyCode) {
    send(app, Msg::Input(Event::Key(KeyEvent::new(code, KeyModifiers::NONE))));
}

fn type_text(app: &mut App, text: &str) {
    text.chars().for_each(|c| press(app, KeyCode::Char(c)));
}

fn mouse(app: &mut App, kind: MouseEventKind, x: u16, y: u16) {
    send(app, Msg::Input(Event::Mouse(MouseEvent { kind, column: x, row: y, modifiers: KeyModifiers::NONE })));
}

/// The engine's level at the listener (θ as set) for the live design, to the polar's digits.
fn level_at_listener(app: &App) -> String {
    let polar = &app.acoustic().unwrap().polar;
    let theta = app.design.observer.theta_rad.to_degrees();
    let (_, db) = polar.iter().find(|p| (p.0 - theta).abs() < 1e-9).expect("the polar holds the listener's own θ");
    thud::units::sig(*db, 4)
}

#[test]
fn slash_th_enter_selects_theta_then_47_sets_it_and_the_polar_reads_47_degrees() {
    let mut app = computed_app();
    assert_eq!(app.param(), Knob::MASS);
    press(&mut app, KeyCode::Char('/'));
    type_text(&mut app, "th");
    assert_eq!(app.mode, Mode::Find("th".into(), 0));
    let screen = render(&mut app, 80, 24);
    assert!(screen.contains("find: th") && screen.contains("θ"), "the filter and its match show:\n{screen}");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.param(), Knob::THETA, "two keys after / reach θ");
    type_text(&mut app, "47");
    press(&mut app, KeyCode::Enter);
    assert!((app.design.observer.theta_rad.to_degrees() - 47.0).abs() < 1e-9, "{}", app.design.observer.theta_rad);
    let screen = render(&mut app, 80, 24);
    let want = format!("θ 47.0° → {} dB", level_at_listener(&app));
    assert!(screen.contains(&want), "the polar reads the level at 47°: {want}\n{screen}");
}

#[test]
fn esc_cancels_the_filter_and_keeps_the_selection() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('/'));
    type_text(&mut app, "gap");
    press(&mut app, KeyCode::Esc);
    assert_eq!((app.mode.clone(), app.param()), (Mode::Normal, Knob::MASS));
    // ↓ moves among the matches; a filter that matches nothing selects nothing.
    press(&mut app, KeyCode::Char('/'));
    type_text(&mut app, "zzz");
    press(&mut app, KeyCode::Enter);
    assert_eq!(app.param(), Knob::MASS);
    assert!(app.status().unwrap().error, "{:?}", app.status());
}

#[test]
fn m_g_r_t_select_the_headline_inputs_and_the_footer_names_them() {
    let mut app = computed_app();
    for (c, k) in [('g', Knob::GAP), ('r', Knob::R), ('t', Knob::THETA), ('m', Knob::MASS)] {
        press(&mut app, KeyCode::Char(c));
        assert_eq!(app.param(), k, "{c}");
    }
    let screen = render(&mut app, 80, 24);
    let footer = screen.lines().last().unwrap();
    assert!(footer.contains("/ find") && footer.contains("mgrt fields"), "{footer}");
}

#[test]
fn a_click_selects_a_field_and_a_click_or_drag_on_the_polar_sets_theta() {
    let mut app = computed_app();
    render(&mut app, 120, 40);
    let (line, i) = app.drawn.fields.iter().find(|(_, i)| Knob::ALL[*i] == Knob::GAP).copied().unwrap();
    mouse(&mut app, MouseEventKind::Down(MouseButton::Left), line.x + 3, line.y);
    assert_eq!((app.param(), i), (Knob::GAP, app.selected));
    // Straight above the polar's centre is the normal, θ 0°.
    render(&mut app, 120, 40);
    let hit = app.drawn.polar.unwrap();
    let (x, y) = (0..120u16)
        .flat_map(|x| (0..40u16).map(move |y| (x, y)))
        .find(|&(x, y)| hit.theta_at(x, y) == Some(0.0))
        .expect("a cell at θ 0°");
    mouse(&mut app, MouseEventKind::Down(MouseButton::Left), x, y);
    assert_eq!(app.param(), Knob::THETA);
    assert!(app.design.observer.theta_rad.abs() < 1e-12, "{}", app.design.observer.theta_rad);
    let (x, y) = (0..120u16)
        .flat_map(|x| (0..40u16).map(move |y| (x, y)))
        .find(|&(x, y)| hit.theta_at(x, y).is_some_and(|t| t > 30.0 && t < 80.0))
        .unwrap();
    let want = hit.theta_at(x, y).unwrap();
    mouse(&mut app, MouseEventKind::Drag(MouseButton::Left), x, y);
    assert!((app.design.observer.theta_rad.to_degrees() - want).abs() < 1e-9);
    let screen = render(&mut app, 120, 40);
    assert!(screen.contains(&format!("θ {}° → {} dB", thud::units::sig(want, 3), level_at_listener(&app))), "{screen}");
}

#[test]
fn a_digit_starts_typing_into_the_selected_field() {
    let mut app = computed_app();
    press(&mut app, KeyCode::Char('g'));
    type_text(&mut app, "3.5");
    assert_eq!(app.mode, Mode::Editing("3.5".into()));
    press(&mut app, KeyCode::Enter);
    assert!((app.design.damper.gap_m - 0.035).abs() < 1e-12);
}
