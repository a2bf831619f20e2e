#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! The house's habits, checked rather than kept by convention: comments say the behaviour, not
//! a tracker's number (the repository has no tracker a reader could look it up in), and the
//! application's rooms stay small — a module over 800 lines or a function over 80 carries a
//! one-line reason at its top (`// Over 800 lines: …` among a module's first lines,
//! `// Over 80 lines: …` among the comment and attribute lines just above a function).

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

/// Whether the comment and attribute lines just above line `i` hold `reason`.
fn has_reason(lines: &[&str], i: usize, reason: &str) -> bool {
    lines[..i]
        .iter()
        .rev()
        .take_while(|l| {
            let t = l.trim_start();
            t.starts_with("//") || t.starts_with("#[")
        })
        .any(|l| l.trim_start().starts_with(reason))
}

#[test]
fn no_long_module_or_function_without_a_reason() {
    let root = root();
    let mut all = Vec::new();
    files(&root.join("src"), &[".rs"], &mut all);
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
                found.push(format!("{name}:{}: fn {fname} is {len} lines, no `{FN_REASON}…` line above it", i + 1));
            }
        }
    }
    assert!(found.is_empty(), "rooms over their size without a reason:\n{}", found.join("\n"));
}

#[test]
fn the_size_check_finds_a_long_function_and_reads_its_reason() {
    let body = vec!["    let x = 1;"; FN_MAX];
    let code = [vec!["/// Doc.", "fn long() {"], body.clone(), vec!["}", "fn short() {", "}"]].concat();
    assert_eq!(long_fns(&code, FN_MAX), vec![(1, "long".to_string(), FN_MAX + 2)]);
    assert!(!has_reason(&code, 1, FN_REASON));
    let reasoned = [vec!["/// Doc.", "// Over 80 lines: one table.", "#[must_use]", "pub fn long() {"], body].concat();
    assert!(has_reason(&reasoned, 3, FN_REASON));
}
