#!/usr/bin/env python3
"""Checks that includes point down the dependency order of docs/design.md §1:

    core ← io ← {synth, fitting} ← quake ← app ← {tools, python}

Every `#include "rockfit/…"` of a library's sources and headers is resolved to the library whose include/
folder holds the header, and must name that library itself or one below it. Exit 0 when every include points
down, 1 with one line per include that points up (file:line: what it includes and why that is not allowed).

    tools/check_include_direction.py [REPOSITORY]
"""
import pathlib
import re
import sys

# Each library: its folder, and the libraries it may include (itself included).
LIBRARIES = {
    "core": ("core", {"core"}),
    "io": ("io", {"core", "io"}),
    "synth": ("io/synth", {"core", "io", "synth"}),
    "fitting": ("fitting", {"core", "io", "fitting"}),
    "quake": ("fitting/quake", {"core", "io", "fitting", "quake"}),
    "app": ("tools/app", {"core", "io", "synth", "fitting", "quake", "app"}),
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"(rockfit/[^"]+)"')


def library_of_file(root, path):
    """The library a source file belongs to: the longest library folder that holds it."""
    relative = path.relative_to(root).as_posix()
    best = None
    for name, (folder, _) in LIBRARIES.items():
        if relative.startswith(folder + "/") and (best is None or len(folder) > len(LIBRARIES[best][0])):
            best = name
    return best


def library_of_header(root, header):
    for name, (folder, _) in LIBRARIES.items():
        if (root / folder / "include" / header).is_file():
            return name
    return None


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
    problems = []
    checked = 0
    for folder in ("core", "io", "fitting", "tools/app"):
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".cpp", ".hpp", ".h") or not path.is_file():
                continue
            owner = library_of_file(root, path)
            allowed = LIBRARIES[owner][1]
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                checked += 1
                target = library_of_header(root, match.group(1))
                if target is None:
                    problems.append(f"{path.relative_to(root)}:{number}: {match.group(1)} is in no library's include/")
                elif target not in allowed:
                    problems.append(f"{path.relative_to(root)}:{number}: {owner} includes {match.group(1)} of {target}, "
                                    f"which sits above it (docs/design.md §1)")
    for problem in problems:
        print(problem)
    print(f"check_include_direction: {checked} includes checked, {len(problems)} pointing up")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
