"""The ``kinelab`` command: thin, it parses, calls library functions and prints.

Each command lives in a module of this package and is registered here with one call: its
name, where it lives, and the first sentence of its help, which ``kinelab --help`` lists.
The module is imported when the command runs, so that a command loads only the rooms and
libraries it uses, and ``kinelab --help`` none of them.  (A command object can also be
added as it is, with ``main.add_command(command)``.)
"""
from kinelab.cli._group import main

main.add_lazy_command("analyze", "kinelab.cli._analyze:analyze",
                      "Sweep MODEL's input range and write one row per sample: inputs; every "
                      "link's angle, omega, alpha; every slide and its rates; every point's x, "
                      "y, vx, vy, ax, ay; K and L of each; det J and the singular flag.")
main.add_lazy_command("check", "kinelab.cli._analyze:check",
                      "Validate MODEL, assemble it at its sketch, and report its mobility, the "
                      "reachable input range and its singular positions over the input range: "
                      "the toggles (det J = 0) and the dead centres of each reported output "
                      "(K = 0); with several inputs, whether det J = 0 is reached over the box "
                      "of their ranges and a few of the points found; in the file's units, or "
                      "SI with --si.")
main.add_lazy_command("plot", "kinelab.cli._draw:plot",
                      "Write MODEL's figures: outputs' position, velocity and acceleration "
                      "against the input; K and L; coupler curves; transmission angle.")
main.add_lazy_command("animate", "kinelab.cli._draw:animate",
                      "Write an animation of MODEL moving through its sweep, with its coupler "
                      "curves traced (and, on request, its instant centres and velocities); "
                      "axes in the file's length unit (--si for m).")
main.add_lazy_command("export", "kinelab.cli._exchange:export",
                      'Export MODEL: link outlines (SVG, DXF) for drawings and cutting, a '
                      'Pyslvs expression, or the model file in other units or as JSON.')
main.add_lazy_command("import", "kinelab.cli._exchange:import_",
                      'Convert SOURCE, a Pyslvs mechanism expression or a linkage2d JSON file, '
                      'into a kinelab model file (the assembly of the drawing is kept).')
main.add_lazy_command("gallery", "kinelab.cli._gallery:gallery",
                      "List the gallery of classic mechanisms, or print NAME's history and "
                      "write its model file, NAME.toml, into --out.")
main.add_lazy_command("mobility", "kinelab.cli._structure:mobility",
                      "Mobility of MODEL: Kutzbach-Gruebler's count and the exact value, with "
                      "the reason they differ.")
main.add_lazy_command("types", "kinelab.cli._structure:types",
                      'Type synthesis: candidate architectures for a space and a mobility.')
main.add_lazy_command("synth", "kinelab.cli._synthesis:synth",
                      'Dimensional synthesis from the TOML task file TASK: a four-bar through '
                      'positions, a function or path generator, a crank-rocker for a swing and '
                      'a time ratio, a quick return.')
main.add_lazy_command("cam", "kinelab.cli._cam:cam_command",
                      "Design a disk cam from the TOML task file TASK: a motion program of rise, "
                      "dwell and return segments and a follower.")
main.add_lazy_command("dynamics", "kinelab.cli._dynamics:dynamics_command",
                      "Actuator efforts, joint reactions and shaking force of MODEL over its "
                      "inputs' sweep.")
main.add_lazy_command("derive", "kinelab.cli._derive:derive_command",
                      "Write the derivation of MODEL in the notes' notation: position equations"
                      " (one vector loop per independent circuit), their time derivative, J, Q,"
                      " det J and the singular configurations, K and L, and for a model with "
                      "masses the Gibbs-Appell / Kane terms, after Erthal, \"Mecanismos com 1 "
                      "GL: análise geral de velocidade e aceleração\" and the course notes "
                      "\"Mecanismos\".")
main.add_lazy_command("polygons", "kinelab.cli._graphical:polygons",
                      "Velocity and acceleration polygons of MODEL at one input: every point's "
                      "velocity and acceleration from the pole, every side with its parts "
                      "(normal, tangential, Coriolis, sliding), printed and drawn to scale "
                      "beside the mechanism.")
main.add_lazy_command("centres", "kinelab.cli._graphical:centres",
                      "Every instant centre of MODEL at one input, found as the notes find "
                      "them: primary centres from the joints, the others by Kennedy's theorem "
                      "in the order of the circle diagram; printed and drawn on the mechanism "
                      "beside the circle diagram.")
main.add_lazy_command("differentiate", "kinelab.cli._graphical:differentiate_command",
                      'Velocity and acceleration of a measured curve: DATA is a CSV file with a'
                      ' header row (e.g.')
main.add_lazy_command("serve", "kinelab.cli._serve:serve",
                      'Open kinelab in the browser: a local web app to draw, drag, animate and '
                      'plot MODEL (or a catalogue mechanism or example chosen on the page).')
main.add_lazy_command("sweep", "kinelab.cli._sweep:sweep_command",
                      'Metrics of every design of FAMILY (a catalogue kind such as fourbar, or '
                      'a model file) over a turn of its input, one row per design of DESIGNS '
                      '(CSV or Parquet) or of --sobol, --random or --grid; on a Dask cluster '
                      'with --scheduler.')
main.add_lazy_command("atlas", "kinelab.cli._sweep:atlas_command",
                      'Atlases of four-bar coupler curves: build one, find the designs nearest '
                      'a path.')

__all__ = ["main"]
