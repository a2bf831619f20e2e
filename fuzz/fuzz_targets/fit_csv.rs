//! The fit's measurement reader (`thud fit … --data FILE`): any bytes, as the text of a file.
//! It must answer with a record or a refusal of the input (exit 2 and its line), never panic.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let ctx = thud::cli::Ctx { no_limit: false };
    if let Err(e) = thud::cli::fit_record_from_text(std::path::Path::new("fuzz.csv"), text, &ctx) {
        let (code, line) = e.report(&[]);
        assert_eq!(code, 2, "bad input is exit 2: {e:?}");
        assert!(line.is_some_and(|l| !l.is_empty()), "a refusal says why: {e:?}");
    }
});
