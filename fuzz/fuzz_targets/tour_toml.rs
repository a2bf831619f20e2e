//! A tour file (`thud tui --tour FILE`) on any text: a tour or an error, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Err(e) = thud::tui::tour::Tour::parse("tour.toml", text) {
        let _ = e.to_string();
    }
});
