//! `thud config check` on any text: every problem found, never a panic (the same code the
//! commands load the settings with).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    for problem in thud::config::check_text(std::path::Path::new("config.toml"), text) {
        let _ = problem.to_string();
    }
});
