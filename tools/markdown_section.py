"""The Python tools' writer of a Markdown section, under the rules of the library's
(`strata_lab::io::markdown`, which the example programs and the tests use): the text between
`<!-- begin NAME -->` and `<!-- end NAME -->` of a file is replaced in place, or a new section is
appended after a blank line; a marker found twice, or only one of the two, or the two out of
order, is refused and the file left as it was. The write goes through a temporary file renamed
over the target while an exclusive `flock` on the file's directory is held (the programs' lock),
so that concurrent writers of `docs/results.md` take turns and none loses a section.

`tests/lab/docs.rs` runs `splice` against the library's `splice_section` on the same cases
(`python3 tools/markdown_section.py splice NAME OLD BLOCK` prints the result, or the refusal on
stderr with exit status 1)."""

import fcntl
import os
import sys


def markers(name: str):
    """The begin and end marker lines of section `name`."""
    return f"<!-- begin {name} -->", f"<!-- end {name} -->"


def splice(text: str, name: str, block: str) -> str:
    """`text` with section `name` set to `block` (the whole section, markers included); a
    ValueError for broken markers."""
    begin, end = markers(name)
    if not (block.startswith(begin) and block.endswith(end)):
        raise ValueError(f"a section block starts with {begin} and ends with {end}")

    def once(marker: str):
        first = text.find(marker)
        if first >= 0 and text.find(marker, first + 1) >= 0:
            raise ValueError(f"the marker {marker} appears more than once")
        return first if first >= 0 else None

    a, b = once(begin), once(end)
    if a is not None and b is not None and b > a:
        return text[:a] + block + text[b + len(end):]
    if a is None and b is None:
        return block + "\n" if text == "" else text.rstrip() + "\n\n" + block + "\n"
    raise ValueError(
        f"the markers of section '{name}' are out of order or one is missing "
        f"({begin} must come before {end})"
    )


def write_section(path: str, name: str, body: str, heading: str = "") -> None:
    """Writes `body` as the section `name` of the Markdown file `path`; a new section goes at
    the end, after `heading` (a line such as `## Quick start`) when one is given. A ValueError
    naming the file, which is left untouched, when its markers are broken."""
    begin, end = markers(name)
    block = f"{begin}\n{body.strip(chr(10))}\n{end}"
    directory = os.path.dirname(os.path.abspath(path))
    lock = os.open(directory, os.O_RDONLY)
    try:
        fcntl.flock(lock, fcntl.LOCK_EX)
        text = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        try:
            new = splice(text, name, block)
        except ValueError as e:
            raise ValueError(f"{path}: {e}; the file was left untouched") from None
        if heading and begin not in text:
            # a new section: its heading before it
            at = new.rfind(begin)
            new = new[:at] + heading + "\n\n" + new[at:]
        tmp = os.path.join(directory, f".{os.path.basename(path)}.{os.getpid()}.tmp")
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(new)
        os.replace(tmp, path)
    finally:
        os.close(lock)


if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] != "splice":
        sys.exit("usage: markdown_section.py splice NAME OLD BLOCK")
    try:
        sys.stdout.write(splice(sys.argv[3], sys.argv[2], sys.argv[4]))
    except ValueError as e:
        print(e, file=sys.stderr)
        sys.exit(1)
