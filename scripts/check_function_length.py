#!/usr/bin/env python3
"""Fails when a function is longer than the house allows: ~120 lines in apps/ and python/src (the
front ends), ~150 in libmassprops/src and libdynamics/src (a function that long holds two concerns). A function is a definition
that starts at column 0 (namespace scope: free functions and out-of-class members) and ends at the
next `}` at column 0. Prints the longest of each tree either way.
Usage: check_function_length.py [ROOT]"""
import os
import re
import sys

LIMITS = {"apps": 120, "python/src": 120, "libmassprops/src": 150, "libdynamics/src": 150}
START = re.compile(r"^[A-Za-z_][^;{}]*\([^;]*\)[^;]*\{\s*(//.*)?$")


def functions(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        head = line
        # A signature broken over lines: join until the line that opens the body.
        j = i
        if re.match(r"^[A-Za-z_]", line) and "(" in line and not line.rstrip().endswith(";") \
                and not line.startswith(("namespace", "struct", "class", "enum", "using", "template", "extern",
                                         "static_assert", "#")):
            while not head.rstrip().endswith("{") and j + 1 < len(lines) and j - i < 8 \
                    and not head.rstrip().endswith(";"):
                j += 1
                head += " " + lines[j].strip()
            if START.match(head) or head.rstrip().endswith("{"):
                k = j + 1
                while k < len(lines) and not lines[k].startswith("}"):
                    k += 1
                name = re.sub(r"\s+", " ", head.split("(")[0]).split(" ")[-1]
                yield name, i + 1, k - i + 1
                i = k + 1
                continue
        i += 1


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    failed = False
    for tree, limit in LIMITS.items():
        found = []
        for folder, _, files in os.walk(os.path.join(root, tree)):
            if "node_modules" in folder:
                continue
            for f in files:
                if f.endswith((".cpp", ".h")):
                    path = os.path.join(folder, f)
                    for name, line, length in functions(path):
                        found.append((length, os.path.relpath(path, root), line, name))
        found.sort(reverse=True)
        over = [x for x in found if x[0] > limit]
        longest = found[0] if found else (0, "-", 0, "-")
        print(f"{tree}: longest function {longest[3]} ({longest[1]}:{longest[2]}), {longest[0]} lines; limit {limit}")
        for length, path, line, name in over:
            print(f"  too long: {name} ({path}:{line}), {length} lines")
            failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
