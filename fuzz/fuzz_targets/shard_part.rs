//! A part of a sharded chart (`thud merge PART…`) on any text: its header and cells checked,
//! a part or an error, never a panic (nor an allocation sized by a forged header).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Err(e) = thud::shard::parse("part.jsonl", text) {
        let _ = e.to_string();
    }
});
