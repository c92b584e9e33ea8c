//! Sections of a Markdown file: the text between the lines `<!-- begin NAME -->` and
//! `<!-- end NAME -->`, which a program, a tool or a test rewrites while keeping the rest of
//! the file. The one home of the rules every writer follows (the programs' `--markdown`, the
//! Python tools in `tools/`, the tests that bless generated tables): a section replaces its
//! earlier version in place; a new one goes at the end, after a blank line; a marker found
//! twice, or only one of the two, or the two out of order, is refused, leaving the file as it
//! was (a hand edit or a merge gone wrong must not be written over).

use crate::{Error, Result};

/// The begin and end marker lines of section `name`.
pub fn markers(name: &str) -> (String, String) {
    (
        format!("<!-- begin {name} -->"),
        format!("<!-- end {name} -->"),
    )
}

/// The place of each of section `name`'s markers in `text`: `(begin, end)` byte offsets, both
/// `None` when the section is absent; an error when a marker appears twice, or only one of
/// them, or the end before the begin.
fn find(text: &str, name: &str) -> Result<Option<(usize, usize)>> {
    let (begin, end) = markers(name);
    let once = |marker: &str| -> Result<Option<usize>> {
        let mut found = text.match_indices(marker).map(|(i, _)| i);
        let first = found.next();
        if found.next().is_some() {
            return Err(Error::input(
                "io::markdown",
                format!("the marker {marker} appears more than once"),
            ));
        }
        Ok(first)
    };
    match (once(&begin)?, once(&end)?) {
        (Some(a), Some(b)) if b > a => Ok(Some((a, b + end.len()))),
        (None, None) => Ok(None),
        _ => Err(Error::input(
            "io::markdown",
            format!(
                "the markers of section '{name}' are out of order or one is missing ({begin} \
                 must come before {end})"
            ),
        )),
    }
}

/// The text of section `name` in `text`, between its begin marker's line and its end marker
/// (`None` when it is absent; an error as for [`splice_section`]).
pub fn section_text<'a>(text: &'a str, name: &str) -> Result<Option<&'a str>> {
    let begin = markers(name).0;
    Ok(find(text, name)?.map(|(a, b)| {
        let inner = &text[a + begin.len()..b - markers(name).1.len()];
        inner.strip_prefix('\n').unwrap_or(inner)
    }))
}

/// `text` with section `name` set to `block`, which is the whole section: its begin marker,
/// what it holds, its end marker (an error otherwise). The earlier version of the section is
/// replaced in place; a new section goes at the end of the text after a blank line (or makes
/// the whole text, with a final newline, when the text is empty); a marker found twice, or
/// only one of the two, or the two out of order, is an error (the caller leaves its file as it
/// was).
pub fn splice_section(text: &str, name: &str, block: &str) -> Result<String> {
    let (begin, end) = markers(name);
    if !block.starts_with(&begin) || !block.ends_with(&end) {
        return Err(Error::input(
            "io::markdown",
            format!("a section block starts with {begin} and ends with {end}"),
        ));
    }
    Ok(match find(text, name)? {
        Some((a, b)) => format!("{}{block}{}", &text[..a], &text[b..]),
        None if text.is_empty() => format!("{block}\n"),
        None => format!("{}\n\n{block}\n", text.trim_end()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_section_is_replaced_in_place_or_appended() {
        let block = |body: &str| format!("<!-- begin s -->\n{body}\n<!-- end s -->");
        let doc = format!("# T\n\n{}\n\ntail\n", block("old"));
        let new = splice_section(&doc, "s", &block("new")).unwrap();
        assert_eq!(new, format!("# T\n\n{}\n\ntail\n", block("new")));
        assert_eq!(section_text(&new, "s").unwrap(), Some("new\n"));
        assert_eq!(
            splice_section("# T\n\n\n", "s", &block("x")).unwrap(),
            format!("# T\n\n{}\n", block("x"))
        );
        assert_eq!(
            splice_section("", "s", &block("x")).unwrap(),
            format!("{}\n", block("x"))
        );
        assert_eq!(section_text("# T\n", "s").unwrap(), None);
    }

    #[test]
    fn broken_markers_are_refused() {
        let block = "<!-- begin s -->\nx\n<!-- end s -->";
        for bad in [
            "<!-- begin s -->\n",
            "<!-- end s -->\n",
            "<!-- end s -->\n<!-- begin s -->\n",
            "<!-- begin s -->\n<!-- end s -->\n<!-- begin s -->\n<!-- end s -->\n",
        ] {
            let e = splice_section(bad, "s", block).unwrap_err().to_string();
            assert!(e.contains("<!--"), "{bad:?}: {e}");
            assert!(section_text(bad, "s").is_err());
        }
        assert!(splice_section("", "s", "x").is_err());
        // another section's markers are not this one's
        let other = "<!-- begin t -->\n<!-- end t -->\n";
        assert!(
            splice_section(other, "s", block)
                .unwrap()
                .starts_with(other)
        );
    }
}
