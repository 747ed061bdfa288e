#!/usr/bin/env python3
"""The house's two rules (docs/architecture.md, issue #34), checked on the source tree:

1. No room's files include each other in a cycle. A "file" is a concept: stem.h with its stem.cpp;
   it includes what either of them includes. Any cycle within a room is reported.
2. No room holds more than 15 % of the product's C++ lines (tests, benchmarks, fuzzers and
   tools are not product).

Prints the rooms with their share; exits 1 naming what breaks a rule.
Usage: check_rooms.py [SOURCE_DIR]
"""
import pathlib
import re
import sys

MAX_SHARE = 0.15
NOT_PRODUCT = {"tests", "bench", "fuzz", "tools", "build", "out", "examples", "docs", "scenes"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def is_test(path: pathlib.Path) -> bool:
    return path.name.endswith("_test.cpp") or "testing" in path.name or path.name == "test_rigs.h"


def rooms(root: pathlib.Path):
    for folder in sorted(p for p in root.iterdir() if p.is_dir() and not p.name.startswith(".")):
        if folder.name in NOT_PRODUCT or not (folder / "CMakeLists.txt").exists():
            continue
        sources = sorted(p for p in folder.rglob("*") if p.suffix in (".h", ".cpp") and not is_test(p))
        if sources:
            yield folder.name, sources


def cycles_in(sources):
    """Cycles among the room's concepts (stem.h + stem.cpp), each reported once."""
    by_header = {p.name: p.stem for p in sources if p.suffix == ".h"}
    edges = {}
    for p in sources:
        for included in INCLUDE.findall(p.read_text(errors="replace")):
            target = by_header.get(pathlib.PurePath(included).name)
            if target and target != p.stem:
                edges.setdefault(p.stem, set()).add(target)
    found, state = [], {}

    def visit(node, trail):
        state[node] = "open"
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == "open":
                found.append(trail[trail.index(nxt):] + [nxt])
            elif nxt not in state:
                visit(nxt, trail + [nxt])
        state[node] = "done"

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    return found


def main() -> int:
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    found = list(rooms(root))
    lines = {name: sum(len(p.read_text(errors="replace").splitlines()) for p in sources) for name, sources in found}
    total = sum(lines.values())
    problems = []
    for name, sources in found:
        share = lines[name] / total
        print(f"{name:12s} {lines[name]:6d} lines  {100 * share:5.1f} %")
        if share > MAX_SHARE:
            problems.append(f"{name}/ holds {100 * share:.1f} % of the product's {total} lines (at most {100 * MAX_SHARE:.0f} %)")
        for cycle in cycles_in(sources):
            problems.append(f"{name}/: files include each other in a cycle: {' -> '.join(cycle)}")
    print(f"{'total':12s} {total:6d} lines in {len(found)} rooms")
    for problem in problems:
        print("check_rooms: " + problem, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
