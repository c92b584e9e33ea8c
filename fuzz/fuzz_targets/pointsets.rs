//! The point-set readers on arbitrary bytes: a set or an error, never a panic or an
//! allocation larger than the input, and a UTF-8 byte-order mark changes nothing.
//! `cargo +nightly fuzz run pointsets fuzz/seeds/pointsets` starts from the hostile inputs of
//! issue 24 (CSV with a byte-order mark, header lines, typos; UTK files whose counts lie).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let plain = strata_lab::pointsets::parse(data);
    let mut marked = b"\xef\xbb\xbf".to_vec();
    marked.extend_from_slice(data);
    if !data.starts_with(b"\xef\xbb\xbf") {
        let with_mark = strata_lab::pointsets::parse(&marked);
        assert_eq!(plain.is_ok(), with_mark.is_ok());
        if let (Ok(a), Ok(b)) = (&plain, &with_mark) {
            assert_eq!(a, b);
        }
    }
    if let Ok(sets) = &plain {
        let values: usize = sets.iter().map(|s| s.coords.len()).sum();
        assert!(values <= data.len(), "{values} values from {} bytes", data.len());
    }
    let _ = strata_lab::pointsets::parse_utk_bin(data);
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = strata_lab::pointsets::parse_csv(text);
        let _ = strata_lab::pointsets::parse_utk_text(text);
    }
});
