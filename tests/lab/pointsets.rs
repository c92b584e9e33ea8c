//! The point-set readers never panic: arbitrary bytes, and valid files of every format with
//! bytes flipped, inserted or cut, give a set or a clear error (proptest's fuzzing; the
//! `fuzz/` crate has a libFuzzer target for longer runs).

use proptest::prelude::*;
use strata_lab::pointsets::{self, Format, PointSet};

fn valid(format: Format, sets: &[PointSet]) -> Vec<u8> {
    let mut out = Vec::new();
    pointsets::write(sets, format, &mut out).unwrap();
    out
}

fn some_sets() -> impl Strategy<Value = Vec<PointSet>> {
    (1usize..4, 1usize..6, 1usize..4).prop_flat_map(|(dims, n, k)| {
        prop::collection::vec(prop::collection::vec(0.0f64..1.0, dims * n), k).prop_map(
            move |sets| {
                sets.into_iter()
                    .map(|c| PointSet::new(c, dims as u32).unwrap())
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

/// A UTK binary header (magic, f32, then the three counts) followed by `values` f32 zeros.
fn utk_bin(sets: u32, points: u32, dims: u32, values: usize) -> Vec<u8> {
    let mut b = b"UTK!".to_vec();
    b.extend_from_slice(&[4, 0, 0, 0]);
    for c in [sets, points, dims] {
        b.extend_from_slice(&c.to_le_bytes());
    }
    b.resize(b.len().max(20), 0);
    b.extend(std::iter::repeat_n(0u8, values * 4));
    b
}

#[test]
fn hostile_files_are_refused_or_read_in_full() {
    // a byte-order mark is not a header: the first row is kept (issue 24, row 3)
    let bom = pointsets::parse(b"\xef\xbb\xbf0.1,0.2\n0.3,0.4\n0.5,0.6\n").unwrap();
    assert_eq!(bom[0].len(), 3);
    assert_eq!(
        pointsets::parse_csv("\u{feff}x,y\n0.1,0.2\n")
            .unwrap()
            .len(),
        1
    );
    // a typo in the first row is an error, not a header; two header lines are an error
    for text in [
        "0.1a,0.2\n0.3,0.4\n",
        "x,y\nu,v\n0.3,0.4\n",
        "\u{feff}a\nb\n0.1\n",
    ] {
        let e = pointsets::parse_csv(text).unwrap_err().to_string();
        assert!(e.contains("is not a number"), "{text:?}: {e}");
    }
    // UTK binary files whose counts lie about the data: more, fewer, or overflowing
    for (sets, points, dims, values) in [
        (1, 4, 2, 7),
        (1, 4, 2, 9),
        (2, 4, 2, 8),
        (u32::MAX, u32::MAX, u32::MAX, 4),
        (1, 1 << 31, 1 << 31, 2),
    ] {
        let e = pointsets::parse_utk_bin(&utk_bin(sets, points, dims, values))
            .unwrap_err()
            .to_string();
        assert!(e.contains("UTK binary"), "{e}");
    }
    assert_eq!(
        pointsets::parse_utk_bin(&utk_bin(2, 4, 2, 16))
            .unwrap()
            .len(),
        2
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, ..ProptestConfig::default() })]

    /// A byte-order mark changes nothing: a CSV reads the same with and without one.
    #[test]
    fn a_byte_order_mark_changes_nothing(sets in some_sets(), header in any::<bool>()) {
        let mut text = valid(Format::Csv, &sets[..1]);
        if !header {
            let cut = text.iter().position(|&b| b == b'\n').unwrap() + 1;
            text.drain(..cut);
        }
        let mut marked = b"\xef\xbb\xbf".to_vec();
        marked.extend_from_slice(&text);
        prop_assert_eq!(pointsets::parse(&marked).unwrap(), pointsets::parse(&text).unwrap());
    }
}
