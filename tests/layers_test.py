#!/usr/bin/python3
"""The include arrows of graspcd's own files point down only (docs/design.md, "Layers").

    /usr/bin/python3 tests/layers_test.py SOURCE_DIR           check; exit 1 on a violation
    /usr/bin/python3 tests/layers_test.py SOURCE_DIR --print   also print the arrows

Reads every #include "graspcd/..." of src/graspcd/<folder>/ and app/ and checks:
  - each folder includes only the folders LAYERS allows it (a folder always includes itself);
  - no unit (a header and its .cpp, named by their stem) reaches itself through a chain of
    includes (no include cycle): when a.cpp includes b.h, b.cpp must not include a.h.
--print gives, per folder, the folders it includes with the number of #include lines, the
arrows that a review of the tree reads from the project's own files.
"""

import re
import sys
from collections import defaultdict
from pathlib import Path

# Which folders each folder of src/graspcd may include. The installed libraries (core, io,
# mujoco) include no layer above them and no peer; the study and the grasp experiment use the
# peers only through peer/'s own modules.
LAYERS = {
    "core": set(),
    "support": {"core"},
    "io": {"core"},
    "exact": {"core"},
    "mujoco": {"core", "io"},
    "version": {"core", "io"},
    "peer": {"core", "io", "study"},
    "decompose": {"core", "exact", "io", "version"},
    "grasp": {"core", "io", "mujoco", "decompose", "version"},
    "study": {"core", "support", "io", "exact", "mujoco", "grasp", "decompose", "version"},
    "app": {"core", "support", "io", "exact", "mujoco", "grasp", "decompose", "version", "study",
            "peer"},
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"(graspcd/[^"]+)"', re.M)


def project_files(root):
    """(name, folder, path) of every C++ file of src/graspcd and app/; name as it is included."""
    for path in sorted((root / "src" / "graspcd").rglob("*")):
        if path.suffix in (".h", ".cpp", ".in"):
            rel = path.relative_to(root / "src")
            yield rel.as_posix(), rel.parts[1], path
    for path in sorted((root / "app").glob("*")):
        if path.suffix in (".h", ".cpp"):
            yield "app/" + path.name, "app", path


def main(argv):
    if len(argv) not in (2, 3) or (len(argv) == 3 and argv[2] != "--print"):
        print("usage: layers_test.py SOURCE_DIR [--print]", file=sys.stderr)
        return 2
    root = Path(argv[1])
    errors = []
    edges = {}
    arrows = defaultdict(lambda: defaultdict(int))
    for name, folder, path in project_files(root):
        if folder not in LAYERS:
            errors.append(f"{name}: folder '{folder}' has no place in the layers of this test")
            continue
        includes = INCLUDE.findall(path.read_text(encoding="utf-8"))
        unit = name.rsplit(".", 1)[0]
        edges.setdefault(unit, set()).update(
            i.rsplit(".", 1)[0] for i in includes if i != "graspcd/version.h")
        edges[unit].discard(unit)
        for inc in includes:
            target = inc.split("/")[1] if inc != "graspcd/version.h" else "version"
            if target == folder:
                continue
            arrows[folder][target] += 1
            if target not in LAYERS[folder]:
                errors.append(f"{name}: includes {inc}, but {folder}/ may include only "
                              f"{', '.join(sorted(LAYERS[folder])) or 'itself'}")
    # Include cycles among the project's units (depth-first search, colours).
    state = {}

    def visit(node, stack):
        state[node] = 1
        for nxt in sorted(edges.get(node, ())):
            if state.get(nxt) == 1:
                cycle = stack[stack.index(nxt):] + [nxt] if nxt in stack else [node, nxt]
                errors.append("include cycle: " + " -> ".join(cycle))
            elif nxt not in state:
                visit(nxt, stack + [nxt])
        state[node] = 2

    for node in sorted(edges):
        if node not in state:
            visit(node, [node])
    if len(argv) == 3:
        for folder in LAYERS:
            if folder in arrows:
                out = ", ".join(f"{t} ({n})" for t, n in sorted(arrows[folder].items()))
                print(f"{folder} -> {out}")
            else:
                print(f"{folder} -> (nothing)")
    for e in errors:
        print(e)
    print(f"{len(edges)} units read, {len(errors)} layer violations")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
