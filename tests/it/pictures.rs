//! The pictures of the README and the guide (`docs/guide/pictures/`), each made by thud: the
//! explorer's screens drawn from its own frame buffer, every other figure by the command the
//! guide's gallery prints beside it. The test makes them all again and fails when a committed
//! one differs, or when the gallery page, a chapter or the README no longer shows what it
//! should; `THUD_BLESS=1 cargo test --release --test it pictures` rewrites them in place.
//!
//! The figures it makes are also the ones the figure checks read (`figure_checks`): every figure
//! kind thud draws, the paper's included.

use crate::common::thud_within;
use crate::support::screen_svg::buffer_svg;
use crossterm::event::KeyCode;
use ratatui::backend::TestBackend;
use ratatui::Terminal;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Duration;
use thud::tui::app::App;
use thud::tui::compute::{Grid, Grids};
use thud::tui::{compute_sync, draw, Palette};

/// Where the pictures live (inside the book's source, so `mdbook build` copies them).
pub const DIR: &str = "docs/guide/pictures";

/// The largest a picture may be (bytes): pages stay light.
const MAX_BYTES: usize = 150_000;

/// One figure of the gallery: its file in [`DIR`], its heading, and the commands that make it,
/// run in turn in one empty folder; `made` is the file they write there.
pub struct Figure {
    pub file: &'static str,
    pub heading: &'static str,
    pub commands: &'static [&'static str],
    pub made: &'static str,
}

/// The command-line figures, in the gallery's order. Sizes are kept small (values, periods,
/// grids) so that each picture stays under [`MAX_BYTES`] and the whole set is made in seconds.
pub const FIGURES: &[Figure] = &[
    Figure {
        file: "waveform.svg",
        heading: "One impact's pressure pulse (the M)",
        commands: &["thud export svg waveform --preset paper-fig2 --u0 1.4 --out waveform.svg"],
        made: "waveform.svg",
    },
    Figure {
        file: "directivity.svg",
        heading: "Where the sound goes: SPL against the observer's angle",
        commands: &["thud export svg directivity --preset paper-fig2 --u0 1.4 --out directivity.svg"],
        made: "directivity.svg",
    },
    Figure {
        file: "history.svg",
        heading: "A damper's free decay, with and without the ball",
        commands: &["thud export svg history --preset paper-fig9 --out history.svg"],
        made: "history.svg",
    },
    Figure {
        file: "forced.svg",
        heading: "Under a harmonic force",
        commands: &["thud export svg history --v0 0 --force-amplitude 1N --freq 5.5Hz --duration 10 --out forced.svg"],
        made: "forced.svg",
    },
    Figure {
        file: "chart.svg",
        heading: "The design chart: zones over impact mass × gap",
        commands: &[
            "thud export svg chart --preset paper-table3 --masses 30g:100g:15 --gaps 2cm:5cm:13 --out chart.svg",
        ],
        made: "chart.svg",
    },
    Figure {
        file: "fig17.svg",
        heading: "Damping against loudness, the zones of Fig 17",
        commands: &[
            "thud export svg fig17 --preset paper-table3 --masses 30g:100g:15 --gaps 2cm:5cm:13 --out fig17.svg",
        ],
        made: "fig17.svg",
    },
    Figure {
        file: "response.svg",
        heading: "The frequency response, with the damper and without",
        commands: &["thud export svg response --preset paper-table3 --mass 60g --gap 2.5cm --force-amplitude 1N \
                     --freqs 4.6Hz:5.6Hz:11 --out response.svg"],
        made: "response.svg",
    },
    Figure {
        file: "restitution.svg",
        heading: "Restitution against impact mass",
        commands: &["thud export svg restitution --out restitution.svg"],
        made: "restitution.svg",
    },
    Figure {
        file: "ensemble.svg",
        heading: "An ensemble chart: how much the ball's start matters in each cell",
        commands: &[
            "thud sweep --preset paper-table3 --masses 30g:100g:8 --gaps 2cm:5cm:6 --ensemble 4 --svg ensemble.svg",
        ],
        made: "ensemble.svg",
    },
    Figure {
        file: "study-1d.svg",
        heading: "A study over one parameter: each metric against the strike speed",
        commands: &["thud sweep --vary v0=0.5:3:11 --svg study-1d.svg"],
        made: "study-1d.svg",
    },
    Figure {
        file: "study-2d.svg",
        heading: "A study over two parameters: a heat map of each metric",
        commands: &["thud sweep --vary v0=1:3:9 --vary c1=10:60:6 --svg study-2d.svg"],
        made: "study-2d.svg",
    },
    Figure {
        file: "bifurcation.svg",
        heading: "A bifurcation diagram over the forcing frequency",
        commands: &["thud bifurcation --preset forced-rattle --vary f=6.5Hz:8Hz:30 --periods 16 --svg bifurcation.svg"],
        made: "bifurcation.svg",
    },
    Figure {
        file: "continue.svg",
        heading: "Periodic orbits continued over the forcing frequency, stable and unstable",
        commands: &["thud continue --preset forced-rattle --vary f=6Hz:8Hz:5 --svg continue.svg"],
        made: "continue.svg",
    },
    Figure {
        file: "branches.svg",
        heading: "The continued branches over the bifurcation diagram",
        commands: &[
            "thud bifurcation --preset forced-rattle --vary f=6.5Hz:8Hz:30 --periods 8 --branches 5 --svg branches.svg",
        ],
        made: "branches.svg",
    },
    Figure {
        file: "impact-map.svg",
        heading: "The impact map of a chaotic orbit",
        commands: &["thud impact-map --preset forced-rattle --freq 7.4Hz --periods 60 --svg impact-map.svg"],
        made: "impact-map.svg",
    },
    Figure {
        file: "basins.svg",
        heading: "Basins of attraction: which ball start ends on which orbit",
        commands: &["thud basins --preset forced-rattle --freq 7.5Hz --grid 12 --svg basins.svg"],
        made: "basins.svg",
    },
    Figure {
        file: "fit.svg",
        heading: "A damper fitted to a measured decay",
        commands: &[
            "thud simulate --c1 40 --csv --samples 2001 > sim.csv",
            "thud export svg fit --damper --data sim.csv --out fit.svg",
        ],
        made: "fit.svg",
    },
    Figure {
        file: "paper-fig2.svg",
        heading: "The paper's Fig 2 (of `thud paper all`)",
        commands: &["thud paper all --out paper"],
        made: "paper/fig2.svg",
    },
    Figure {
        file: "paper-fig11.svg",
        heading: "The paper's Fig 11: SPLmax against impact mass and gap",
        commands: &["thud paper all --out paper"],
        made: "paper/fig11.svg",
    },
    Figure {
        file: "paper-fig15.svg",
        heading: "The paper's Fig 15: damping over the mass × gap plane",
        commands: &["thud paper all --out paper"],
        made: "paper/fig15.svg",
    },
    Figure {
        file: "paper-table1.svg",
        heading: "The paper's Table 1: both models beside the measurements",
        commands: &["thud paper all --out paper"],
        made: "paper/table1.svg",
    },
];

/// The explorer's screens: (file, heading, preset, keys pressed, width, height).
pub const SCREENS: &[(&str, &str, &str, &str, u16, u16)] = &[
    ("explorer.svg", "The explorer (`thud`), 120 × 40", "default", "", 120, 40),
    ("tour.svg", "The guided tour's first step (`thud tui --tour`), 100 × 30", "default", "T", 100, 30),
];

/// Which pictures each page must show (by file name).
const SHOWN: &[(&str, &[&str])] = &[
    ("README.md", &["explorer.svg", "chart.svg", "response.svg", "tour.svg"]),
    ("docs/guide/getting-started.md", &["explorer.svg"]),
    ("docs/guide/the-explorer.md", &["explorer.svg", "tour.svg"]),
    ("docs/guide/commands/pulse.md", &["waveform.svg", "directivity.svg"]),
    ("docs/guide/commands/simulate.md", &["history.svg"]),
    ("docs/guide/commands/forced.md", &["forced.svg"]),
    ("docs/guide/commands/response.md", &["response.svg"]),
    ("docs/guide/commands/sweep.md", &["chart.svg", "fig17.svg", "ensemble.svg", "study-1d.svg", "study-2d.svg"]),
    ("docs/guide/commands/restitution.md", &["restitution.svg"]),
    ("docs/guide/commands/paper.md", &["paper-fig2.svg", "paper-fig11.svg"]),
    ("docs/guide/commands/export.md", &["waveform.svg"]),
    ("docs/guide/dynamics.md", &["bifurcation.svg", "continue.svg", "branches.svg", "impact-map.svg", "basins.svg"]),
    ("docs/guide/fit.md", &["fit.svg"]),
    ("docs/guide/physical-model.md", &["paper-table1.svg"]),
];

/// The gallery page; its figures sit between these markers, written by this test.
const GALLERY: &str = "docs/guide/gallery.md";
const GALLERY_OPEN: &str = "<!-- gallery: THUD_BLESS=1 cargo test --release --test it pictures -->\n";
const GALLERY_CLOSE: &str = "<!-- /gallery -->";

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(path)
}

/// The explorer on `preset` with every result computed on this thread, as it looks once the
/// worker is done (the full 16 × 12 chart), after `keys`, drawn at `w` × `h`.
fn screen(preset: &str, keys: &str, w: u16, h: u16, title: &str) -> String {
    let d = thud::presets::preset(preset).unwrap();
    let grids = Grids { coarse: None, fine: Grid::standard(16, 12) };
    let mut app = App::with_grids(d, preset, Palette::default(), grids);
    app.mouse = true;
    let reqs = app.initial_requests();
    compute_sync(&mut app, reqs);
    for c in keys.chars() {
        crate::support::explorer::press(&mut app, KeyCode::Char(c));
    }
    let mut term = Terminal::new(TestBackend::new(w, h)).unwrap();
    draw(&mut term, &mut app).unwrap();
    buffer_svg(term.backend().buffer(), title)
}

/// Runs `commands` (each starting `thud `, its output sent to a file by a last `> FILE`) in
/// turn in the empty folder `dir`.
fn run(dir: &Path, commands: &[&str]) {
    std::fs::create_dir_all(dir).unwrap();
    for command in commands {
        let (command, to) = command.split_once(" > ").map_or((*command, None), |(c, f)| (c, Some(f)));
        let args: Vec<&str> = command.split_whitespace().skip(1).collect();
        let ran = thud_within(dir, &args, Duration::from_secs(120));
        assert_eq!(ran.code, 0, "{command}: {}", ran.stderr);
        if let Some(file) = to {
            std::fs::write(dir.join(file.trim()), ran.stdout).unwrap();
        }
    }
}

/// Every picture, made once for the tests of this binary that read them.
pub struct Made {
    /// The pictures of [`DIR`]: file name → contents.
    pub pictures: BTreeMap<String, String>,
    /// Every SVG figure the commands wrote (the paper's all, not only those shown): the
    /// folder's name and the file's → contents.
    pub figures: BTreeMap<String, String>,
}

/// The pictures and figures, made on first use (a few seconds; the tests share them).
pub fn made() -> &'static Made {
    static MADE: std::sync::OnceLock<Made> = std::sync::OnceLock::new();
    MADE.get_or_init(|| {
        let work = tempfile::tempdir().unwrap();
        let (pictures, dirs) = make_all(work.path());
        let mut figures = BTreeMap::new();
        for dir in dirs.values() {
            for sub in [dir.clone(), dir.join("paper")] {
                let Ok(entries) = std::fs::read_dir(&sub) else { continue };
                for e in entries {
                    let p = e.unwrap().path();
                    if p.extension().is_some_and(|x| x == "svg") {
                        let name = p.strip_prefix(work.path()).unwrap().to_string_lossy().into_owned();
                        figures.insert(name, std::fs::read_to_string(&p).unwrap());
                    }
                }
            }
        }
        Made { pictures, figures }
    })
}

/// Every picture made afresh in `work`: file name → contents, and the folder of each figure's
/// own run.
fn make_all(work: &Path) -> (BTreeMap<String, String>, BTreeMap<String, PathBuf>) {
    let mut folders: BTreeMap<&[&str], PathBuf> = BTreeMap::new();
    for f in FIGURES {
        let n = folders.len();
        folders.entry(f.commands).or_insert_with(|| work.join(format!("run{n}")));
    }
    std::thread::scope(|s| {
        for (commands, dir) in &folders {
            s.spawn(move || run(dir, commands));
        }
    });
    let mut out = BTreeMap::new();
    for f in FIGURES {
        let path = folders[f.commands].join(f.made);
        out.insert(f.file.to_string(), std::fs::read_to_string(&path).unwrap());
    }
    for (file, heading, preset, keys, w, h) in SCREENS {
        out.insert((*file).to_string(), screen(preset, keys, *w, *h, heading));
    }
    let dirs = FIGURES.iter().map(|f| (f.file.to_string(), folders[f.commands].clone())).collect();
    (out, dirs)
}

/// The gallery's generated part: each figure under its heading with the commands that made it.
fn gallery_body() -> String {
    let mut s = String::new();
    for (file, heading, ..) in SCREENS {
        s += &format!("## {heading}\n\n![{heading}](pictures/{file})\n\n");
    }
    for f in FIGURES {
        s += &format!(
            "## {}\n\n```sh\n{}\n```\n\n![{}](pictures/{})\n\n",
            f.heading,
            f.commands.join("\n"),
            f.heading,
            f.file
        );
    }
    s
}

fn bless() -> bool {
    std::env::var_os("THUD_BLESS").is_some()
}

/// Writes `contents` to `path` whole (a temporary file renamed over it).
fn write(path: &Path, contents: &str) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut tmp = tempfile::NamedTempFile::new_in(path.parent().unwrap()).unwrap();
    std::io::Write::write_all(&mut tmp, contents.as_bytes()).unwrap();
    tmp.persist(path).unwrap();
}

#[test]
fn pictures_are_what_thud_draws_today_and_every_page_shows_its_own() {
    let made = &made().pictures;
    let dir = repo(DIR);
    for (file, contents) in made {
        assert!(contents.len() <= MAX_BYTES, "{file} is {} bytes, over {MAX_BYTES}", contents.len());
        roxmltree::Document::parse(contents).unwrap_or_else(|e| panic!("{file}: {e}"));
        let path = dir.join(file);
        if bless() {
            if std::fs::read_to_string(&path).ok().as_ref() != Some(contents) {
                write(&path, contents);
            }
        } else {
            let committed = std::fs::read_to_string(&path).unwrap_or_default();
            assert!(
                committed == *contents,
                "{DIR}/{file} is not what thud draws today; remake it with \
                 THUD_BLESS=1 cargo test --release --test it pictures"
            );
        }
    }
    // No picture in the folder that nothing makes.
    let mut kept: Vec<String> =
        std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    kept.sort();
    let want: Vec<String> = made.keys().cloned().collect();
    assert_eq!(kept, want, "the pictures in {DIR}");

    // The gallery shows every one, with its commands.
    let path = repo(GALLERY);
    let page = std::fs::read_to_string(&path).unwrap();
    let open = page.find(GALLERY_OPEN).expect("the gallery's opening marker") + GALLERY_OPEN.len();
    let close = page.find(GALLERY_CLOSE).expect("the gallery's closing marker");
    let body = gallery_body();
    if bless() {
        if page[open..close] != body {
            write(&path, &format!("{}{body}{}", &page[..open], &page[close..]));
        }
    } else {
        assert!(
            page[open..close] == body,
            "{GALLERY} does not show the pictures as made; rewrite it with \
             THUD_BLESS=1 cargo test --release --test it pictures"
        );
    }
    let summary = std::fs::read_to_string(repo("docs/guide/SUMMARY.md")).unwrap();
    assert!(summary.contains("(gallery.md)"), "the gallery is in the book's SUMMARY.md");

    // Each page shows its pictures, and no page points at a picture that is not made.
    for (page, files) in SHOWN {
        let text = std::fs::read_to_string(repo(page)).unwrap();
        for file in *files {
            assert!(text.contains(&format!("pictures/{file})")), "{page} does not show {file}");
        }
    }
    for entry in walk(&repo("docs/guide")).into_iter().chain([repo("README.md")]) {
        let text = std::fs::read_to_string(&entry).unwrap();
        for (i, _) in text.match_indices("pictures/") {
            let name: String = text[i + "pictures/".len()..].chars().take_while(|c| *c != ')' && *c != '"').collect();
            assert!(made.contains_key(&name), "{} shows pictures/{name}, which nothing makes", entry.display());
        }
    }
}

/// The Markdown pages under `dir`.
fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut out = vec![];
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(walk(&p));
        } else if p.extension().is_some_and(|x| x == "md") {
            out.push(p);
        }
    }
    out
}
