#!/usr/bin/env python3
"""Convert OpenQMC's Sobol' blue-noise tables to little-endian u32 binaries.

Input : include/oqmc/data/sobol/keys.txt and ranks.txt from OpenQMC commit
        294d65627f667b668373250a751862232cf21d65 (one C literal per line,
        e.g. "0x818a1c22U,"; 65536 lines each; these are #included verbatim
        into bntables::sobol::keyTable / rankTable in include/oqmc/bntables.h).
Output: sobol_keys.bin and sobol_ranks.bin, 65536 * 4 bytes each, element i of
        the C++ array at byte offset 4*i, little-endian.

Usage (from /work/scratch/openqmc):
    python3 convert.py upstream/include/oqmc/data/sobol .
"""

import re
import struct
import sys

LITERAL = re.compile(r"^0x([0-9a-fA-F]{1,8})[uU]?,?$")
SIZE = 1 << 16  # bntables::size = 1 << (xBits + yBits), xBits = yBits = 8


def parse(path):
    values = []
    with open(path, "r", encoding="ascii") as f:
        for lineno, line in enumerate(f, 1):
            line = line.strip()
            if not line:
                continue
            m = LITERAL.match(line)
            if not m:
                raise ValueError(f"{path}:{lineno}: unexpected line {line!r}")
            values.append(int(m.group(1), 16))
    if len(values) != SIZE:
        raise ValueError(f"{path}: {len(values)} values, expected {SIZE}")
    return values


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else "upstream/include/oqmc/data/sobol"
    dst = sys.argv[2] if len(sys.argv) > 2 else "."
    for name in ("keys", "ranks"):
        values = parse(f"{src}/{name}.txt")
        with open(f"{dst}/sobol_{name}.bin", "wb") as f:
            f.write(struct.pack(f"<{len(values)}I", *values))
        print(f"sobol_{name}.bin: {len(values)} u32, max 0x{max(values):08x}")


if __name__ == "__main__":
    main()
