"""The command starts quickly: `kinelab --help` imports no command, and a command imports
only the rooms and libraries it uses.  Module lists, not times (the times are measured by
hand; see docs/command-line.md)."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import click
import pytest

from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
HEAVY = ("scipy", "sympy", "matplotlib", "pandas", "numba")


# run the command, then list every module loaded by its end (-X importtime would miss the
# modules imported through importlib, as lazy commands and names are)
_RUN = """
import atexit, sys
atexit.register(lambda: print("\\n".join(sorted(sys.modules)), file=sys.stderr))
from kinelab.cli import main
main()
"""


def imported(*args: str) -> set[str]:
    """The modules a fresh process has loaded when ``kinelab *args`` ends, in the default
    kernel mode, "auto"."""
    env = {**os.environ, "KINELAB_KERNEL": "auto"}
    done = subprocess.run([sys.executable, "-c", _RUN, *args], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return set(done.stderr.split())


def heavy(modules: set[str]) -> list[str]:
    return sorted(m for m in modules if m.split(".")[0] in HEAVY)


def test_help_imports_no_command_and_no_room():
    modules = imported("--help")
    assert heavy(modules) == []
    assert "numpy" not in modules
    assert sorted(m for m in modules if m.startswith("kinelab.") and m not in (
        "kinelab.cli", "kinelab.cli._group", "kinelab.errors")) == []


def test_check_imports_no_heavy_library():
    """`kinelab check` of the demo imports none of scipy, sympy, matplotlib, pandas, numba
    (in "auto" mode a warm compile cache is not loaded for its few hundred samples)."""
    modules = imported("check", "examples/crank_rocker.toml")
    assert heavy(modules) == []
    assert "kinelab.cli._analyze" in modules and "kinelab.cli._draw" not in modules


@pytest.mark.parametrize("limit", [20, 30, 45, 59, 72, 120, 400])
def test_help_lists_each_command_as_its_own_help_says(limit):
    """The sentence each command is registered with gives the short help that the command's
    own help gives, at any width of the list."""
    for name in main.commands:
        command = main.commands[name]
        stand_in = click.Command(name, help=main.commands.summary(name))
        assert stand_in.get_short_help_str(limit) == command.get_short_help_str(limit), name


def test_commands_load_when_looked_up():
    """Every registered command is found by its name, with its own name."""
    names = list(main.commands)
    assert len(names) == len(set(names)) == len(main.commands)
    for name in names:
        assert main.get_command(click.Context(main), name).name == name
