#!/usr/bin/env python3
"""Print the medians of a criterion run as a Markdown table, with ratios to a baseline.

usage: tools/criterion_table.py GROUP_PREFIX [BASELINE_ID] [--before SAVED] [--markdown FILE --section NAME]

Reads target/criterion/<group>/<id>/new/estimates.json (under $CARGO_TARGET_DIR when set) for every group whose name starts with
GROUP_PREFIX (criterion writes '/' in group names as '_'). For each group, prints the median time
per iteration, the time per element when the benchmark declared a throughput, and the ratio to
BASELINE_ID measured in the same group (default: the id containing 'baseline'; a comma-separated
list: the first of them that the group has).

With --before SAVED (a baseline saved by `cargo bench -- --save-baseline SAVED`, e.g. on an
earlier commit), the table shows both runs side by side: the time per element before and now,
and each run's speed relative to BASELINE_ID measured in that same run (above 1: faster than the
baseline), so that a change of the machine's speed between the runs cancels out.

With --markdown FILE the table also goes into FILE between `<!-- begin NAME -->` and
`<!-- end NAME -->` (replacing an earlier version of the section, appending it otherwise), as the
example programs write docs/results.md.
"""
import builtins
import json
import os
import sys

from markdown_section import write_section


def human(ns):
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("us", 1e3)):
        if ns >= scale:
            return f"{ns / scale:.3g} {unit}"
    return f"{ns:.3g} ns"


def read(directory):
    """(median ns per iteration, elements per iteration or None) of one run, or None."""
    est = os.path.join(directory, "estimates.json")
    if not os.path.exists(est):
        return None
    median = json.load(open(est))["median"]["point_estimate"]
    info = os.path.join(directory, "benchmark.json")
    elements = None
    if os.path.exists(info):
        tp = json.load(open(info)).get("throughput") or {}
        elements = tp.get("Elements")
    return median, elements


def main():
    args = sys.argv[1:]
    markdown = section = None
    if "--markdown" in args:
        i = args.index("--markdown")
        markdown = args[i + 1]
        del args[i : i + 2]
    before = None
    if "--before" in args:
        i = args.index("--before")
        before = args[i + 1]
        del args[i : i + 2]
    if "--section" in args:
        i = args.index("--section")
        section = args[i + 1]
        del args[i : i + 2]
    if not args or (markdown and not section):
        sys.exit(__doc__)
    prefix = args[0].replace("/", "_")
    baseline_id = args[1] if len(args) > 1 else None
    # criterion writes under the cargo target directory (CARGO_TARGET_DIR when set)
    root = os.path.join(os.environ.get("CARGO_TARGET_DIR") or "target", "criterion")
    groups = sorted(g for g in os.listdir(root) if g.startswith(prefix))
    lines = []
    print = lines.append  # noqa: A001 - collect the table, then print or write it
    if before:
        print(f"| group | benchmark | per element, {before} | speed vs baseline, {before} | per element, now | speed vs baseline, now |")
        print("|---|---|---|---|---|---|")
    else:
        print("| group | benchmark | median / iter | per element | ratio to baseline |")
        print("|---|---|---|---|---|")
    for g in groups:
        rows = {}
        old = {}
        for bench in sorted(os.listdir(os.path.join(root, g))):
            got = read(os.path.join(root, g, bench, "new"))
            if got is None:
                continue
            rows[bench] = got
            if before:
                old[bench] = read(os.path.join(root, g, bench, before))
        ids = baseline_id.split(",") if baseline_id else []
        present = [b for b in ids if b in rows]
        is_base = lambda b: b == present[0] if present else (not ids and "baseline" in b)
        base = next((rows[b][0] for b in rows if is_base(b)), None)
        if before:
            old_base = next((old[b][0] for b in old if is_base(b) and old[b]), None)
            for b, (median, elements) in rows.items():
                then = old.get(b)
                cells = []
                for run, base_of_run in ((then, old_base), ((median, elements), base)):
                    if run is None:
                        cells += ["-", "-"]
                        continue
                    per = human(run[0] / run[1]) if run[1] else human(run[0])
                    cells += [per, f"{base_of_run / run[0]:.2f}x" if base_of_run else ""]
                print(f"| {g} | {b} | " + " | ".join(cells) + " |")
            continue
        for b, (median, elements) in rows.items():
            per = human(median / elements) if elements else ""
            ratio = (f"{median / base:.2f}x" if median >= base else f"{median / base:.4f}x ({base / median:.2f}x faster)") if base else ""
            print(f"| {g} | {b} | {human(median)} | {per} | {ratio} |")
    table = "\n".join(lines)
    builtins.print(table)
    if markdown:
        command = " ".join(["python3", "tools/criterion_table.py"] + sys.argv[1:])
        # the build the run measured: the environment that changes it, as given
        given = {k: os.environ.get(k) for k in ("CARGO_TARGET_DIR", "RUSTFLAGS")}
        if given["CARGO_TARGET_DIR"]:
            given["CARGO_TARGET_DIR"] = os.path.relpath(given["CARGO_TARGET_DIR"])
        env = " ".join(f"{k}='{v}'" for k, v in given.items() if v)
        bench = f"{env} cargo bench" if env else "cargo bench"
        write_section(markdown, section, f"<!-- written by `{command}` after `{bench}` -->\n\n{table}\n")


if __name__ == "__main__":
    main()
