#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test or benchmark fails
//! The layering ARCHITECTURE.md describes, checked rather than kept by convention: the engine
//! crate depends on no UI, file or terminal crate, and no two modules of a crate import each
//! other, directly or round a circle (a module may use its own submodules and its parents).

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The crates whose modules are checked, as (name, source root).
const CRATES: [(&str, &str); 4] = [
    ("thud", "src"),
    ("thud-core", "crates/thud-core/src"),
    ("thud-render", "crates/thud-render/src"),
    ("thud-py", "crates/thud-py/src"),
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a source file (`tui/app.rs` → `["tui", "app"]`, `damper/mod.rs` →
/// `["damper"]`, `lib.rs` → `[]`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        parts.pop();
    }
    parts
}

/// The code of a file without its unit tests and comment lines.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]\nmod tests").next().unwrap_or_default();
    text.lines().filter(|l| !l.trim_start().starts_with("//")).collect::<Vec<_>>().join("\n")
}

/// Every path a file names through `crate::` or `super::`, resolved to absolute module
/// segments (`super::app::Panel` in `tui/tour.rs` → `["tui", "app", "Panel"]`).
fn named_paths(module: &[String], code: &str) -> Vec<Vec<String>> {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    let mut out = Vec::new();
    for (i, _) in code.match_indices("::") {
        let head_start = code[..i].rfind(|c: char| !ident(c)).map_or(0, |j| j + 1);
        let head = &code[head_start..i];
        if !(head == "crate" || head == "super") || code[..head_start].ends_with("::") {
            continue;
        }
        // `super` is the parent module (of x::y, in `x/y.rs` or `x/y/mod.rs`, it is x).
        let mut segs: Vec<String> =
            if head == "crate" { Vec::new() } else { module[..module.len().saturating_sub(1)].to_vec() };
        let mut rest = &code[i + 2..];
        loop {
            let end = rest.find(|c: char| !ident(c)).unwrap_or(rest.len());
            if end == 0 {
                break;
            }
            let seg = &rest[..end];
            if seg == "super" {
                segs.pop();
            } else {
                segs.push(seg.to_string());
            }
            if !rest[end..].starts_with("::") {
                break;
            }
            rest = &rest[end + 2..];
        }
        out.push(segs);
    }
    out
}

/// The module graph of a crate: each module and the modules of the same crate it imports
/// (not its own submodules or parents, which may use each other freely).
fn graph(src: &Path) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_of(src, f)).collect();
    let mut g = BTreeMap::new();
    for file in &files {
        let m = module_of(src, file);
        let text = fs::read_to_string(file).unwrap();
        let mut deps = BTreeSet::new();
        for path in named_paths(&m, &code(&text)) {
            // The longest module the path starts with.
            let Some(target) = (1..=path.len()).rev().map(|n| path[..n].to_vec()).find(|p| modules.contains(p)) else {
                continue;
            };
            let related = target.starts_with(&m) || m.starts_with(&target);
            if !related {
                deps.insert(target);
            }
        }
        g.insert(m, deps);
    }
    g
}

/// The circles of a graph: its strongly connected components with more than one module.
fn circles(g: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<String>> {
    let reach = |from: &Vec<String>| {
        let mut seen = BTreeSet::new();
        let mut stack = vec![from.clone()];
        while let Some(m) = stack.pop() {
            for d in g.get(&m).into_iter().flatten() {
                if seen.insert(d.clone()) {
                    stack.push(d.clone());
                }
            }
        }
        seen
    };
    let reachable: BTreeMap<_, _> = g.keys().map(|m| (m.clone(), reach(m))).collect();
    let mut out: Vec<Vec<String>> = Vec::new();
    for m in g.keys() {
        let circle: Vec<String> = g
            .keys()
            .filter(|n| *n == m || (reachable[m].contains(*n) && reachable[*n].contains(m)))
            .map(|n| n.join("::"))
            .collect();
        if circle.len() > 1 && !out.contains(&circle) {
            out.push(circle);
        }
    }
    out
}

#[test]
fn no_module_imports_another_that_imports_it_back() {
    for (name, src) in CRATES {
        let g = graph(&root().join(src));
        assert!(g.len() > 3, "{name}: found only {} modules under {src}", g.len());
        let found = circles(&g);
        assert!(found.is_empty(), "{name}: modules that import each other (directly or round a circle): {found:?}");
    }
}

#[test]
fn the_circle_check_finds_a_planted_circle() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    fs::create_dir(src.join("tui")).unwrap();
    fs::write(src.join("lib.rs"), "pub mod tui;\npub mod design;\n").unwrap();
    fs::write(src.join("design.rs"), "use crate::units::Kind;\n").unwrap();
    fs::write(src.join("units.rs"), "// use crate::design::Design; (a comment is no import)\n").unwrap();
    fs::write(src.join("tui/mod.rs"), "pub mod app;\npub mod tour;\nuse crate::design;\n").unwrap();
    fs::write(src.join("tui/app.rs"), "use super::tour::{Tour, TourSource};\n").unwrap();
    fs::write(src.join("tui/tour.rs"), "fn f() -> super::app::Panel { todo!() }\n").unwrap();
    assert_eq!(circles(&graph(src)), vec![vec!["tui::app".to_string(), "tui::tour".to_string()]]);
    fs::write(src.join("tui/tour.rs"), "use super::view::Panel;\n").unwrap();
    assert!(circles(&graph(src)).is_empty());
}

/// The explorer's app modules (`src/tui/app/`) in order: each calls methods of `App` defined in
/// itself or the modules before it, never after, so no two of them call each other.
const APP_LAYERS: [&str; 7] = ["state", "change", "screen", "guide", "files", "input", "update"];

/// The names of the functions a piece of code defines.
fn defined_fns(code: &str) -> BTreeSet<String> {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    code.match_indices("fn ")
        .filter(|(i, _)| *i == 0 || !code[..*i].ends_with(ident))
        .map(|(i, _)| code[i + 3..].chars().take_while(|c| ident(*c)).collect::<String>())
        .filter(|n| !n.is_empty())
        .collect()
}

/// The methods a piece of code calls on `self`.
fn self_calls(code: &str) -> BTreeSet<String> {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    code.match_indices("self.")
        .filter_map(|(i, _)| {
            let rest = &code[i + 5..];
            let end = rest.find(|c: char| !ident(c)).unwrap_or(rest.len());
            rest[end..].starts_with('(').then(|| rest[..end].to_string())
        })
        .collect()
}

/// The calls up of layered code, given as (module, code) in order: "M calls self.f() of N" for
/// each method `f` that M calls and only a later module N defines.
fn calls_up(layers: &[(&str, String)]) -> Vec<String> {
    let defs: Vec<BTreeSet<String>> = layers.iter().map(|(_, c)| defined_fns(c)).collect();
    let mut out = Vec::new();
    for (i, (module, code)) in layers.iter().enumerate() {
        for called in self_calls(code) {
            if defs[..=i].iter().any(|d| d.contains(&called)) {
                continue;
            }
            if let Some(j) = (i + 1..layers.len()).find(|&j| defs[j].contains(&called)) {
                out.push(format!("{module} calls self.{called}() of {}", layers[j].0));
            }
        }
    }
    out
}

#[test]
fn the_explorers_app_modules_call_only_the_ones_above_them() {
    let dir = root().join("src/tui/app");
    let mut files: Vec<String> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path().file_stem().unwrap().to_string_lossy().into_owned())
        .filter(|m| m != "mod")
        .collect();
    files.sort_unstable();
    let mut layers = APP_LAYERS.map(String::from).to_vec();
    layers.sort_unstable();
    assert_eq!(files, layers, "every module of src/tui/app has its place in APP_LAYERS");
    let layers: Vec<(&str, String)> =
        APP_LAYERS.iter().map(|m| (*m, code(&fs::read_to_string(dir.join(format!("{m}.rs"))).unwrap()))).collect();
    assert_eq!(calls_up(&layers), Vec::<String>::new());
    let mut all = Vec::new();
    rust_files(&root().join("src"), &mut all);
    for f in all.iter().filter(|f| !f.starts_with(&dir)) {
        let text = code(&fs::read_to_string(f).unwrap());
        assert!(!text.contains("impl App {"), "{} adds to App outside src/tui/app", f.display());
    }
}

#[test]
fn the_layer_check_finds_a_call_up() {
    let planted = [
        ("state", "fn busy(&self) -> bool { self.ready() && self.work().is_empty() }\nfn ready(&self) {}".to_string()),
        ("update", "fn work(&mut self) -> Vec<u8> { self.busy(); vec![] }".to_string()),
    ];
    assert_eq!(calls_up(&planted), vec!["state calls self.work() of update".to_string()]);
}

#[test]
fn the_engine_depends_on_no_ui_file_or_terminal_crate() {
    let manifest = fs::read_to_string(root().join("crates/thud-core/Cargo.toml")).unwrap();
    let deps: Vec<&str> = manifest
        .split("[dependencies]")
        .nth(1)
        .unwrap()
        .lines()
        .skip(1)
        .take_while(|l| !l.starts_with('['))
        .filter_map(|l| l.split('=').next().map(str::trim).filter(|n| !n.is_empty() && !n.starts_with('#')))
        .collect();
    assert!(deps.contains(&"nalgebra") && deps.contains(&"serde"), "{deps:?}");
    for ui in ["ratatui", "crossterm", "clap", "hound", "directories", "toml", "pyo3", "csv", "signal-hook"] {
        assert!(!deps.contains(&ui), "thud-core depends on {ui}: {deps:?}");
    }
}

/// The packages `name` depends on in Cargo.lock, directly or through others (every kind of
/// dependency: a superset of what `cargo tree -p name -e normal` lists).
fn locked_closure(name: &str) -> BTreeSet<String> {
    let lock = fs::read_to_string(root().join("Cargo.lock")).unwrap();
    let mut deps: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for block in lock.split("[[package]]").skip(1) {
        let field =
            |key: &str| block.lines().find_map(|l| l.strip_prefix(key)).map(|v| v.trim_matches('"').to_string());
        let Some(pkg) = field("name = ") else { continue };
        let list = block.split("dependencies = [").nth(1).and_then(|s| s.split(']').next()).unwrap_or("");
        let names = list
            .lines()
            .filter_map(|l| l.trim().trim_end_matches(',').trim_matches('"').split(' ').next().map(str::to_string))
            .filter(|n| !n.is_empty());
        deps.entry(pkg).or_default().extend(names);
    }
    let mut seen = BTreeSet::new();
    let mut todo = vec![name.to_string()];
    while let Some(p) = todo.pop() {
        for d in deps.get(&p).into_iter().flatten() {
            if seen.insert(d.clone()) {
                todo.push(d.clone());
            }
        }
    }
    seen
}

#[test]
fn the_python_module_builds_on_the_engine_alone() {
    let all = locked_closure("thud-py");
    assert!(all.contains("thud-core") && all.contains("thud-presets") && all.contains("pyo3"), "{all:?}");
    // `directories` is shared: the module finds a saved design by name (`design="NAME"`) in the
    // folder the command line saves it to.
    for app in ["thud", "ratatui", "crossterm", "clap", "clap_complete", "hound", "indicatif"] {
        assert!(!all.contains(app), "thud-py depends on {app}");
    }
    // The check sees the app's own crates: the app itself does depend on them.
    assert!(locked_closure("thud").contains("ratatui"));
}

#[test]
fn the_renderers_build_on_the_engine_alone() {
    let all = locked_closure("thud-render");
    assert!(all.contains("thud-core") && all.contains("svg2pdf"), "{all:?}");
    // Bytes from results: no app, no terminal, no command line, no progress bar, no Python.
    for ui in ["thud", "ratatui", "crossterm", "clap", "directories", "pyo3", "indicatif", "signal-hook"] {
        assert!(!all.contains(ui), "thud-render depends on {ui}");
    }
}

/// The places a file's text names a `Result` whose error is a bare `String` (`Result<T, String>`),
/// as `file:line`.
fn string_errors(file: &str, text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut rest = line;
        while let Some(at) = rest.find("Result<") {
            rest = &rest[at + "Result<".len()..];
            // The type arguments up to the matching `>`, nested generics included.
            let mut depth = 1;
            let end = rest.char_indices().find_map(|(j, c)| {
                match c {
                    '<' | '(' => depth += 1,
                    '>' | ')' => depth -= 1,
                    _ => {}
                }
                (depth == 0).then_some(j)
            });
            let args = &rest[..end.unwrap_or(rest.len())];
            if args.contains(',') && args.rsplit(',').next().is_some_and(|e| e.trim() == "String") {
                found.push(format!("{file}:{}", i + 1));
            }
        }
    }
    found
}

/// Typed errors end to end: no `Result<_, String>` in the app, the engine or the
/// Python module, tests included.
#[test]
fn no_result_has_a_bare_string_error() {
    let mut files = Vec::new();
    for dir in ["src", "crates"] {
        rust_files(&root().join(dir), &mut files);
    }
    let found: Vec<String> =
        files.iter().flat_map(|f| string_errors(&f.display().to_string(), &fs::read_to_string(f).unwrap())).collect();
    assert!(found.is_empty(), "Result<_, String> at {found:?}");
}

#[test]
fn the_string_error_check_finds_one() {
    let planted = "fn f() -> Result<Vec<(f64, usize)>, String> {\n    type R = Result<usize, JobError>;\n}";
    assert_eq!(string_errors("x.rs", planted), ["x.rs:1"]);
    assert!(string_errors("x.rs", "fn g() -> io::Result<String> {}").is_empty());
}
