#![allow(clippy::unwrap_used, clippy::expect_used)] // a panic is how a test fails
//! Documentation that cannot drift.
//!
//! - Every ```console session of the README and of the guide (docs/guide/**/*.md) is run by
//!   trycmd and its output compared (stdout and stderr together, `? CODE` for an exit status,
//!   `...` for lines left out, `[..]` for part of a line). `TRYCMD=overwrite cargo test --release
//!   --test it docs` writes the real output back into the pages (then restore any `...` by hand).
//! - The guide's range table (docs/guide/limits.md) is generated from the engine's table
//!   (`thud_core::limits`, what `thud limits` prints); `THUD_BLESS=1` regenerates it.
//! - The README stays a front door: at most 200 lines, prose within 100 columns, its lecture is
//!   the example tour file and loads, and every page of the guide is in the book's contents.
//! - `thud man --install` puts the pages where `man` finds them for the `thud` on `PATH`.

use std::path::{Path, PathBuf};

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(name: &str) -> String {
    std::fs::read_to_string(repo().join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Every Markdown page of the guide, relative to the repository (SUMMARY.md included).
fn guide_pages() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path.strip_prefix(repo()).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(&repo().join("docs/guide"), &mut out);
    out.sort();
    out
}

#[test]
fn console_sessions_run_as_written() {
    // The sessions run with an empty HOME (no user's config or saved designs) from the
    // repository's root, as a reader who has just cloned it.
    // The environment is the sessions' own (set on each command, never on this test process,
    // which the other tests of the binary share).
    let home = tempfile::tempdir().unwrap();
    let at = |sub: &str| home.path().join(sub).to_string_lossy().into_owned();
    let cases = trycmd::TestCases::new();
    cases
        .env("HOME", at(""))
        .env("XDG_CONFIG_HOME", at("config"))
        .env("XDG_DATA_HOME", at("data"))
        .env("XDG_CONFIG_DIRS", at("no-config-dirs"))
        .env("NO_COLOR", "1");
    cases.register_bin("thud", trycmd::cargo::cargo_bin!("thud")).case("README.md");
    for page in guide_pages() {
        cases.case(page);
    }
    cases.run();
}

/// The session check is not vacuous: a page whose shown output differs from the real one by one
/// digit fails it.
#[test]
fn console_sessions_fail_when_an_output_changes() {
    let dir = tempfile::tempdir().unwrap();
    let page = dir.path().join("changed.md");
    let real = read("README.md");
    let at = real.find("$ thud simulate --preset paper-table3").expect("recipe 1's simulate");
    let block = &real[at..at + real[at..].find("\n```").unwrap()];
    assert!(block.contains("zone 3 (quiet, strong)"), "{block}");
    let changed = block.replacen("zone 3 (quiet, strong)", "zone 2 (quiet, strong)", 1);
    std::fs::write(&page, format!("```console\n{changed}\n```\n")).unwrap();
    let unchanged = dir.path().join("same.md");
    std::fs::write(&unchanged, format!("```console\n{block}\n```\n")).unwrap();
    let run = |path: PathBuf| {
        std::panic::catch_unwind(|| {
            trycmd::TestCases::new().register_bin("thud", trycmd::cargo::cargo_bin!("thud")).case(&path).run();
        })
    };
    assert!(run(unchanged).is_ok(), "the README's own session passes");
    assert!(run(page).is_err(), "a changed output must fail");
}

/// The range table and the work caps as Markdown, from the engine's table.
fn limits_tables() -> String {
    use thud::limits::{short, CAPS, GRID_N, THREADS};
    let cell = |s: &str| s.replace('|', "\\|");
    let mut s = String::from("| flag | what | range | why |\n|---|---|---|---|\n");
    for r in thud::params::listed_ranges().into_iter().chain([&GRID_N, &THREADS]) {
        let flag = if r.param == "N" {
            "`FROM:TO:N`".to_string()
        } else {
            format!("`--{}`", thud::cli::design_args::flag_of(r.param))
        };
        s += &format!("| {flag} | {} | {} | {} |\n", cell(r.what), cell(&r.describe()), cell(r.reason));
    }
    s += "\n| work | cap | how the cap was set (release build, 2 cores) |\n|---|---|---|\n";
    for c in &CAPS {
        s += &format!("| {} | {} | {} |\n", cell(c.what), short(c.max), cell(c.basis));
    }
    s += "\n| solver work | cap per run | why |\n|---|---|---|\n";
    for c in &thud::damper::SOLVER_CAPS {
        s += &format!("| {} | {} | {} |\n", cell(c.what), short(c.max), cell(c.basis));
    }
    s
}

/// docs/guide/limits.md's tables between `<!-- limits:start -->` and `<!-- limits:end -->` are
/// the engine's ranges and caps; `THUD_BLESS=1 cargo test --release --test it docs::limits`
/// regenerates them after a row changes.
#[test]
fn limits_table_of_the_guide_is_the_engine_s() {
    const PAGE: &str = "docs/guide/limits.md";
    let (start_mark, end_mark) = ("<!-- limits:start", "<!-- limits:end -->");
    let text = read(PAGE);
    let start = text.find(start_mark).expect("the range table's start marker");
    let start = start + text[start..].find("-->\n").unwrap() + "-->\n".len();
    let end = text.find(end_mark).expect("the range table's end marker");
    let want = format!("\n{}\n", limits_tables());
    if std::env::var_os("THUD_BLESS").is_some() {
        let new = format!("{}{}{}", &text[..start], want, &text[end..]);
        if new != text {
            let path = repo().join(PAGE);
            let mut tmp = tempfile::NamedTempFile::new_in(path.parent().unwrap()).unwrap();
            std::io::Write::write_all(&mut tmp, new.as_bytes()).unwrap();
            tmp.persist(&path).unwrap();
        }
        return;
    }
    assert_eq!(
        text[start..end],
        want,
        "{PAGE}'s range table is not the engine's; regenerate it with \
         THUD_BLESS=1 cargo test --release --test it docs::limits"
    );
}

/// The fenced blocks of a Markdown text: (info string, body).
fn fenced(text: &str) -> Vec<(String, String)> {
    let mut blocks = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if let Some(info) = line.strip_prefix("```") {
            let body: Vec<&str> = lines.by_ref().take_while(|l| !l.starts_with("```")).collect();
            blocks.push((info.trim().to_string(), body.join("\n") + "\n"));
        }
    }
    blocks
}

/// Lines of `text` outside fenced blocks and HTML comments.
fn prose(text: &str) -> Vec<&str> {
    let mut in_fence = false;
    text.lines()
        .filter(|l| {
            if l.starts_with("```") {
                in_fence = !in_fence;
                return false;
            }
            !in_fence && !l.starts_with("<!--")
        })
        .collect()
}

#[test]
fn the_readme_is_a_front_door() {
    let readme = read("README.md");
    let n = readme.lines().count();
    assert!(n <= 200, "README.md has {n} lines; the limit is 200 (the rest belongs in docs/guide)");
    for line in prose(&readme) {
        assert!(line.chars().count() <= 100, "a README line past 100 columns: {line}");
    }
    // The two commands, exactly as written.
    let blocks = fenced(&readme);
    assert!(
        blocks.iter().any(|(info, body)| info == "sh"
            && body.lines().any(|l| l.starts_with("cargo run --release "))
            && body.lines().any(|l| l.starts_with("cargo test --release "))),
        "the README's two commands"
    );
    // The three recipes, each with a session that runs (tested above).
    for recipe in ["## Recipe 1: ", "## Recipe 2: ", "## Recipe 3: "] {
        let at = readme.find(recipe).unwrap_or_else(|| panic!("no `{recipe}`"));
        let section = &readme[at..];
        let section = &section[..section[3..].find("\n## ").map_or(section.len(), |e| e + 3)];
        assert!(section.contains("```console\n$ thud "), "{recipe} has no session");
    }
}

#[test]
fn the_readme_s_lecture_is_the_example_tour_and_loads() {
    let readme = read("README.md");
    let lecture = fenced(&readme).into_iter().find(|(info, _)| info == "toml").expect("the lecture").1;
    let file = read("examples/tours/lecture.toml");
    let body: String = file.lines().filter(|l| !l.starts_with('#')).map(|l| format!("{l}\n")).collect();
    assert_eq!(lecture, body, "the README's lecture is examples/tours/lecture.toml");
    let tour = thud::tui::tour::Tour::parse("examples/tours/lecture.toml", &file).unwrap();
    assert_eq!(tour.steps.len(), 2);
    assert!(thud::tui::tour::Tour::parse("typo.toml", &read("examples/tours/typo.toml")).is_err());
}

#[test]
fn every_page_of_the_guide_is_in_the_book_and_every_link_leads_to_a_file() {
    let summary = read("docs/guide/SUMMARY.md");
    let listed: Vec<&str> = summary.split("](").skip(1).map(|s| s.split(')').next().unwrap()).collect();
    for page in guide_pages() {
        let rel = page.strip_prefix("docs/guide").unwrap().to_str().unwrap().to_string();
        if rel != "SUMMARY.md" {
            assert!(listed.contains(&rel.as_str()), "docs/guide/{rel} is not in SUMMARY.md");
        }
    }
    // Relative links of the README and of the guide's pages (SUMMARY.md aside: `mdbook build
    // docs` checks it, and it lists pages other work adds) lead to files of the repository.
    let mut pages: Vec<PathBuf> = guide_pages().into_iter().filter(|p| !p.ends_with("SUMMARY.md")).collect();
    pages.push(PathBuf::from("README.md"));
    for page in pages {
        let text = read(page.to_str().unwrap());
        let prose_text = prose(&text).join("\n");
        for link in prose_text.split("](").skip(1).map(|s| s.split(')').next().unwrap()) {
            if link.contains("://") || link.starts_with('#') || link.starts_with("mailto:") {
                continue;
            }
            let file = link.split('#').next().unwrap();
            let target = repo().join(page.parent().unwrap()).join(file);
            assert!(target.exists(), "{}: the link {link} leads nowhere", page.display());
        }
    }
}

/// Every page of the guide has a title (its first `# …` line) of its own: two pages called
/// "The explorer" read as one in the book's search and a browser's tabs.
#[test]
fn every_guide_page_has_a_title_of_its_own() {
    let mut seen: Vec<(String, PathBuf)> = Vec::new();
    for page in guide_pages() {
        let text = read(page.to_str().unwrap());
        // The first heading (a page may open with a comment or include its text from elsewhere).
        let Some(title) = text.lines().find(|l| l.starts_with("# ")).map(str::to_string) else { continue };
        if let Some((_, other)) = seen.iter().find(|(t, _)| *t == title) {
            panic!("{} and {} are both titled {title}", other.display(), page.display());
        }
        seen.push((title, page));
    }
    assert!(seen.iter().any(|(t, _)| t == "# Getting started"), "a getting-started page");
}

/// `thud man --install` run through a symbolic link on `PATH` (`BIN/thud` → a binary
/// elsewhere) writes beside the link's folder, where man looks for the `thud` on `PATH`, not
/// beside the binary's; with `MANPATH` set, into its first folder.
#[test]
fn man_install_through_a_link_writes_where_man_looks_and_follows_manpath() {
    let root = tempfile::tempdir().unwrap();
    let real = root.path().join("build/release");
    let bin = root.path().join("prefix/bin");
    std::fs::create_dir_all(&real).unwrap();
    std::fs::create_dir_all(&bin).unwrap();
    crate::common::copy_thud(&real.join("thud"));
    std::os::unix::fs::symlink(real.join("thud"), bin.join("thud")).unwrap();
    let path = format!("{}:/usr/bin:/bin", bin.display());
    // Run by name, as a shell runs it: found on PATH.
    let out = std::process::Command::new("thud")
        .args(["man", "--install"])
        .env("PATH", &path)
        .env_remove("MANPATH")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(root.path().join("prefix/share/man/man1/thud.1").is_file(), "beside the link's folder");
    assert!(!root.path().join("build/share").exists(), "not beside the binary's");
    // Run by the link's path.
    std::fs::remove_dir_all(root.path().join("prefix/share")).unwrap();
    let out =
        std::process::Command::new(bin.join("thud")).args(["man", "--install"]).env_remove("MANPATH").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(root.path().join("prefix/share/man/man1/thud.1").is_file());
    // MANPATH set (":" first is an empty entry, skipped): its first folder.
    let mine = root.path().join("man");
    let out = std::process::Command::new(bin.join("thud"))
        .args(["man", "--install"])
        .env("MANPATH", format!(":{}:/usr/share/man", mine.display()))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(mine.join("man1/thud-sweep.1").is_file(), "MANPATH's first folder");
}

/// `thud man --install` writes the pages beside the binary's folder (`BIN/../share/man/man1`),
/// where man-db's manpath looks for the `thud` on `PATH`: after it `man -w thud` finds thud(1)
/// with no MANPATH set. Run from a copy of the binary in a temporary prefix.
#[test]
fn man_finds_thud_after_man_install() {
    let prefix = tempfile::tempdir().unwrap();
    let bin = prefix.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    crate::common::copy_thud(&bin.join("thud"));
    let out =
        std::process::Command::new(bin.join("thud")).args(["man", "--install"]).env_remove("MANPATH").output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let page = prefix.path().join("share/man/man1/thud.1");
    assert!(std::fs::read_to_string(&page).unwrap().starts_with(".TH"), "{}", page.display());
    assert!(prefix.path().join("share/man/man1/thud-sweep.1").is_file());
    // --install goes alone: with a command, --all or --force it is refused with one line.
    for (args, names) in [
        (&["man", "--install", "--force"][..], ["--install", "--force"]),
        (&["man", "pulse", "--install"][..], ["COMMAND", "--install"]),
        (&["man", "--install", "--all", "x"][..], ["--install", "--all"]),
    ] {
        let o = std::process::Command::new(bin.join("thud")).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(names.iter().all(|n| err.contains(n)), "{args:?}: {err}");
    }
    // A second install replaces the pages (an upgrade), never refuses.
    let again =
        std::process::Command::new(bin.join("thud")).args(["man", "--install"]).env_remove("MANPATH").output().unwrap();
    assert!(again.status.success(), "{}", String::from_utf8_lossy(&again.stderr));
    // man(1) itself, where it is installed (man-db: Debian's `man-db` package).
    let Ok(man) = std::process::Command::new("man")
        .args(["-w", "thud"])
        .env_remove("MANPATH")
        .env("PATH", format!("{}:/usr/bin:/bin", bin.display()))
        .output()
    else {
        crate::support::skip::skip("man is not installed (man-db): only the pages' place was checked");
        return;
    };
    assert!(man.status.success(), "man -w thud: {}", String::from_utf8_lossy(&man.stderr));
    assert_eq!(String::from_utf8_lossy(&man.stdout).trim(), page.to_str().unwrap());
}
