"""The one writer of a Markdown section for the Python tools, as the example programs write
theirs (`examples/common`): the text between `<!-- begin NAME -->` and `<!-- end NAME -->` of a
file is replaced, or the section is appended, through a temporary file renamed over the target,
while an exclusive `flock` on the file's directory is held (the programs' lock), so that
concurrent writers of `docs/results.md` take turns and none loses a section."""

import fcntl
import os


def write_section(path: str, name: str, body: str, heading: str = "") -> None:
    """Writes `body` as the section `name` of the Markdown file `path`; a new section goes at
    the end, after `heading` (a line such as `## Quick start`) when one is given."""
    begin, end = f"<!-- begin {name} -->", f"<!-- end {name} -->"
    block = f"{begin}\n{body.strip(chr(10))}\n{end}"
    directory = os.path.dirname(os.path.abspath(path))
    lock = os.open(directory, os.O_RDONLY)
    try:
        fcntl.flock(lock, fcntl.LOCK_EX)
        text = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
        i = text.find(begin + "\n")
        j = text.find(end, i + 1) if i >= 0 else -1
        if i >= 0 and j > i:
            text = text[:i] + block + text[j + len(end):]
        else:
            lead = f"{heading}\n\n" if heading else ""
            text = text.rstrip("\n") + "\n\n" + lead + block + "\n"
        tmp = os.path.join(directory, f".{os.path.basename(path)}.{os.getpid()}.tmp")
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, path)
    finally:
        os.close(lock)
