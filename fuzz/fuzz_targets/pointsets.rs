//! The point-set readers on arbitrary bytes: a set or an error, never a panic or an
//! allocation larger than the input. `cargo +nightly fuzz run pointsets`.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = strata::pointsets::parse(data);
    let _ = strata::pointsets::parse_utk_bin(data);
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = strata::pointsets::parse_csv(text);
        let _ = strata::pointsets::parse_utk_text(text);
    }
});
