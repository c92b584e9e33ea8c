#!/usr/bin/env python3
"""Regenerates docs/results.md, the measured figures, from the current code: one command.

    python3 tools/results.py             # every section (about 40 minutes on 2 cores)
    python3 tools/results.py --quick     # the sections that take under two minutes each
    python3 tools/results.py NAME...     # these sections (see --list)
    python3 tools/results.py --list      # the sections, their commands, which are expensive
    python3 tools/results.py --assemble  # only the layout: listed sections kept, others dropped
    python3 tools/results.py --extras    # also the studies kept out of the file, into
                                         # out/results/extras.md

The file is rebuilt from the list below, in its order, under its headings, with a table of
contents: a section that is not rerun keeps its last text, a section that is not listed is
dropped (history is git's). Each program writes its own section (`--markdown`, through the
library's section rules, `strata_lab::io::markdown`), naming the command that wrote it; this
script adds the commit it ran at (and whether the tree had uncommitted changes) and the date.
The programs' other outputs go under out/results/.
"""

import datetime
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from markdown_section import markers, splice  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS = "docs/results.md"
EX = ["cargo", "run", "--release", "--quiet", "--example"]

# (heading, [(section names, command, expensive)]): a command may write several sections.
# `{md}` is the Markdown file; `{out}` a directory under out/results.
LAYOUT = [
    ("Quick start", [
        (["quick-start"], ["python3", "tools/quickstart_times.py", "--markdown", "{md}"], True),
    ]),
    ("Spectra and spacing", [
        (["spectrum"], EX + ["spectrum", "--", "--out", "{out}", "--markdown", "{md}"], False),
        (["blue-noise-table"], EX + ["spectrum", "--", "--blue-noise-table", "--markdown", "{md}"],
         False),
    ]),
    ("Convergence, and the time to an error", [
        (["tradeoff", "time-to-error"],
         EX + ["tradeoff", "--", "--out", "{out}", "--markdown", "{md}"], False),
    ]),
    ("Conformance of the path-tracer sequences", [
        (["conformance"], EX + ["conformance", "--", "--sampler", "all", "--markdown", "{md}"],
         False),
        (["pair-test"], EX + ["conformance", "--", "--pairs", "--seeds", "8", "--markdown", "{md}"],
         True),
    ]),
    ("The nets of the jointly Z-ordered sequences", [
        (["nets-zquad"], EX + ["nets", "--", "--sequence", "zquad", "--markdown", "{md}"], False),
    ]),
    ("In a path tracer", [
        (["render-cornell-direct-1,2,4,16,64"],
         EX + ["render", "--", "--scene", "cornell-direct", "--seeds", "16", "--spp",
               "1,2,4,16,64", "--samplers",
               "sobol,zsobol,zjoint,zquad,sobol12,zsobol12,pbrt-padded,pbrt-zsobol",
               "--interactions", "--out", "{out}", "--markdown", "{md}"], True),
        (["render-studio-direct-1,2,4"],
         EX + ["render", "--", "--scene", "studio-direct", "--seeds", "512", "--spp", "1,2,4",
               "--samplers", "sobol,zsobol,zjoint,pbrt-zsobol,pbrt-zsobol-seeded", "--out",
               "{out}", "--markdown", "{md}"], True),
        # zsobol against pbrt's ZSobol, its pixel order fixed (pbrt's) and drawn per seed
        (["render-cornell-direct-1,2,4"],
         EX + ["render", "--", "--scene", "cornell-direct", "--seeds", "512", "--spp", "1,2,4",
               "--samplers", "sobol,zsobol,zjoint,pbrt-zsobol,pbrt-zsobol-seeded", "--out",
               "{out}", "--markdown", "{md}"], True),
    ]),
    ("Blue noise without a count", [
        # one configuration of the progressive sequences at every count, beside zsobol told
        # each count and OpenQMC's blue-noise sampler, and an adaptive image
        (["render-" + scene + "-1,2,3,4,8,16,64,256-adaptive"],
         EX + ["render", "--", "--scene", scene, "--seeds", "32", "--spp",
               "1,2,3,4,8,16,64,256", "--samplers", "sobol,zsobol,sobolbn,openqmc-sobolbn",
               "--adaptive", "64", "--out", "{out}", "--markdown", "{md}"], True)
        for scene in ["cornell-direct", "cornell", "studio"]
    ] + [
        # the studio's small counts, where 32 seeds do not resolve the order of the samplers
        (["render-studio-1,2,4"],
         EX + ["render", "--", "--scene", "studio", "--seeds", "512", "--spp", "1,2,4",
               "--samplers", "sobol,zsobol,sobolbn,openqmc-sobolbn", "--out", "{out}",
               "--markdown", "{md}"], True),
    ]),
    ("Speed of the path-tracer adapter", [
        (["bench-pixel"],
         ["sh", "-c", "cargo bench -p strata-benches --bench pixel && python3 "
          "tools/criterion_table.py pixel sobol_burley-sample_4d,sobol_burley-sample "
          "--markdown {md} --section bench-pixel"], True),
        # the same image group built for x86-64-v3 (AVX2; SSE4.1's 32-bit multiply), where the
        # peer's four-lane code runs natively: needs such a CPU
        (["bench-pixel-x86-64-v3"],
         ["sh", "-c", "export CARGO_TARGET_DIR=\"$PWD/target/x86-64-v3\" RUSTFLAGS='-C "
          "target-cpu=x86-64-v3' && cargo bench -p strata-benches --bench pixel -- pixel/get_2d "
          "&& python3 tools/criterion_table.py pixel_get_2d "
          "sobol_burley-sample_4d,sobol_burley-sample --markdown {md} "
          "--section bench-pixel-x86-64-v3"], True),
    ]),
]

# Studies kept out of the file (their latest runs are in git's history), rerun by --extras.
EXTRAS = [
    (["render-cornell-direct-1,2,4,16,64-interacting"],
     EX + ["render", "--", "--scene", "cornell-direct", "--seeds", "16", "--spp",
           "1,2,4,16,64", "--samplers", "sobol,zjoint,zquad,sobol12-4,zsobol12-4",
           "--layout", "interacting", "--interactions", "--out", "{out}", "--markdown",
           "{md}"], True),
    (["nets-zjoint-8"], EX + ["nets", "--", "--markdown", "{md}"], False),
    (["render-cornell-4,16,64,256"],
     EX + ["render", "--", "--scene", "cornell", "--seeds", "16", "--spp", "4,16,64,256",
           "--samplers", "sobol,pmj02,zsobol,pbrt-padded,pbrt-zsobol", "--out", "{out}",
           "--markdown", "{md}"], True),
    (["render-studio-direct-16,64,256"],
     EX + ["render", "--", "--scene", "studio-direct", "--seed", "1001", "--seeds", "64",
           "--spp", "16,64,256", "--samplers", "sobol,sobol+shells,sobol+permute,pbrt-padded",
           "--out", "{out}", "--markdown", "{md}"], True),
    (["render-spheres-1,2,4,16"],
     EX + ["render", "--", "--scene", "spheres", "--samplers",
           "sobol,zsobol,zjoint-4,zjoint,zjoint-256", "--spp", "1,2,4,16", "--seeds", "16",
           "--out", "{out}", "--markdown", "{md}"], False),
]

INTRO = """# Results

The measured figures of the two crates, regenerated from the current code by one command,
`python3 tools/results.py` (`--quick` for the sections that take under two minutes, `NAME...`
for some, `--list` for all with their commands). Each section names the command that wrote it,
the commit it ran at and the date; rerun it to refresh it. Machine: 2 cores.
"""


def sections():
    """Every listed section, in the file's order: (heading, names, command, expensive)."""
    for heading, commands in LAYOUT:
        for names, command, expensive in commands:
            yield heading, names, command, expensive


def anchor(heading: str) -> str:
    """GitHub's anchor of a heading."""
    kept = "".join(c for c in heading.lower() if c.isalnum() or c in " -")
    return kept.replace(" ", "-")


def skeleton(old: str) -> str:
    """The file's layout with the current text of every listed section (an empty section where
    there is none yet) and nothing else."""
    toc = "\n".join(f"- [{h}](#{anchor(h)}): " + ", ".join(
        f"`{n}`" for names, _, _ in cmds for n in names) for h, cmds in LAYOUT)
    parts = [INTRO, "## Contents\n\n" + toc + "\n"]
    for heading, commands in LAYOUT:
        parts.append(f"## {heading}\n")
        for names, _, _ in commands:
            for name in names:
                begin, end = markers(name)
                a, b = old.find(begin), old.find(end)
                if a >= 0 and b > a:
                    parts.append(old[a:b + len(end)] + "\n")
                else:
                    parts.append(f"{begin}\n(not yet run: `python3 tools/results.py {name}`)\n"
                                 f"{end}\n")
    return "\n".join(parts)


def stamp(path: str, name: str, when: str) -> None:
    """Adds to section `name` of `path` the commit and date of the run that just wrote it."""
    text = open(path, encoding="utf-8").read()
    begin, end = markers(name)
    a, b = text.find(begin), text.find(end)
    if a < 0 or b < a:
        raise SystemExit(f"results: the run wrote no section {name} into {path}")
    inner = text[a + len(begin):b].lstrip("\n")
    lines = [l for l in inner.split("\n") if not l.startswith("<!-- at commit ")]
    block = f"{begin}\n<!-- at commit {when} -->\n" + "\n".join(lines).rstrip("\n") + f"\n{end}"
    new = splice(text, name, block)
    tmp = path + f".{os.getpid()}.tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(new)
    os.replace(tmp, path)


def commit() -> str:
    """The commit, with a note when the tree has uncommitted changes, and today's date."""
    head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                          text=True).stdout.strip() or "unknown"
    # the results file itself is being rewritten: not a change of the code measured
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no", "--", ".",
                            f":!{RESULTS}"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    note = " with uncommitted changes" if dirty else ""
    return f"{head}{note}, {datetime.date.today().isoformat()}"


def run(names, command, md: str) -> None:
    out = os.path.join("out", "results", names[0])
    argv = [a.replace("{md}", md).replace("{out}", out) for a in command]
    print(f"results: {' '.join(names)}: {' '.join(argv)}", flush=True)
    subprocess.run(argv, cwd=ROOT, check=True)
    when = commit()
    for name in names:
        stamp(os.path.join(ROOT, md), name, when)


def main(argv) -> None:
    if "--help" in argv or "-h" in argv:
        print(__doc__)
        return
    flags = {"--list", "--quick", "--assemble", "--extras"}
    bad = [a for a in argv if a.startswith("-") and a not in flags]
    if bad:
        raise SystemExit(f"results: unknown option(s) {', '.join(bad)}; allowed: "
                         f"{', '.join(sorted(flags))}, --help, or section names (see --list)")
    if "--list" in argv:
        for heading, names, command, expensive in sections():
            cost = "expensive" if expensive else "quick"
            print(f"{', '.join(names):<48} {cost:<9} {' '.join(command)}")
        for names, command, _ in EXTRAS:
            print(f"{', '.join(names):<48} {'extra':<9} {' '.join(command)}")
        return
    known = {n for _, names, _, _ in sections() for n in names}
    wanted = [a for a in argv if not a.startswith("--")]
    unknown = [n for n in wanted if n not in known]
    if unknown:
        raise SystemExit(f"results: unknown section(s) {', '.join(unknown)}; see --list")
    path = os.path.join(ROOT, RESULTS)
    old = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
    new = skeleton(old)
    if new != old:
        tmp = path + f".{os.getpid()}.tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(new)
        os.replace(tmp, path)
    if "--assemble" in argv:
        return
    for _, names, command, expensive in sections():
        chosen = set(names) & set(wanted) if wanted else (not expensive or "--quick" not in argv)
        if chosen:
            run(names, command, RESULTS)
    if "--extras" in argv:
        os.makedirs(os.path.join(ROOT, "out", "results"), exist_ok=True)
        for names, command, _ in EXTRAS:
            run(names, command, os.path.join("out", "results", "extras.md"))


if __name__ == "__main__":
    main(sys.argv[1:])
