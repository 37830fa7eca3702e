"""The ``kinelab`` command: thin, it parses, calls library functions and prints.

Each command lives in a module of this package and is registered here with one line, so a
room adds its commands with ``main.add_command(command)``.
"""
from kinelab.cli._analyze import analyze, check
from kinelab.cli._derive import derive_command
from kinelab.cli._draw import animate, plot
from kinelab.cli._dynamics import dynamics_command
from kinelab.cli._exchange import export, import_
from kinelab.cli._graphical import centres, differentiate_command, polygons
from kinelab.cli._main import main
from kinelab.cli._serve import serve
from kinelab.cli._structure import mobility, types
from kinelab.cli._sweep import atlas_command, sweep_command
from kinelab.cli._synthesis import synth

main.add_command(analyze)
main.add_command(check)
main.add_command(plot)
main.add_command(animate)
main.add_command(export)
main.add_command(import_)
main.add_command(mobility)
main.add_command(types)
main.add_command(synth)
main.add_command(dynamics_command)
main.add_command(derive_command)
main.add_command(polygons)
main.add_command(centres)
main.add_command(differentiate_command)
main.add_command(serve)
main.add_command(sweep_command)
main.add_command(atlas_command)

__all__ = ["main"]
