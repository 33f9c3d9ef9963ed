#!/usr/bin/env python3
"""The library's folders stand in layers: a folder includes headers of its own layer or
of the layers below it, never of a layer above, and the folders of one layer form no
include cycle. Exits non-zero naming every include that breaks this.

    python3 tests/layout/check_layers.py [SOURCE_DIR]

doc/design.md ("Layers") explains the order. A forwarding header kept for one release
(its first comment says 'Forwarding header') may point anywhere.
"""
import collections
import pathlib
import re
import sys

LAYERS = [
    ["base"],
    ["particles", "grid"],
    ["materials", "shape_functions", "geometry", "boundary", "distributed"],
    ["fracture", "solver"],
    ["contact", "output", "scenes"],
    ["simulation"],
    ["app"],
]
RANK = {folder: i for i, layer in enumerate(LAYERS) for folder in layer}


def folder_of(path, root):
    parts = path.relative_to(root).parts
    return parts[2] if parts[0] == "include" else parts[1]


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    files = list((root / "source").rglob("*.cc")) + list((root / "source").rglob("*.h"))
    files += list((root / "include" / "lme_mpm").rglob("*.h"))
    problems, edges = [], collections.defaultdict(set)
    for f in sorted(files):
        text = f.read_text()
        if "// Forwarding header" in text:
            continue
        mine = folder_of(f, root)
        if mine not in RANK:
            problems.append(f"{f.relative_to(root)}: folder '{mine}' is in no layer")
            continue
        for n, line in enumerate(text.splitlines(), 1):
            m = re.match(r'#include <lme_mpm/([a-z_]+)/', line)
            if not m or m.group(1) == mine:
                continue
            theirs = m.group(1)
            if theirs not in RANK:
                problems.append(f"{f.relative_to(root)}:{n}: '{theirs}' is in no layer")
            elif RANK[theirs] > RANK[mine]:
                problems.append(f"{f.relative_to(root)}:{n}: {mine} (layer {RANK[mine]}) "
                                f"includes {theirs} (layer {RANK[theirs]}), above it")
            else:
                edges[mine].add(theirs)
    # Within a layer, no cycle between folders.
    def reaches(a, b, seen):
        return any(c == b or (c not in seen and reaches(c, b, seen | {c}))
                   for c in edges[a] if RANK[c] == RANK[a])
    for a in list(edges):
        if reaches(a, a, {a}):
            problems.append(f"folder '{a}' is part of an include cycle in its layer")
    for p in problems:
        print(p)
    print(f"{len(files)} files, {sum(len(v) for v in edges.values())} folder links, "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
