//! The point-set readers never panic: arbitrary bytes, and valid files of every format with
//! bytes flipped, inserted or cut, give a set or a clear error (proptest's fuzzing; the
//! `fuzz/` crate has a libFuzzer target for longer runs).

use proptest::prelude::*;
use strata::pointsets::{self, Format, PointSet};

fn valid(format: Format, sets: &[PointSet]) -> Vec<u8> {
    let mut out = Vec::new();
    pointsets::write(&mut out, format, sets).unwrap();
    out
}

fn some_sets() -> impl Strategy<Value = Vec<PointSet>> {
    (1usize..4, 1usize..6, 1usize..4).prop_flat_map(|(dims, n, k)| {
        prop::collection::vec(prop::collection::vec(0.0f64..1.0, dims * n), k).prop_map(
            move |sets| {
                sets.into_iter()
                    .map(|c| PointSet::new(dims, c).unwrap())
                    .collect::<Vec<_>>()
            },
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..256)) {
        let _ = pointsets::parse(&bytes);
        let _ = pointsets::parse_utk_bin(&bytes);
        if let Ok(text) = std::str::from_utf8(&bytes) {
            let _ = pointsets::parse_csv(text);
            let _ = pointsets::parse_utk_text(text);
        }
    }

    #[test]
    fn damaged_files_never_panic(
        sets in some_sets(),
        format in 0usize..3,
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), 0u8..3), 1..6),
    ) {
        let format = [Format::Csv, Format::UtkText, Format::UtkBin][format];
        let sets = if format == Format::Csv { sets[..1].to_vec() } else { sets };
        let mut bytes = valid(format, &sets);
        prop_assert_eq!(pointsets::parse(&bytes).unwrap(), sets);
        for (at, byte, kind) in edits {
            if bytes.is_empty() {
                break;
            }
            let at = at % bytes.len();
            match kind {
                0 => bytes[at] = byte,
                1 => bytes.insert(at, byte),
                _ => bytes.truncate(at),
            }
        }
        // a set or an error, and an error says something
        if let Err(e) = pointsets::parse(&bytes) {
            prop_assert!(!e.to_string().is_empty());
        }
    }
}
