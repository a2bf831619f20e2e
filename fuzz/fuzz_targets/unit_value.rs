//! A value with its unit as a flag takes it (`--mass 40.5g`, `--gap 4cm`, `--freq 5Hz`), for
//! every kind of quantity: a number or an error naming the flag, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use thud::units::{self, Kind};

const KINDS: [Kind; 18] = [
    Kind::Mass,
    Kind::Length,
    Kind::Speed,
    Kind::Angle,
    Kind::Time,
    Kind::Stiffness,
    Kind::Damping,
    Kind::HertzStiffness,
    Kind::Density,
    Kind::Impedance,
    Kind::Level,
    Kind::Inclination,
    Kind::Force,
    Kind::Frequency,
    Kind::Temperature,
    Kind::Pressure,
    Kind::Acceleration,
    Kind::Number,
];

fuzz_target!(|data: &[u8]| {
    let Some((&k, rest)) = data.split_first() else { return };
    let Ok(text) = std::str::from_utf8(rest) else { return };
    let kind = KINDS[usize::from(k) % KINDS.len()];
    if let Err(e) = units::parse("--value", text, kind) {
        let message = e.to_string();
        assert!(message.contains("--value"), "the error names the flag: {message:?}");
    }
});
