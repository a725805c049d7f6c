#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The harness's rooms include one way: every quoted include in bench/ names its room
("judge/verdict.h") and points at a room below the includer's (bench/CMakeLists.txt draws the
same order). Also: no room holds more than a dozen sources.

Usage: rooms_test.py PROJECT_DIR"""
import pathlib
import re
import sys

# Each room and the rooms it may include (besides itself). Order matters only for reading.
ROOMS = {
    "support": [],
    "model": ["support"],
    "scenes": ["model", "support"],
    "box2d_ref": ["model"],
    "chipmunk_ref": ["model"],
    "box2d3": ["model", "support"],
    "engines": ["model", "support", "box2d_ref", "chipmunk_ref"],
    "index": ["engines", "model", "support"],
    "judge": ["index", "engines", "model", "support"],
    "run": ["judge", "index", "engines", "model", "support"],
    "output": ["run", "judge", "index", "engines", "model", "support", "replay"],
    "campaign": ["output", "run", "judge", "index", "engines", "scenes", "model", "support"],
    "cli": ["campaign", "output", "run", "judge", "index", "engines", "scenes", "model", "support"],
    "benchmarks": ["run", "judge", "index", "engines", "scenes", "model", "support", "box2d3"],
    "replay": [],
}
# Files a room generates into its build folder and includes by name.
GENERATED = {"engine_list.inc"}
MAX_SOURCES = 12

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def room_dir(project, room):
    top = project / room
    return top if room in ("box2d_ref", "chipmunk_ref", "box2d3") else project / "bench" / room


def check(project):
    faults = []
    for room, allowed in ROOMS.items():
        folder = room_dir(project, room)
        if not folder.is_dir():
            faults.append(f"{folder}: room {room} is missing")
            continue
        files = sorted(p for p in folder.iterdir() if p.suffix in (".h", ".cpp"))
        sources = [p for p in files if p.suffix == ".cpp"]
        if len(sources) > MAX_SOURCES:
            faults.append(f"{folder}: {len(sources)} sources, more than {MAX_SOURCES}: split the room")
        for path in files:
            text = path.read_text()
            for match in INCLUDE.finditer(text):
                name = match.group(1)
                line = text.count("\n", 0, match.start()) + 1
                where = f"{path.relative_to(project)}:{line}"
                if name in GENERATED:
                    continue
                if "/" not in name:
                    faults.append(f'{where}: #include "{name}" does not name its room')
                    continue
                target = name.split("/", 1)[0]
                if target not in ROOMS:
                    faults.append(f'{where}: #include "{name}": no room {target}')
                elif target != room and target not in allowed:
                    faults.append(f'{where}: #include "{name}" points up or across: {room} may '
                                  f'include {", ".join(allowed) or "no other room"}')
                elif not (room_dir(project, target) / name.split("/", 1)[1]).is_file():
                    faults.append(f'{where}: #include "{name}": no such file')
    for folder in sorted((project / "bench").iterdir()):
        if folder.is_dir() and any(folder.glob("*.cpp")) and folder.name not in ROOMS:
            faults.append(f"{folder}: a folder of sources that is not a room of this table")
    return faults


def self_test():
    """The check itself fails where it should: an include pointing up, one without its room, one
    to no file, and a room grown past a dozen sources."""
    import tempfile
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for room in ROOMS:
            room_dir(root, room).mkdir(parents=True, exist_ok=True)
        (root / "bench/run/runner.h").write_text("")
        (root / "bench/judge/verdict.h").write_text("")
        (root / "bench/run/ok.cpp").write_text('#include "judge/verdict.h"\n#include "run/runner.h"\n')
        assert check(root) == [], check(root)
        (root / "bench/judge/up.cpp").write_text('#include "run/runner.h"\n')
        (root / "bench/judge/flat.cpp").write_text('#include "verdict.h"\n')
        (root / "bench/judge/gone.cpp").write_text('#include "judge/gone.h"\n')
        for i in range(MAX_SOURCES):
            (root / f"bench/index/s{i}.cpp").write_text("")
        (root / "bench/index/one_more.cpp").write_text("")
        faults = check(root)
        expected = ["judge/up.cpp:1", "judge/flat.cpp:1", "judge/gone.cpp:1", "bench/index: 13"]
        for e in expected:
            assert any(e in f for f in faults), (e, faults)
        assert len(faults) == len(expected), faults


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    self_test()
    faults = check(pathlib.Path(sys.argv[1]).resolve())
    for f in faults:
        print(f)
    print(f"{len(faults)} faults" if faults else "rooms: every include points down")
    sys.exit(1 if faults else 0)


if __name__ == "__main__":
    main()
