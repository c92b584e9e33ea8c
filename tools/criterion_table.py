#!/usr/bin/env python3
"""Print the medians of a criterion run as a Markdown table, with ratios to a baseline.

usage: tools/criterion_table.py GROUP_PREFIX [BASELINE_ID] [--markdown FILE --section NAME]

Reads target/criterion/<group>/<id>/new/estimates.json for every group whose name starts with
GROUP_PREFIX (criterion writes '/' in group names as '_'). For each group, prints the median time
per iteration, the time per element when the benchmark declared a throughput, and the ratio to
BASELINE_ID measured in the same group (default: the id containing 'baseline').

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


def main():
    args = sys.argv[1:]
    markdown = section = None
    if "--markdown" in args:
        i = args.index("--markdown")
        markdown = args[i + 1]
        del args[i : i + 2]
    if "--section" in args:
        i = args.index("--section")
        section = args[i + 1]
        del args[i : i + 2]
    if not args or (markdown and not section):
        sys.exit(__doc__)
    prefix = args[0].replace("/", "_")
    baseline_id = args[1] if len(args) > 1 else None
    root = os.path.join("target", "criterion")
    groups = sorted(g for g in os.listdir(root) if g.startswith(prefix))
    lines = []
    print = lines.append  # noqa: A001 - collect the table, then print or write it
    print("| group | benchmark | median / iter | per element | ratio to baseline |")
    print("|---|---|---|---|---|")
    for g in groups:
        rows = {}
        for bench in sorted(os.listdir(os.path.join(root, g))):
            est = os.path.join(root, g, bench, "new", "estimates.json")
            info = os.path.join(root, g, bench, "new", "benchmark.json")
            if not os.path.exists(est):
                continue
            median = json.load(open(est))["median"]["point_estimate"]
            elements = None
            if os.path.exists(info):
                tp = json.load(open(info)).get("throughput") or {}
                elements = tp.get("Elements")
            rows[bench] = (median, elements)
        base = None
        for b in rows:
            if (baseline_id and b == baseline_id) or (not baseline_id and "baseline" in b):
                base = rows[b][0]
        for b, (median, elements) in rows.items():
            per = human(median / elements) if elements else ""
            ratio = (f"{median / base:.2f}x" if median >= base else f"{median / base:.4f}x ({base / median:.2f}x faster)") if base else ""
            print(f"| {g} | {b} | {human(median)} | {per} | {ratio} |")
    table = "\n".join(lines)
    builtins.print(table)
    if markdown:
        command = " ".join(["python3", "tools/criterion_table.py"] + sys.argv[1:])
        write_section(markdown, section, f"<!-- written by `{command}` after `cargo bench` -->\n\n{table}\n")


if __name__ == "__main__":
    main()
