#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! End to end: the real binary in a tmux pane. The screen appears, a key changes a value, a
//! resize to 80×24 keeps it usable, `q` exits with status 0 and the terminal is sane after:
//! canonical mode and echo on, alternate screen left, cursor shown, mouse reporting off. The
//! teaching layout: at 80×24 the pulse and the polar side by side on start, the chart's marker
//! showing the readout's zone at 80×24 and 200×60, typed values in the unit shown, the tour.
//! Requires tmux (CI installs it); fails with a clear message without it.

use std::path::PathBuf;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use crate::support::stranger::Stranger;

const TIMEOUT: Duration = Duration::from_secs(20);

/// A private tmux server (own socket), killed when dropped.
struct Tmux {
    socket: String,
    dir: PathBuf,
}

impl Tmux {
    /// Starts `shell_cmd(dir)` in a `w × h` pane; `dir` is a fresh temporary directory.
    fn start(shell_cmd: impl Fn(&std::path::Path) -> String, w: u16, h: u16) -> Self {
        let found = Command::new("tmux").arg("-V").output().is_ok_and(|o| o.status.success());
        assert!(found, "tmux is not installed: install it (apt-get install tmux) to run this end-to-end test");
        let socket = format!("thud-test-{}-{}", std::process::id(), rand_suffix());
        let dir = std::env::temp_dir().join(&socket);
        std::fs::create_dir_all(&dir).unwrap();
        let t = Self { socket, dir };
        let out = t.run(&[
            "new-session",
            "-d",
            "-x",
            &w.to_string(),
            "-y",
            &h.to_string(),
            "-e",
            "TERM=xterm-256color",
            "sh",
            "-c",
            &shell_cmd(&t.dir),
        ]);
        assert!(out.status.success(), "tmux new-session failed: {}", String::from_utf8_lossy(&out.stderr));
        t
    }

    /// Starts the built explorer (mouse on, its config and data in the pane's folder) in a
    /// `w × h` pane; when it ends, its exit status goes to `status`, `stty -a` to `stty`, and the
    /// shell prints AFTER-THUD and waits.
    fn explorer(w: u16, h: u16) -> Self {
        let bin = env!("CARGO_BIN_EXE_thud");
        Self::start(
            |d| {
                format!(
                    "cd '{d}' && XDG_CONFIG_HOME='{d}/config' XDG_DATA_HOME='{d}/data' '{bin}' tui --mouse; \
                     echo $? > '{d}/status'; stty -a > '{d}/stty'; echo AFTER-THUD; exec sleep 60",
                    d = d.display()
                )
            },
            w,
            h,
        )
    }

    fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux").arg("-L").arg(&self.socket).arg("-f").arg("/dev/null").args(args).output().unwrap()
    }

    fn capture(&self) -> String {
        String::from_utf8_lossy(&self.run(&["capture-pane", "-p"]).stdout).into_owned()
    }

    fn format(&self, f: &str) -> String {
        String::from_utf8_lossy(&self.run(&["display-message", "-p", f]).stdout).trim().to_string()
    }

    fn keys(&self, keys: &[&str]) {
        let mut args = vec!["send-keys"];
        args.extend_from_slice(keys);
        assert!(self.run(&args).status.success());
    }

    /// Polls the screen until `ok` holds; panics with the last screen after the timeout.
    fn wait_for(&self, what: &str, ok: impl Fn(&str) -> bool) -> String {
        let start = Instant::now();
        loop {
            let screen = self.capture();
            if ok(&screen) {
                return screen;
            }
            assert!(start.elapsed() < TIMEOUT, "timed out waiting for {what}; screen:\n{screen}");
            std::thread::sleep(Duration::from_millis(40));
        }
    }

    fn wait_file(&self, name: &str) -> String {
        let path = self.dir.join(name);
        let start = Instant::now();
        loop {
            if let Ok(s) = std::fs::read_to_string(&path) {
                if s.ends_with('\n') {
                    return s;
                }
            }
            assert!(start.elapsed() < TIMEOUT, "timed out waiting for {}; screen:\n{}", path.display(), self.capture());
            std::thread::sleep(Duration::from_millis(40));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn rand_suffix() -> u128 {
    std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos())
}

/// True if `word` is a whitespace-separated token of `text` (so "echo" but not "-echo").
fn has_token(text: &str, word: &str) -> bool {
    text.split_whitespace().any(|t| t == word)
}

#[test]
fn real_binary_in_tmux_starts_changes_resizes_quits_and_restores() {
    let t = Tmux::explorer(120, 40);

    // 1. The screen appears with computed numbers.
    let computed = |s: &str| s.lines().any(|l| l.contains("U0max") && l.contains("m/s"));
    let s = t.wait_for("the main screen with a computed readout", |s| s.contains("parameters") && computed(s));
    assert!(s.contains("40.50 g"), "{s}");
    assert_eq!(t.format("#{alternate_on}"), "1", "runs on the alternate screen");

    // 2. A key changes a value.
    t.keys(&["Right"]);
    t.wait_for("mass 41.50 g", |s| s.contains("41.50 g"));

    // 3. Resize to 80×24: still usable (parameters and readout on screen).
    assert!(t.run(&["resize-window", "-x", "80", "-y", "24"]).status.success());
    let s = t.wait_for("the 80×24 layout", |s| {
        s.lines().count() <= 24 && s.contains("parameters") && s.contains("readout") && s.contains("U0max")
    });
    assert!(s.lines().all(|l| l.chars().count() <= 80), "{s}");
    // `-` (the table's other key for a smaller step) rather than ←: ← is an escape sequence,
    // which a loaded machine can deliver split so that the terminal reads a lone Esc; step 2
    // already drove the arrows.
    t.keys(&["-"]);
    t.wait_for("mass back to 40.50 g at 80×24", |s| s.contains("40.50 g"));

    // 4. With --mouse, a click on a chart cell (the bottom row: gap 1 cm) selects that design.
    // At 80×24 the pulse and the polar come first; Tab brings in the history and the chart.
    t.keys(&["Tab", "Tab", "Tab"]);
    let s = t.wait_for("the chart's bottom row", |s| s.lines().any(|l| l.contains("│  1.0 ")));
    let (y, line) = s.lines().enumerate().find(|(_, l)| l.contains("│  1.0 ")).unwrap();
    let label_end = line.find("│  1.0 ").unwrap() + "│  1.0 ".len();
    let x = line[..label_end].chars().count() + 2;
    // An SGR mouse press and release at (x, y), 1-based, as a terminal would send it.
    let click = format!("\x1b[<0;{};{}M\x1b[<0;{};{}m", x + 1, y + 1, x + 1, y + 1);
    t.keys(&["-l", &click]);
    t.wait_for("the clicked design (gap 1.00 cm)", |s| s.contains("d 1.00 cm"));

    // 5. s saves into $XDG_DATA_HOME/thud/designs; e exports into the current directory.
    t.keys(&["s"]);
    t.wait_for("the save line", |s| s.contains("save as: design-1"));
    t.keys(&["Enter"]);
    t.wait_for("the saved path", |s| s.contains("saved design-1 to"));
    assert!(t.dir.join("data/thud/designs/design-1.toml").is_file(), "saved in the XDG data dir");
    t.keys(&["e"]);
    t.wait_for("the export menu", |s| s.contains("sound WAV"));
    t.keys(&["Enter"]);
    t.wait_for("the exported file", |s| s.contains("exported waveform CSV to thud-waveform.csv"));
    assert!(t.dir.join("thud-waveform.csv").is_file());
    assert!(!t.dir.join("config").exists(), "the config is never written");

    // 6. q exits with status 0.
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0", "exit status");

    // 7. The terminal is sane afterwards.
    let stty = t.wait_file("stty");
    assert!(has_token(&stty, "icanon") && has_token(&stty, "echo"), "raw mode left on:\n{stty}");
    let s = t.wait_for("the shell after thud", |s| s.contains("AFTER-THUD"));
    assert!(!s.contains("parameters"), "alternate screen left behind:\n{s}");
    assert_eq!(t.format("#{alternate_on}"), "0", "alternate screen off");
    assert_eq!(t.format("#{cursor_flag}"), "1", "cursor shown");
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off");
}

#[test]
fn a_panic_restores_the_terminal_before_printing() {
    let bin = env!("CARGO_BIN_EXE_thud");
    let t = Tmux::start(
        |d| {
            format!(
                "THUD_TUI_PANIC_FOR_TEST=1 '{bin}' tui --mouse; echo $? > '{d}/status'; stty -a > '{d}/stty'; \
                 echo AFTER-THUD; exec sleep 60",
                d = d.display()
            )
        },
        100,
        30,
    );
    assert_ne!(t.wait_file("status").trim(), "0", "a panic exits non-zero");
    let stty = t.wait_file("stty");
    assert!(has_token(&stty, "icanon") && has_token(&stty, "echo"), "raw mode left on after a panic:\n{stty}");
    let s = t.wait_for("the shell after the panic", |s| s.contains("AFTER-THUD"));
    assert!(s.contains("panicking on purpose"), "the panic message is printed on the normal screen:\n{s}");
    assert_eq!(t.format("#{alternate_on}"), "0", "alternate screen off");
    assert_eq!(t.format("#{cursor_flag}"), "1", "cursor shown");
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off");
}

/// Starts the explorer with mouse capture in a pane, waits for its screen, sends `signal` to
/// its pid and checks that it exits with 128 + the signal number and leaves the terminal as it
/// found it: main screen, cursor visible, mouse reporting off, canonical mode and echo on.
fn a_signal_restores_the_terminal(signal: &str, number: i32) {
    let bin = env!("CARGO_BIN_EXE_thud");
    let t = Tmux::start(
        |d| {
            // The inner shell writes its pid and becomes thud (exec), so the pid is thud's. No
            // core file from the faults (SIGILL, SIGFPE, SIGSEGV).
            format!(
                "ulimit -c 0; cd '{d}' && sh -c 'echo $$ > pid; exec env XDG_CONFIG_HOME=\"{d}/config\" XDG_DATA_HOME=\"{d}/data\" \"{bin}\" tui --mouse'; \
                 echo $? > '{d}/status'; stty -a > '{d}/stty'; echo AFTER-THUD; exec sleep 60",
                d = d.display()
            )
        },
        100,
        30,
    );
    t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    assert_eq!(t.format("#{alternate_on}"), "1", "runs on the alternate screen");
    assert_eq!(t.format("#{mouse_any_flag}"), "1", "mouse reporting on");
    let pid = t.wait_file("pid");
    let sent = Command::new("kill").args([&format!("-{signal}"), pid.trim()]).status().unwrap();
    assert!(sent.success(), "kill -{signal} {pid}");
    assert_eq!(t.wait_file("status").trim(), (128 + number).to_string(), "exit status after SIG{signal}");
    let stty = t.wait_file("stty");
    assert!(has_token(&stty, "icanon") && has_token(&stty, "echo"), "raw mode left on after SIG{signal}:\n{stty}");
    t.wait_for("the shell after thud", |s| s.contains("AFTER-THUD"));
    assert_eq!(t.format("#{alternate_on}"), "0", "alternate screen off after SIG{signal}");
    assert_eq!(t.format("#{cursor_flag}"), "1", "cursor shown after SIG{signal}");
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off after SIG{signal}");
}

#[test]
fn sigterm_restores_the_terminal() {
    a_signal_restores_the_terminal("TERM", 15);
}

#[test]
fn sighup_restores_the_terminal() {
    a_signal_restores_the_terminal("HUP", 1);
}

#[test]
fn sigint_restores_the_terminal() {
    a_signal_restores_the_terminal("INT", 2);
}

/// Every other signal whose default action ends the process restores the terminal too, and
/// exits with 128 + its number (one test, one pane after another, to keep the time small).
#[test]
fn every_ending_signal_restores_the_terminal() {
    for (signal, number) in
        [("QUIT", 3), ("USR1", 10), ("USR2", 12), ("ALRM", 14), ("XCPU", 24), ("VTALRM", 26), ("PROF", 27)]
    {
        a_signal_restores_the_terminal(signal, number);
    }
}

/// SIGILL, SIGFPE and SIGSEGV, which no handler thread may catch, restore the terminal from
/// their handler (`thud_fatal`), and the process still dies by the signal: the shell reports
/// 128 + its number.
#[test]
fn fault_signals_restore_the_terminal() {
    for (signal, number) in [("ILL", 4), ("FPE", 8), ("SEGV", 11)] {
        a_signal_restores_the_terminal(signal, number);
    }
}

/// Under a pids limit the pool leaves room for the explorer's own threads: it runs with the
/// worker threads it got (one warning) and quits with 0. Root ignores RLIMIT_NPROC, so it runs
/// as a user with no other process, from a copy of the binary it can reach ([`Stranger`];
/// skipped, with the reason printed, where that is not possible).
#[test]
fn the_explorer_runs_under_a_pids_limit() {
    let Some(stranger) = Stranger::new(1) else { return };
    let (setpriv, bin) = (stranger.setpriv_line(), stranger.bin.display());
    let t = Tmux::start(
        |d| {
            format!(
                "{setpriv} bash -c \
                 'ulimit -u 14; HOME=/nonexistent RAYON_NUM_THREADS=8 exec \"{bin}\" tui' 2> '{d}/err'; \
                 echo $? > '{d}/status'; exec sleep 60",
                d = d.display()
            )
        },
        100,
        30,
    );
    t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0");
    let err = std::fs::read_to_string(t.dir.join("err")).unwrap();
    assert!(err.starts_with("thud: warning: only ") && err.lines().count() == 1, "{err}");
}

/// The explorer in a `w × h` pane with its own config and data folders, `args` after `tui`.
fn explorer(args: &str, w: u16, h: u16) -> Tmux {
    let bin = env!("CARGO_BIN_EXE_thud");
    Tmux::start(
        |d| {
            format!(
                "cd '{d}' && XDG_CONFIG_HOME='{d}/config' XDG_DATA_HOME='{d}/data' '{bin}' tui {args}; \
                 echo $? > '{d}/status'; echo AFTER-THUD; exec sleep 60",
                d = d.display()
            )
        },
        w,
        h,
    )
}

/// The zone number in the readout's zone row ("│zone   1 noisy, weak").
fn readout_zone(s: &str) -> Option<char> {
    let line = s.lines().find(|l| l.contains("│zone "))?;
    let rest = &line[line.find("│zone ")? + "│zone ".len()..];
    rest.trim_start().chars().next().filter(char::is_ascii_digit)
}

/// Every zone the chart's marker shows ("[n]" on the grid and on the line under it).
fn marker_zones(s: &str) -> Vec<char> {
    let c: Vec<char> = s.chars().collect();
    c.windows(3).filter(|w| w[0] == '[' && w[2] == ']').map(|w| w[1]).collect()
}

/// True when nothing is being computed: the readout has its zone and the chart is full.
fn settled(s: &str) -> bool {
    readout_zone(s).is_some() && !s.contains("filling chart") && !s.contains("computing") && !s.contains("[?]")
}

#[test]
fn at_80x24_pulse_and_polar_show_first_and_the_marker_shows_the_readouts_zone_at_80x24_and_200x60() {
    let t = explorer("", 80, 24);
    let s = t.wait_for("the pulse and the polar, computed", |s| {
        let top = s.lines().nth(1).unwrap_or("");
        top.contains("p(t)") && top.contains("SPL(θ)") && readout_zone(s).is_some()
    });
    assert!(s.contains("ms after the direct arrival") && s.contains("dB"), "{s}");
    assert!(s.lines().all(|l| l.chars().count() <= 80), "{s}");

    // Tab brings in the chart: its marker shows the readout's zone.
    t.keys(&["Tab", "Tab", "Tab"]);
    let s = t.wait_for("the chart at 80×24, settled", |s| s.contains("m (g)") && settled(s));
    let zone = readout_zone(&s).unwrap();
    let marks = marker_zones(&s);
    assert!(!marks.is_empty() && marks.iter().all(|z| *z == zone), "readout zone {zone}, marker {marks:?}:\n{s}");

    // 200×60: everything on screen, the same agreement.
    assert!(t.run(&["resize-window", "-x", "200", "-y", "60"]).status.success());
    let s = t.wait_for("the 200×60 layout, settled", |s| {
        s.lines().count() > 40 && s.contains("parameters") && s.contains("m (g)") && settled(s)
    });
    let zone = readout_zone(&s).unwrap();
    let marks = marker_zones(&s);
    assert!(!marks.is_empty() && marks.iter().all(|z| *z == zone), "readout zone {zone}, marker {marks:?}:\n{s}");

    // Typing 45 in the mass field is 45 g, as the field shows.
    t.keys(&["Enter"]);
    t.wait_for("the input line in g", |s| s.contains("plain number: g"));
    t.keys(&["-l", "45"]);
    t.keys(&["Enter"]);
    let s = t.wait_for("mass 45.00 g", |s| s.contains("m 45.00 g") && settled(s));
    let zone = readout_zone(&s).unwrap();
    assert!(marker_zones(&s).iter().all(|z| *z == zone), "{s}");
    // The design changed and is not saved: q asks once, y quits.
    t.keys(&["q"]);
    t.wait_for("the quit question", |s| s.contains("quit without saving? y/n"));
    t.keys(&["y"]);
    assert_eq!(t.wait_file("status").trim(), "0");
}

#[test]
fn the_tour_runs_through_every_step_and_leaves_to_the_explorer() {
    let n = thud::tui::tour::Tour::load(&thud::tui::tour::TourSource::BuiltIn).unwrap().steps.len();
    let t = explorer("--tour", 80, 24);
    t.wait_for("the tour's first step", |s| s.contains(&format!("tour 1/{n}:")) && s.contains("peaks +1.853"));
    let steps = thud::tui::tour::Tour::load(&thud::tui::tour::TourSource::BuiltIn).unwrap().steps;
    for i in 2..=n {
        t.keys(&["Right"]);
        t.wait_for(&format!("step {i}"), |s| s.contains(&format!("tour {i}/{n}:")));
        if steps[i - 1].animate {
            // The animation step: an impact flashes within 2 s of the step on screen.
            let shown = Instant::now();
            t.wait_for("an impact of the animation", |s| s.contains(" at the ") && s.contains("m/s, SPL"));
            let waited = shown.elapsed();
            eprintln!("tour step {i}: the first impact flashed {:.2} s after the step was seen", waited.as_secs_f64());
            assert!(waited < Duration::from_secs(2), "{waited:?} before an impact was seen");
        }
    }
    // The last step jumps to the best zone-3 design once its chart is in.
    // The step's chart fills the screen (zoomed): its marker shows the design's zone.
    t.wait_for("the best zone-3 design", |s| {
        !s.contains("filling chart") && !s.contains("computing") && !s.contains("[?]") && {
            let m = marker_zones(s);
            !m.is_empty() && m.iter().all(|z| *z == '3')
        }
    });
    t.keys(&["Right"]);
    let s = t.wait_for("the explorer after the tour", |s| s.contains("tour finished") && settled(s));
    assert!(!s.contains(&format!("tour {n}/{n}")), "the caption box is gone:\n{s}");
    assert!(s.lines().last().is_some_and(|l| l.contains("quit")), "the footer is back:\n{s}");
    // The last step found a zone-3 design; the explorer works from there.
    assert_eq!(readout_zone(&s), Some('3'), "{s}");
    let before = s.lines().next().unwrap_or("").to_string();
    // One → too many (the tour's "next") changes nothing and says what → does now.
    t.keys(&["Right"]);
    let s = t.wait_for("the word after the tour", |s| s.contains("the tour is over"));
    assert_eq!(s.lines().next().unwrap_or(""), before, "the design is as the tour left it");
    t.keys(&["Right"]);
    t.wait_for("a step of the mass", |s| s.lines().next().unwrap_or("") != before);
    t.keys(&["q"]);
    t.wait_for("the quit question", |s| s.contains("quit without saving? y/n"));
    t.keys(&["y"]);
    assert_eq!(t.wait_file("status").trim(), "0");
}

#[test]
fn under_term_xterm_the_real_binary_sends_no_256_colour_code() {
    let bin = env!("CARGO_BIN_EXE_thud");
    let t = Tmux::start(
        |d| {
            // A second's pause so the pipe below is attached before the first frame.
            format!(
                "sleep 1; cd '{d}' && env -u COLORTERM TERM=xterm XDG_CONFIG_HOME='{d}/config' \
                 XDG_DATA_HOME='{d}/data' '{bin}' tui; echo $? > '{d}/status'; exec sleep 60",
                d = d.display()
            )
        },
        120,
        40,
    );
    let wire = t.dir.join("wire");
    let out = t.run(&["pipe-pane", "-o", &format!("cat >> '{}'", wire.display())]);
    assert!(out.status.success(), "tmux pipe-pane: {}", String::from_utf8_lossy(&out.stderr));
    t.wait_for("the main screen with its chart", |s| s.contains("U0max") && !s.contains("filling chart"));
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0");
    let sent = String::from_utf8_lossy(&std::fs::read(&wire).unwrap()).into_owned();
    assert!(sent.contains("U0max"), "the pipe saw the frames ({} bytes)", sent.len());
    assert!(!sent.contains("38;5;") && !sent.contains("48;5;"), "a 256-colour code under TERM=xterm");
    assert!(sent.contains(";36m") && (sent.contains(";41m") || sent.contains(";41;")), "the classic colour codes");
}

/// A stray bracketed-paste start without its end marker (a pasted fragment, a
/// broken terminal, `printf '\e[200~'` into the pty) no longer swallows every key for good.
/// Within about a second the explorer drops the paste (its text, a `q` included, is not taken
/// as keys) and says so; then `q` quits and the terminal is restored.
#[test]
fn an_unterminated_bracketed_paste_times_out_and_q_quits() {
    let t = Tmux::explorer(100, 30);
    t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    t.keys(&["-l", "\x1b[200~abc q"]);
    let sent = Instant::now();
    let s = t.wait_for("the dropped paste", |s| s.contains("dropped a paste that never ended"));
    let took = sent.elapsed();
    assert!(took < Duration::from_secs(5), "the paste was dropped only after {took:?}:\n{s}");
    assert!(s.contains("(5 bytes)") && s.contains("parameters"), "the text was not replayed as keys:\n{s}");
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0", "exit status");
    let stty = t.wait_file("stty");
    assert!(has_token(&stty, "icanon") && has_token(&stty, "echo"), "raw mode left on:\n{stty}");
    t.wait_for("the shell after thud", |s| s.contains("AFTER-THUD"));
    assert_eq!(t.format("#{alternate_on}"), "0", "alternate screen off");
    assert_eq!(t.format("#{cursor_flag}"), "1", "cursor shown");
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off");
}

/// Waits for the explorer's main screen at `w × h`, resizes the window to `to`, waits for the
/// new layout, quits and returns the shell's screen.
fn resize_and_quit(from: (u16, u16), to: (u16, u16)) -> String {
    let t = explorer("", from.0, from.1);
    t.wait_for("the main screen, computed", |s| s.contains("parameters") && readout_zone(s).is_some());
    let (w, h) = (to.0.to_string(), to.1.to_string());
    assert!(t.run(&["resize-window", "-x", &w, "-y", &h]).status.success());
    let last = usize::from(to.1) - 1;
    t.wait_for("the new layout, computed", |s| {
        s.lines().nth(last).is_some_and(|l| l.contains("quit")) && s.contains("parameters") && settled(s)
    });
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0", "exit status");
    t.wait_for("the shell after thud", |s| s.contains("AFTER-THUD"))
}

/// After a resize and `q`, none of the explorer's text is left on the
/// shell's screen (tmux carried the alternate screen's rows beyond the old size over to the
/// main screen when it was left; the restore empties the alternate screen first).
#[test]
fn a_resize_then_quit_leaves_nothing_on_the_shell_screen() {
    for (from, to) in [((80, 24), (120, 40)), ((120, 40), (80, 24))] {
        let s = resize_and_quit(from, to);
        let left: Vec<&str> = s.lines().filter(|l| !l.trim().is_empty()).collect();
        assert_eq!(left, ["AFTER-THUD"], "{from:?} → {to:?}: the explorer's text stayed on the shell's screen:\n{s}");
    }
}

/// The mouse is on with no flag (the footer says `mouse on`, and a click on
/// a chart cell selects it); `--no-mouse` and the config's `mouse = false` turn it off.
#[test]
fn the_mouse_is_on_by_default_and_off_by_flag_or_config() {
    let t = explorer("", 80, 24);
    t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    assert_eq!(t.format("#{mouse_any_flag}"), "1", "mouse reporting on with no flag");
    t.wait_for("the footer's mouse hint at 80 columns", |s| s.lines().nth(23).is_some_and(|l| l.contains("mouse on")));
    // The bottom row of the chart (gap 1 cm), as in the test with --mouse above.
    t.keys(&["Tab", "Tab", "Tab"]);
    let s = t.wait_for("the chart's bottom row", |s| s.lines().any(|l| l.contains("│  1.0 ")));
    let (y, line) = s.lines().enumerate().find(|(_, l)| l.contains("│  1.0 ")).unwrap();
    let x = line[..line.find("│  1.0 ").unwrap() + "│  1.0 ".len()].chars().count() + 2;
    t.keys(&["-l", &format!("\x1b[<0;{};{}M\x1b[<0;{};{}m", x + 1, y + 1, x + 1, y + 1)]);
    t.wait_for("the clicked design (gap 1.00 cm)", |s| s.contains("d 1.00 cm"));
    drop(t);

    let t = explorer("--no-mouse", 120, 40);
    let s = t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off with --no-mouse");
    assert!(!s.lines().nth(39).unwrap_or("").contains("mouse"), "{s}");
    drop(t);

    let bin = env!("CARGO_BIN_EXE_thud");
    let t = Tmux::start(
        |d| {
            format!(
                "cd '{d}' && mkdir -p config/thud && echo 'mouse = false' > config/thud/config.toml && \
                 XDG_CONFIG_HOME='{d}/config' XDG_DATA_HOME='{d}/data' '{bin}' tui; exec sleep 60",
                d = d.display()
            )
        },
        120,
        40,
    );
    let s = t.wait_for("the main screen", |s| s.contains("parameters") && s.contains("U0max"));
    assert_eq!(t.format("#{mouse_any_flag}"), "0", "mouse reporting off with mouse = false in config.toml");
    assert!(!s.lines().nth(39).unwrap_or("").contains("mouse"), "{s}");
    assert!(!s.contains("warning"), "the key is known: {s}");
}

/// The picture of the animation at 80×24 (its left part, above the status lines).
fn anim_picture(s: &str) -> String {
    s.lines().skip(2).take(16).map(|l| l.chars().take(44).collect::<String>()).collect::<Vec<_>>().join("\n")
}

#[test]
fn a_plays_the_animation_the_first_impact_flashes_at_its_wall_and_space_pauses() {
    let t = explorer("", 80, 24);
    t.wait_for("the design computed", |s| readout_zone(s).is_some());
    let out = Command::new(env!("CARGO_BIN_EXE_thud")).args(["simulate", "--json"]).output().unwrap();
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let side = if json["impacts"][0]["wall"].as_i64().unwrap() > 0 { "upper wall" } else { "lower wall" };
    t.keys(&["a"]);
    // It opens at 1/10×: the first impact (10 ms into the run) flashes at the wall `thud
    // simulate --json` puts it on about 0.1 s later.
    let start = t.wait_for("the animation", |s| s.contains("speed 1/10×") && s.contains("playing"));
    t.wait_for("the first impact's flash", |s| s.contains(&format!("impact 1 at the {side}")));
    // Slowed to 1/1000× the ball's drawn position still moves.
    t.keys(&["Home", "[", "[", "[", "["]);
    let slow = t.wait_for("the slowest speed", |s| s.contains("speed 1/1000×"));
    std::thread::sleep(Duration::from_secs(3));
    let later = t.capture();
    assert_ne!(anim_picture(&slow), anim_picture(&later), "the ball moves:\n{start}\n{slow}\n{later}");
    // Space pauses: the screen stops changing.
    t.keys(&["Space"]);
    let paused = t.wait_for("paused", |s| s.contains("paused"));
    std::thread::sleep(Duration::from_secs(1));
    assert_eq!(t.capture(), paused, "paused, nothing changes");
    t.keys(&["q"]);
    assert_eq!(t.wait_file("status").trim(), "0");
}
