"""The rooms of the package import only rooms below them (DESIGN.md's table, top to bottom)."""
import ast
from pathlib import Path

import pytest

import kinelab

ROOMS = ("cli", "web", "plot", "gallery", "io", "sweep", "verify", "derive", "synthesis", "dynamics", "cams", "gears", "kinematics",
         "spatial", "structure", "mechanisms", "solvers", "model", "errors")
PACKAGE = Path(kinelab.__file__).parent
# Known exceptions, each a lazy import inside one convenience method:
# Mechanism.pose (the model at one input) calls kinematics.pose; a cam joint given its
# program as plain data (Mechanism.from_dict) makes it a kinelab.cams.MotionProgram;
# mechanisms.spherical_fourbar (the catalogue's constructor) builds a spatial.SphericalFourBar.
ALLOWED = {"model/_mechanism.py": {"kinematics", "cams"}, "mechanisms/_spherical.py": {"spatial"}}


def _imported_rooms(path: Path) -> set[str]:
    rooms = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                 else [node.module or ""] if isinstance(node, ast.ImportFrom) and node.level == 0
                 else [])
        for name in names:
            parts = name.split(".")
            if parts[0] == "kinelab" and len(parts) > 1 and parts[1] in ROOMS:
                rooms.add(parts[1])
            elif parts == ["kinelab"] and isinstance(node, ast.ImportFrom):
                rooms.update(a.name for a in node.names if a.name in ROOMS)
    return rooms


@pytest.mark.parametrize("room", [r for r in ROOMS if (PACKAGE / r).is_dir()])
def test_a_room_imports_only_rooms_below_it(room):
    above = set(ROOMS[:ROOMS.index(room)])
    wrong = {}
    for f in sorted((PACKAGE / room).rglob("*.py")):
        name = f.relative_to(PACKAGE).as_posix()
        bad = _imported_rooms(f) & above - ALLOWED.get(name, set())
        if bad:
            wrong[name] = sorted(bad)
    assert not wrong, f"{room} imports rooms above it: {wrong}"
