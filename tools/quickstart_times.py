#!/usr/bin/env python3
"""Times the README's two quick-start commands as a newcomer runs them: each in a fresh clone of
this repository (its committed HEAD), with an empty cargo cache (a new CARGO_HOME: the crates are
downloaded and every dependency is built), one after the other so that they do not share the
cores. Prints a Markdown section and, with --markdown FILE, writes it into FILE as the section
`quick-start` (between `<!-- begin quick-start -->` and `<!-- end quick-start -->`).

Usage: python3 tools/quickstart_times.py [--markdown docs/results.md]
"""

import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

from markdown_section import write_section

COMMANDS = [
    ("main job", ["cargo", "run", "--release", "--example", "spectrum"]),
    ("tests", ["cargo", "test"]),
]


def run(repo: str, cmd: list) -> float:
    work = tempfile.mkdtemp(prefix="strata-quickstart-")
    try:
        clone = os.path.join(work, "strata")
        subprocess.run(["git", "clone", "--quiet", repo, clone], check=True)
        env = dict(os.environ)
        env["CARGO_HOME"] = os.path.join(work, "cargo-home")  # empty: nothing cached
        env.pop("CARGO_TARGET_DIR", None)
        start = time.monotonic()
        done = subprocess.run(cmd, cwd=clone, env=env, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
        elapsed = time.monotonic() - start
        if done.returncode != 0:
            sys.exit(f"{' '.join(cmd)} failed with status {done.returncode}")
        return elapsed
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main() -> None:
    args = sys.argv[1:]
    markdown = None
    if args[:1] == ["--markdown"] and len(args) == 2:
        markdown = args[1]
    elif args:
        sys.exit(__doc__)
    repo = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=repo,
                          capture_output=True, text=True, check=True).stdout.strip()
    rustc = subprocess.run(["rustc", "--version"], capture_output=True, text=True,
                           check=True).stdout.strip()
    rows = []
    for what, cmd in COMMANDS:
        t = run(repo, cmd)
        rows.append((what, " ".join(cmd), t))
        print(f"{what}: {t:.0f} s", file=sys.stderr)
    body = (
        f"`python3 tools/quickstart_times.py --markdown docs/results.md`: each command in a fresh "
        f"clone of `{head}` with an empty cargo cache (the crates downloaded and every "
        f"dependency built), one after the other; {os.cpu_count()} cores, {rustc}, "
        f"{platform.machine()}.\n\n"
        "| command | wall time |\n|---|---|\n"
        + "".join(f"| `{c}` ({w}) | {t / 60:.1f} min ({t:.0f} s) |\n" for w, c, t in rows)
    )
    print(body)
    if markdown:
        write_section(markdown, "quick-start", body, heading="## Quick start")

if __name__ == "__main__":
    main()
