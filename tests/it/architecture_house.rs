#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The house's habits, checked rather than kept by convention: comments say the behaviour, not
//! a tracker's number (the repository has no tracker a reader could look it up in), and every
//! crate's rooms stay small — a module over 800 lines or a function over 80 carries a one-line
//! reason at its top (`// Over 800 lines: …` among a module's first lines, `// Over 80 lines: …`
//! among the comment and attribute lines just above a function or the comment lines that open
//! its body). The same walk counts the house's figures that ARCHITECTURE.md shows
//! ([`house_figures`]).

use std::fs;
use std::path::{Path, PathBuf};

const MODULE_MAX: usize = 800;
const FN_MAX: usize = 80;
const MODULE_REASON: &str = "// Over 800 lines: ";
const FN_REASON: &str = "// Over 80 lines: ";

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every file under `dir` whose name ends in one of `exts`, build and tool folders left out.
fn files(dir: &Path, exts: &[&str], out: &mut Vec<PathBuf>) {
    let Ok(entries) = fs::read_dir(dir) else { return };
    for entry in entries {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if !(name == "target" || name.starts_with('.') || name == "__pycache__" || name == "node_modules") {
                files(&path, exts, out);
            }
        } else if exts.iter().any(|e| name.ends_with(e)) {
            out.push(path);
        }
    }
}

/// The comment text of a line of source: after `//` in Rust, after `#` in Python (a
/// docstring line counts whole), the whole line in Markdown.
fn comment(ext: &str, line: &str) -> Option<String> {
    match ext {
        "md" => Some(line.to_string()),
        "rs" => line.find("//").map(|i| line[i..].to_string()),
        _ => Some(line.to_string()),
    }
}

/// Whether `text` names a tracker's number: the word for a tracker's entry (singular or
/// plural) then a number, with or without a hash, or a bare hash and up to four digits (a
/// hex colour such as `#000000` is not one). The planted cases are in the test below.
fn names_an_issue(text: &str) -> bool {
    let lower = text.to_lowercase();
    let b = lower.as_bytes();
    let word = ["iss", "ue"].concat();
    for (i, _) in lower.match_indices(&word) {
        if i > 0 && b[i - 1].is_ascii_alphanumeric() {
            continue;
        }
        let mut j = i + word.len();
        if b.get(j) == Some(&b's') {
            j += 1;
        }
        if b.get(j) != Some(&b' ') {
            continue;
        }
        j += 1;
        if b.get(j) == Some(&b'#') {
            j += 1;
        }
        if b.get(j).is_some_and(u8::is_ascii_digit) {
            return true;
        }
    }
    for (i, _) in lower.match_indices('#') {
        let before_ok = i == 0 || matches!(b[i - 1], b' ' | b'(' | b'\t');
        let run: String = lower[i + 1..].chars().take_while(char::is_ascii_alphanumeric).collect();
        if before_ok && !run.is_empty() && run.len() <= 4 && run.chars().all(|c| c.is_ascii_digit()) {
            return true;
        }
    }
    false
}

#[test]
fn no_comment_names_an_issue_number() {
    let root = root();
    let mut all = Vec::new();
    for dir in ["src", "tests", "docs", "benches", "examples", "crates/thud-py"] {
        files(&root.join(dir), &[".rs", ".md", ".py", ".pyi"], &mut all);
    }
    assert!(all.len() > 100, "the walk found the sources: {}", all.len());
    let mut found = Vec::new();
    for f in &all {
        let ext = f.extension().unwrap().to_string_lossy().into_owned();
        let text = fs::read_to_string(f).unwrap();
        for (n, line) in text.lines().enumerate() {
            if comment(&ext, line).is_some_and(|c| names_an_issue(&c)) {
                found.push(format!("{}:{}: {}", f.strip_prefix(&root).unwrap().display(), n + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "comments that name an issue number instead of the behaviour:\n{}", found.join("\n"));
}

#[test]
fn the_issue_check_finds_one() {
    let i = ["Iss", "ue"].concat();
    for planted in [
        format!("// the readout ({} 27, item 4)", i.to_lowercase()),
        format!("/// {i} 17 item 5: the marker"),
        format!("(item 4 of {} 19)", i.to_lowercase()),
        format!("{}s 26 and 27", i.to_lowercase()),
        format!("see {} #12", i.to_lowercase()),
        "fixed in #12".to_string(),
    ] {
        assert!(names_an_issue(&planted), "{planted}");
    }
    for fine in ["the issue is the gap", "colour #000000 and #1f77b4", "Table 1 (dB)", "§11", "a#1"] {
        assert!(!names_an_issue(fine), "{fine}");
    }
}

/// The functions of `lines` longer than `max` lines: (first line index, name, length). A
/// function runs from its `fn` line to the first line that closes it at its own indent.
fn long_fns(lines: &[&str], max: usize) -> Vec<(usize, String, usize)> {
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let t = line.trim_start();
        let indent = &line[..line.len() - t.len()];
        let mut rest = t;
        for prefix in ["pub(crate) ", "pub(super) ", "pub ", "const ", "async ", "unsafe ", "extern \"C\" "] {
            rest = rest.strip_prefix(prefix).unwrap_or(rest);
        }
        let Some(sig) = rest.strip_prefix("fn ") else { continue };
        let name: String = sig.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        // The signature's end: a body opened, or a declaration without one.
        let Some(open) = (i..lines.len()).find(|&j| {
            let l = lines[j].trim_end();
            l.ends_with('{') || l.ends_with(';') || l.ends_with('}')
        }) else {
            continue;
        };
        if !lines[open].trim_end().ends_with('{') {
            continue;
        }
        let close = format!("{indent}}}");
        let Some(end) = (open + 1..lines.len()).find(|&j| lines[j] == close) else { continue };
        let len = end - i + 1;
        if len > max {
            out.push((i, name, len));
        }
    }
    out
}

/// Whether the comment and attribute lines just above line `i` (a function's `fn` line), or the
/// comment lines that open its body, hold `reason`.
fn has_reason(lines: &[&str], i: usize, reason: &str) -> bool {
    let is_comment = |l: &&&str| l.trim_start().starts_with("//");
    let above = lines[..i].iter().rev().take_while(|l| is_comment(l) || l.trim_start().starts_with("#["));
    let open = (i..lines.len()).find(|&j| lines[j].trim_end().ends_with('{')).unwrap_or(lines.len() - 1);
    let opening = lines[open + 1..].iter().take_while(is_comment);
    above.chain(opening).any(|l| l.trim_start().starts_with(reason))
}

/// The house's areas as ARCHITECTURE.md counts them: a name and the source folders it holds.
const AREAS: [(&str, &[&str]); 5] = [
    ("engine", &["crates/thud-core/src"]),
    ("app", &["src"]),
    ("renderers", &["crates/thud-render/src"]),
    ("Python module", &["crates/thud-py/src"]),
    ("presets, fatal", &["crates/thud-presets/src", "crates/thud-fatal/src"]),
];

/// The inline test modules of `lines`: from a `#[cfg(test)]` line followed by `mod NAME {` to
/// the brace that closes it at its indent (line indices).
fn test_modules(lines: &[&str]) -> Vec<std::ops::Range<usize>> {
    let mut out = Vec::new();
    let mut i = 0;
    while i + 1 < lines.len() {
        let next = lines[i + 1];
        let t = next.trim_start();
        let indent = &next[..next.len() - t.len()];
        let opens = t.strip_prefix("pub(crate) ").unwrap_or(t).starts_with("mod ") && t.ends_with(" {");
        if lines[i].trim() == "#[cfg(test)]" && opens {
            let close = format!("{indent}}}");
            let end = (i + 2..lines.len()).find(|&j| lines[j] == close).unwrap_or(lines.len() - 1);
            out.push(i..end + 1);
            i = end + 1;
        } else {
            i += 1;
        }
    }
    out
}

/// The files of `all` that are test modules of their own: `tests.rs`, or a module its parent
/// declares under `#[cfg(test)]` (`#[cfg(test)] mod scheme_checks;`).
fn test_files(all: &[PathBuf]) -> Vec<PathBuf> {
    let mut out: Vec<PathBuf> =
        all.iter().filter(|f| f.file_name().is_some_and(|n| n == "tests.rs")).cloned().collect();
    for f in all {
        let text = fs::read_to_string(f).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let stem = f.file_stem().unwrap().to_string_lossy().into_owned();
        let dir = f.parent().unwrap();
        let dir = if ["mod", "lib", "main"].contains(&stem.as_str()) { dir.to_path_buf() } else { dir.join(&stem) };
        for w in lines.windows(2) {
            let decl = w[1].trim().strip_prefix("pub(crate) ").unwrap_or(w[1].trim());
            if let (true, Some(name)) =
                (w[0].trim() == "#[cfg(test)]", decl.strip_prefix("mod ").and_then(|d| d.strip_suffix(';')))
            {
                out.push(dir.join(format!("{name}.rs")));
                out.push(dir.join(name).join("mod.rs"));
            }
        }
    }
    out
}

/// One area's figures: production lines (test modules and test files left out), the modules
/// over [`MODULE_MAX`] lines and the functions over [`FN_MAX`] outside tests, each as
/// `(name, lines, has its reason)`.
struct Figures {
    lines: usize,
    modules: Vec<(String, usize, bool)>,
    functions: Vec<(String, usize, bool)>,
}

fn figures(root: &Path, dirs: &[&str]) -> Figures {
    let mut fig = Figures { lines: 0, modules: Vec::new(), functions: Vec::new() };
    for dir in dirs {
        let mut all = Vec::new();
        files(&root.join(dir), &[".rs"], &mut all);
        all.sort();
        let tests = test_files(&all);
        for f in all.iter().filter(|f| !tests.contains(f)) {
            let text = fs::read_to_string(f).unwrap();
            let lines: Vec<&str> = text.lines().collect();
            let module = f.strip_prefix(root.join(dir)).unwrap().with_extension("").display().to_string();
            let tests = test_modules(&lines);
            fig.lines += lines.len() - tests.iter().map(ExactSizeIterator::len).sum::<usize>();
            if lines.len() > MODULE_MAX {
                let reason = lines.iter().take(5).any(|l| l.starts_with(MODULE_REASON));
                fig.modules.push((format!("{module}.rs"), lines.len(), reason));
            }
            let module = module.trim_end_matches("/mod").replace('/', "::");
            for (i, fname, len) in long_fns(&lines, FN_MAX) {
                if !tests.iter().any(|r| r.contains(&i)) {
                    fig.functions.push((format!("{module}::{fname}"), len, has_reason(&lines, i, FN_REASON)));
                }
            }
        }
    }
    fig
}

/// Every crate's long modules and functions, tests included, say why (see the module's doc).
#[test]
fn no_long_module_or_function_without_a_reason() {
    let root = root();
    let mut all = Vec::new();
    for (_, dirs) in AREAS {
        for dir in dirs {
            files(&root.join(dir), &[".rs"], &mut all);
        }
    }
    assert!(all.len() > 100, "the walk found the sources: {}", all.len());
    let mut found = Vec::new();
    for f in &all {
        let text = fs::read_to_string(f).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let name = f.strip_prefix(&root).unwrap().display().to_string();
        if lines.len() > MODULE_MAX && !lines.iter().take(5).any(|l| l.starts_with(MODULE_REASON)) {
            found.push(format!("{name}: {} lines, no `{MODULE_REASON}…` line at its top", lines.len()));
        }
        for (i, fname, len) in long_fns(&lines, FN_MAX) {
            if !has_reason(&lines, i, FN_REASON) {
                found.push(format!("{name}:{}: fn {fname} is {len} lines, no `{FN_REASON}…` line at its top", i + 1));
            }
        }
    }
    assert!(found.is_empty(), "rooms over their size without a reason:\n{}", found.join("\n"));
}

/// The house's figures as ARCHITECTURE.md's table shows them, printed as its rows:
/// `cargo test --release --test it architecture_house::house_figures -- --nocapture`. Each area
/// is found and holds code, and every long room it lists carries its reason.
#[test]
fn house_figures() {
    let root = root();
    let thousands = |n: usize| {
        let s = n.to_string();
        let mut out = String::new();
        for (k, c) in s.chars().enumerate() {
            if k > 0 && (s.len() - k).is_multiple_of(3) {
                out.push(',');
            }
            out.push(c);
        }
        out
    };
    let list = |rooms: &[(String, usize, bool)]| {
        let names: Vec<String> = rooms.iter().map(|(n, len, _)| format!("`{n}` ({len})")).collect();
        if names.is_empty() {
            "0".to_string()
        } else {
            format!("{}: {}", names.len(), names.join(", "))
        }
    };
    println!("| area | production lines | modules over {MODULE_MAX} | functions over {FN_MAX} |");
    println!("|---|---:|---|---|");
    for (area, dirs) in AREAS {
        let fig = figures(&root, dirs);
        assert!(fig.lines > 0, "{area}: no source found under {dirs:?}");
        let unexplained: Vec<&String> =
            fig.modules.iter().chain(&fig.functions).filter(|(_, _, why)| !why).map(|(n, _, _)| n).collect();
        assert!(unexplained.is_empty(), "{area}: long rooms without a reason: {unexplained:?}");
        let folders: Vec<String> = dirs.iter().map(|d| format!("`{d}`")).collect();
        println!(
            "| {area} ({}) | {} | {} | {} |",
            folders.join(", "),
            thousands(fig.lines),
            list(&fig.modules),
            list(&fig.functions)
        );
    }
}

#[test]
fn the_size_check_finds_a_long_function_and_reads_its_reason() {
    let body = vec!["    let x = 1;"; FN_MAX];
    let code = [vec!["/// Doc.", "fn long() {"], body.clone(), vec!["}", "fn short() {", "}"]].concat();
    assert_eq!(long_fns(&code, FN_MAX), vec![(1, "long".to_string(), FN_MAX + 2)]);
    assert!(!has_reason(&code, 1, FN_REASON));
    let reasoned =
        [vec!["/// Doc.", "// Over 80 lines: one table.", "#[must_use]", "pub fn long() {"], body.clone()].concat();
    assert!(has_reason(&reasoned, 3, FN_REASON));
    let in_body = [vec!["fn long(", "    x: u8,", ") {", "    // Over 80 lines: one table."], body.clone()].concat();
    assert!(has_reason(&in_body, 0, FN_REASON));
    let later = [vec!["fn long() {", "    let y = 0;", "    // Over 80 lines: one table."], body].concat();
    assert!(!has_reason(&later, 0, FN_REASON), "a reason further down the body is not at its top");
}

#[test]
fn the_count_leaves_out_test_modules_and_test_files() {
    let code = ["fn a() {}", "#[cfg(test)]", "mod tests {", "    fn t() {", "    }", "}", "fn b() {}"];
    assert_eq!(test_modules(&code), vec![1..6]);
    let root = root();
    let all = [root.join("crates/thud-core/src/damper/mod.rs"), root.join("crates/thud-core/src/damper/stepper.rs")];
    let tests = test_files(&all);
    assert!(tests.contains(&root.join("crates/thud-core/src/damper/scheme_checks.rs")), "{tests:?}");
    assert!(!tests.contains(&root.join("crates/thud-core/src/damper/stepper.rs")));
}
