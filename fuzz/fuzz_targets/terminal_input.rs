//! The explorer's terminal input parser on any bytes, cut into reads anywhere: every byte is
//! consumed, what it holds between reads stays within `SEQUENCE_MAX`, never a panic.
#![no_main]

use std::time::{Duration, Instant};

use libfuzzer_sys::fuzz_target;
use thud::tui::input_parse::{Parser, SEQUENCE_MAX};

fuzz_target!(|data: &[u8]| {
    // The first byte chooses where reads end: every (1 + its low 6 bits) bytes.
    let Some((&cut, bytes)) = data.split_first() else { return };
    let step = 1 + usize::from(cut & 0x3f);
    let mut parser = Parser::default();
    let start = Instant::now();
    for (i, chunk) in bytes.chunks(step).enumerate() {
        let now = start + Duration::from_millis(u64::try_from(i).unwrap_or(u64::MAX) * u64::from(cut >> 6) * 300);
        parser.feed(chunk, false, now);
        parser.expire(now);
        assert!(parser.held() <= SEQUENCE_MAX, "held {} bytes", parser.held());
        while parser.next_parsed().is_some() {}
    }
    parser.finish();
    assert_eq!(parser.held(), 0);
    while parser.next_parsed().is_some() {}
});
