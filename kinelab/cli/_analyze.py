"""``kinelab analyze`` and ``kinelab check``."""
from __future__ import annotations

import dataclasses
import math

import click
import numpy as np

from kinelab import io, kinematics, solvers, verify
from kinelab._files import outputs
from kinelab.cli._format import configuration_text, summary_text
from kinelab.cli._main import (CHANGE_POINTS, DEGREES, SI, VERIFY, certificate_path, errors_from,
                               light_work, output_path, output_units, parse_inputs, read_model,
                               report, stem, sweep)
from kinelab.io._modelfile import MAX_SAMPLES
from kinelab.errors import AssemblyError, KinelabError, ModelError, shown_path
from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._columns import INPUT_SI_UNITS, table_width

__all__ = ["analyze", "check"]

MODEL = click.argument("model", type=click.Path(dir_okay=False))
SAMPLES = click.option("--samples", type=click.IntRange(2, MAX_SAMPLES), default=None,
                       help="Samples per input, instead of the file's.")


def summarise(mf, sol):
    o = mf.outputs
    with errors_from(mf):
        s = io.summary(sol, report=o.report or None, transmission=o.transmission or None,
                       time_ratio=o.time_ratio)
    if s.reachable and not s.full_turn and kinematics.plan(mf.mechanism).input_kinds == ("angle",):
        # limit positions by the swept range, not a whole turn away from it
        middle = 0.5 * sum(s.input_range[0])
        s = dataclasses.replace(s, reachable=tuple(solvers.turn_intervals(s.reachable, middle)))
    return s


def missing_time_ratio(mf, s, units) -> str | None:
    """Why the time ratio the file asks for is not in the summary, in one line (input
    values in ``units``)."""
    output = mf.outputs.time_ratio
    if s is None or not output or s.quick_return is not None:
        return None
    try:
        kinematics.time_ratio(mf.mechanism, output)
    except AssemblyError as exc:
        spans = " and ".join(f"[{units.convert(a, 'rad'):.6g}, {units.convert(b, 'rad'):.6g}]"
                             for a, b in s.reachable or exc.reachable)
        return (f"time ratio of {output}: none; {mf.mechanism.input_names[0]} cannot turn a full "
                f"turn (it reaches only {spans} {units.unit('rad')})")
    except KinelabError as exc:
        return f"time ratio of {output}: none; " + str(exc).removeprefix("time_ratio: ")
    return None


@click.command()
@MODEL
@click.option("--out", "-o", "out", default=None, metavar="PATH",
              help="Directory (the table is named after the model) or file name; default: "
                   "the current directory.")
@click.option("--format", "fmt", type=click.Choice(io.RESULT_FORMATS), default=None,
              help="Table format (default: from the file name, else csv).")
@SAMPLES
@SI
@DEGREES
@click.option("--at", "at", default=None, metavar="VALUE",
              help="Print one configuration in full instead of sweeping: the input value in "
                   "the file's unit, or with a unit (30deg, 0.5rad, 12mm); comma-separated for "
                   "several inputs.")
@click.option("--speed", "speed", default=None, metavar="VALUE",
              help="Input speed for this run, instead of the file's: in the file's unit per "
                   "second, or with a unit (60deg, 1rad, 12mm: per second); comma-separated "
                   "for several inputs.")
@CHANGE_POINTS
@click.option("--quiet", "-q", is_flag=True, help="Do not print the summary.")
@VERIFY
def analyze(model, out, fmt, samples, si, degrees, at, speed, change_points, quiet, verify_):
    """Sweep MODEL's input range and write one row per sample: inputs; every link's angle,
    omega, alpha; every slide and its rates; every point's x, y, vx, vy, ax, ay; K and L of
    each; det J and the singular flag.  Prints a summary.  Results are in the file's units
    (--si for m and rad), each column named item.quantity[unit].  With --verify, every
    number is computed again by independent routes and the certificate is printed last and
    written beside the table."""
    mf = read_model(model)
    if mf.mechanism.space == "spherical":
        if at is not None or speed is not None or verify_ or change_points != "smooth":
            raise click.UsageError("a spherical four-bar is swept over its input range; "
                                   "--at, --speed, --change-points and --verify are for "
                                   "planar models")
        _analyze_spherical(mf, model, out, fmt, samples, output_units(mf.units, si, degrees),
                           quiet)
        return
    if speed is not None:
        mf = with_speeds(mf, parse_inputs(speed, mf, "--speed", rate=True))
    light_work(mf, samples)
    m = mf.mechanism
    units = output_units(mf.units, si, degrees)
    if at is not None:
        sol = configuration(mf, at, change_points)
        click.echo(configuration_text(sol, units))
        if verify_:
            report(verify.certify(sol))
        return
    path = output_path(out, stem(model), fmt or "csv")
    kind = io.result_format(path, fmt)       # before the sweep, which can be long
    check_table_size(mf, samples, kind)
    sol = sweep(mf, samples, change_points=change_points)
    s = None if quiet else summarise(mf, sol)
    certificate = verify.certify(sol) if verify_ else None
    with outputs(path.parent) as files:      # the table and its certificate, or neither
        written = files.write(path.name, lambda p: io.write_results(sol, p, format=kind,
                                                                    units=units))
        if certificate is not None:
            proof = files.write(certificate_path(written).name, certificate.to_json)
    if s is not None:
        click.echo(summary_text(s, units))
        note = missing_time_ratio(mf, s, units)
        if note:
            click.echo(note)
    told = f"{kind.upper()} as --format says, whatever the name; " if (
        written.suffix.lower() != f".{kind}") else ""
    click.echo(f"wrote {shown_path(written)} ({told}{sol.N} rows, {len(sol.columns())} columns)")
    if certificate is not None:
        click.echo(f"wrote {shown_path(proof)}")
        report(certificate)


def _spherical_linkage(mf: io.ModelFile):
    from kinelab.spatial import SphericalFourBar
    with errors_from(mf):
        return SphericalFourBar.from_mechanism(mf.mechanism)


def _spherical_span(mf: io.ModelFile, linkage) -> tuple[float, float]:
    """The input range to sweep (rad): the file's, else a full turn or the first reachable
    interval; refused when it goes where the loop does not close."""
    units = mf.units
    reach = linkage.reachable_inputs()
    rng = mf.mechanism.inputs[0].range
    if rng is None:
        if not reach:
            with errors_from(mf, "spherical"):
                raise ModelError("the loop closes at no input angle; check the arcs")
        return (0.0, 2 * math.pi) if reach == [(-math.pi, math.pi)] else reach[0]
    lo, hi = rng
    q = np.linspace(lo, hi, 721)
    if not linkage.positions(q).assembled.all():
        spans = ", ".join(f"[{units.convert(a, 'rad'):.6g}, {units.convert(b, 'rad'):.6g}]"
                          for a, b in reach) or "nothing"
        with errors_from(mf, "inputs[0].range"):
            raise ModelError(f"[{units.convert(lo, 'rad'):.6g}, {units.convert(hi, 'rad'):.6g}] "
                             f"{units.unit('rad')} goes where the spherical four-bar does not "
                             f"assemble; it reaches {spans} {units.unit('rad')}; narrow the range")
    return lo, hi


def _analyze_spherical(mf, model, out, fmt, samples, units, quiet) -> None:
    """``analyze`` of a spherical four-bar: kinelab.spatial sweeps it; the table has the
    angles, rates, K and L of coupler and rocker over the input."""
    from kinelab.io._spherical import spherical_columns, write_spherical_results
    from kinelab.io._modelfile import DEFAULT_SAMPLES

    linkage = _spherical_linkage(mf)
    lo, hi = _spherical_span(mf, linkage)
    n = samples or (mf.samples[0] if mf.samples else DEFAULT_SAMPLES)
    inp = mf.mechanism.inputs[0]
    path = output_path(out, stem(model), fmt or "csv")
    kind = io.result_format(path, fmt)
    if kind not in ("csv", "json"):
        raise click.UsageError(f"a spherical four-bar's table is written as csv or json, "
                               f"not {kind}")
    sol = linkage.analyze(np.linspace(lo, hi, n), inp.speed, inp.acceleration,
                          unreachable="mask")
    with outputs(path.parent) as files:
        written = files.write(path.name, lambda p: write_spherical_results(
            sol, p, format=kind, units=units))
    if not quiet:
        a = units.unit("rad")

        def ang(v):
            return f"{units.convert(v, 'rad'):.6g}"
        click.echo(f"spherical four-bar: arcs ground {ang(linkage.alpha1)}, crank "
                   f"{ang(linkage.alpha2)}, coupler {ang(linkage.alpha3)}, rocker "
                   f"{ang(linkage.alpha4)} {a}; branch {linkage.branch}; "
                   f"{linkage.grashof().kind}")
        t4 = sol.theta4[sol.assembled]
        click.echo(f"rocker: {ang(np.min(t4))} to {ang(np.max(t4))} {a}; "
                   f"K4 from {np.nanmin(sol.K4):.6g} to {np.nanmax(sol.K4):.6g}; "
                   f"{int(sol.singular.sum())} singular sample(s)")
    told = f"{kind.upper()} as --format says, whatever the name; " if (
        written.suffix.lower() != f".{kind}") else ""
    click.echo(f"wrote {shown_path(written)} ({told}{len(sol.theta2)} rows, "
               f"{len(spherical_columns(sol))} columns)")


def _check_spherical(mf: io.ModelFile) -> None:
    """The spherical four-bar's lines of ``check``: arcs, Grashof class on the sphere,
    reachable input, input and output limits, in the file's units."""
    linkage = _spherical_linkage(mf)
    u = mf.units
    a = u.unit("rad")

    def ang(v):
        return f"{u.convert(v, 'rad'):.6g}"
    click.echo(f"spherical four-bar: arcs ground {ang(linkage.alpha1)}, crank "
               f"{ang(linkage.alpha2)}, coupler {ang(linkage.alpha3)}, rocker "
               f"{ang(linkage.alpha4)} {a}; branch {linkage.branch}")
    g = linkage.grashof()
    click.echo(f"Grashof on the sphere: {g.kind} (margin (p + q) - (s + l) = "
               f"{ang(g.margin)} {a}" + (f", with axes {', '.join(g.reversed_axes)} reversed"
                                         if g.reversed_axes else "") + ")")
    reach = linkage.reachable_inputs()
    click.echo("input reaches: " + (", ".join(f"[{ang(x)}, {ang(y)}]" for x, y in reach)
                                    + f" {a}" if reach else "nothing"))
    limits = linkage.input_limits()
    click.echo("input limits (coupler and rocker in line): " + (
        ", ".join(ang(x) for x in limits) + f" {a}" if limits else "none, the crank turns fully"))
    stops = linkage.output_limits()
    click.echo("rocker stops (crank and coupler in line): " + (", ".join(
        f"θ2 = {ang(t2)}, θ4 = {ang(t4)}" for t2, t4 in stops) + f" {a}" if stops else "none"))
    _spherical_span(mf, linkage)


def check_table_size(mf: io.ModelFile, samples: int | None, kind: str) -> None:
    """Refuse, before the sweep, a table too large to write as ``kind`` in about 30 s."""
    from kinelab.io._results import table_too_large
    with errors_from(mf):
        width = table_width(kinematics.plan(mf.mechanism))
    problem = table_too_large(kind, mf.sample_count(samples), width)
    if problem:
        raise ModelError(f"{'--samples' if samples is not None else 'inputs.samples'}: {problem}; "
                         "or write Parquet (--format parquet)",
                         source=None if samples is not None else mf.source)


def configuration(mf: io.ModelFile, at: str, change_points: str = "smooth") -> KinematicSolution:
    """The file's mechanism at the input typed in ``--at``, at the file's input speeds and
    accelerations; a singular configuration is flagged, not refused."""
    m = mf.mechanism
    q = parse_inputs(at, mf)
    M = len(m.inputs)
    qd = np.array([i.speed for i in m.inputs]) if M > 1 else m.inputs[0].speed
    qdd = np.array([i.acceleration for i in m.inputs]) if M > 1 else m.inputs[0].acceleration
    with errors_from(mf, "--at"):
        return kinematics.analyze(m, q, qd, qdd, at_singular="flag", at_change_point=change_points)


def with_speeds(mf, qd) -> io.ModelFile:
    """The model file with its inputs' speeds replaced by ``qd`` (SI, one per input)."""
    m = mf.mechanism
    inputs = tuple(dataclasses.replace(i, speed=float(v))
                   for i, v in zip(m.inputs, np.atleast_1d(qd)))
    return dataclasses.replace(mf, mechanism=dataclasses.replace(m, inputs=inputs))


@click.command()
@MODEL
@SI
@DEGREES
@click.option("--lang", type=click.Choice(("en", "pt")), default="en", show_default=True,
              help="Language of the lines on singular positions (toggles, dead centres).")
def check(model, si, degrees, lang):
    """Validate MODEL, assemble it at its sketch, and report its mobility, the reachable
    input range and its singular positions over the input range: the toggles (det J = 0)
    and the dead centres of each reported output (K = 0); with several inputs, whether
    det J = 0 is reached over the box of their ranges and a few of the points found; in the
    file's units, or SI with --si.  Exit status 2 when something is wrong.

    A spherical or spatial model is checked for what it describes: its mobility, counted
    and exact (with the reason they differ, as for the overconstrained linkages of Sarrus
    and Bennett), one input per degree of freedom; kinelab.spatial analyses its motion."""
    mf = read_model(model)
    if mf.mechanism.space != "planar":
        _check_spatial(mf, model)
        return
    light_work(mf)
    m = mf.mechanism
    units = output_units(mf.units, si, degrees)
    with errors_from(mf):
        p = kinematics.plan(m)
    click.echo(f"{shown_path(model)}: {m.name}: {len(m.points)} points, {len(m.links)} links, "
               f"{len(m.joints)} joints, {len(m.inputs)} input(s); units {mf.units.length}, "
               f"{mf.units.angle}")
    mobility = _mobility(m)
    click.echo(f"mobility: {len(m.inputs)} degree(s) of freedom at the sketch, one per input"
               + (f"; {mobility}" if mobility else ""))
    if mf.assembly is not None:
        moved = mf.assembly.moved
        click.echo("assembled from the sketch with the links' lengths: " + (", ".join(
            f"{n} moved {units.convert(d, 'm'):.4g} {units.unit('m')}" for n, d in moved.items())
            if moved else "no point moved"))
        if mf.assembly.switched:
            click.echo("the sketch's assembly mode does not close at its inputs: assembled in "
                       "the other mode of " + ", ".join(mf.assembly.switched))
    click.echo("assembles at the sketch, solved as: " + "; ".join(
        s.label for s in p.steps if s.kind not in ("locked", "placed")))
    si_unit = [INPUT_SI_UNITS[k] for k in p.input_kinds]
    click.echo("sketch: " + ", ".join(f"{n} = {units.convert(q, u):.6g} {units.unit(u)}"
                                      for n, q, u in zip(m.input_names, p.q_sketch, si_unit)))
    if len(m.inputs) == 1:
        with errors_from(mf):
            ranges = kinematics.reachable_ranges(m)
        full = kinematics.turns_fully(m, ranges)
        u = si_unit[0]
        if full:
            click.echo(f"reachable: {m.input_names[0]} turns fully")
        else:
            click.echo(f"reachable: {m.input_names[0]} in " + ", ".join(
                f"[{units.convert(lo, u):.6g}, {units.convert(hi, u):.6g}] {units.unit(u)}"
                for lo, hi in ranges) + " (its limit positions)")
        _check_range(mf, ranges, full, u)
    with errors_from(mf, "inputs"):
        q, qd, qdd = mf.sample_inputs(min(mf.samples or (361,)))
        status = kinematics.assembly_status(m, q)      # a few bytes a sample, whatever the model
        if not status.assembled.all():                 # the analysis says where and why
            kinematics.analyze(m, q[~status.assembled][:1])
    _probe_loads(mf, q, qd)
    n_sing = int(status.singular.sum())
    click.echo(f"sweep: {len(q)} samples assemble" + (f", {n_sing} singular" if n_sing else
                                                      ", none singular"))
    for line in singular_positions(mf, units, lang):
        click.echo(line)
    click.echo("ok")


def singular_positions(mf: io.ModelFile, units, lang: str = "en") -> list[str]:
    """The lines of ``check`` on the singular positions over the input range of a one-input
    model: where det J = 0 is reached (toggles) and the dead centres (K = 0) of each output
    the file reports (else of every moving link and slide), input and output values in
    ``units``, in the language ``lang``.  With several inputs, over the box of their ranges:
    whether det J = 0 is reached there, and a few of the points found."""
    m = mf.mechanism
    words = SINGULAR_WORDS[lang]
    if len(m.inputs) > 1:
        return _singular_positions_of_several(mf, units, words)
    with errors_from(mf):
        p = kinematics.plan(m)
        lo, hi = kinematics.input_span(m)
        found = kinematics.toggles(m, lo, hi)
    u = INPUT_SI_UNITS[p.input_kinds[0]]
    name = m.input_names[0]

    def q_text(v):
        return f"{_short(units.convert(v, u))} {units.unit(u)}"
    span = f"[{_short(units.convert(lo, u))}, {_short(units.convert(hi, u))}] {units.unit(u)}"
    if found:
        parts = []
        for t in found:
            what = words[t.kind]
            if t.group in ("RRR", "RRP") and len(t.links) == 2:
                what += ": " + words[t.group].format(a=t.links[0], b=t.links[1])
            elif t.label:
                what += ": " + words["folds"].format(label=t.label)
            parts.append(f"{q_text(t.q)} ({what})")
        lines = [words["toggles"] + f"{name} = " + ", ".join(parts)]
    else:
        lines = [words["toggles"] + words["not_reached"].format(name=name, span=span)]
    report = mf.outputs.report or io.default_outputs(m)
    for output in report:
        if output in p.slide_item:
            kind, si_unit = "slide", "m"
        elif output in p.link_item and not m.link(output).ground:
            kind, si_unit = "link", "rad"
        else:
            continue                 # a point has no dead centre of its own
        with errors_from(mf, "outputs.report"):
            dc = kinematics.dead_centres(m, output, lo, hi)
        head = words["dead_" + kind].format(output=output)
        if not len(dc):
            lines.append(head + words["none"].format(name=name, span=span))
            continue
        value = words["value_" + kind]
        lines.append(head + f"{name} = " + ", ".join(
            f"{q_text(a)} ({value} = {_short(units.convert(b, si_unit))} {units.unit(si_unit)})"
            for a, b in zip(dc.q, dc.value)))
    return lines


def _singular_positions_of_several(mf: io.ModelFile, units, words: dict) -> list[str]:
    """:func:`singular_positions` of a model of several inputs."""
    m = mf.mechanism
    with errors_from(mf):
        p = kinematics.plan(m)
    if p.groups is not None:          # continuation: no sample is solved on its own
        return [words["toggles"] + words["newton_box"],
                words["dead_many"].format(count=len(m.inputs))]
    with errors_from(mf):
        locus = kinematics.toggles(m)
    si_units = [INPUT_SI_UNITS[k] for k in p.input_kinds]

    def value(v, u):
        return f"{_short(units.convert(v, u))} {units.unit(u)}"

    def point(q):
        return "(" + ", ".join(value(v, u) for v, u in zip(q, si_units)) + ")"
    box = " x ".join(f"{n} {words['in']} [{_short(units.convert(a, u))}, "
                     f"{_short(units.convert(b, u))}] "
                     f"{units.unit(u)}" for n, a, b, u in zip(m.input_names, locus.lo, locus.hi,
                                                             si_units))
    names = "(" + ", ".join(m.input_names) + ")"
    grid = " x ".join(str(n) for n in locus.samples)
    lines = []
    if locus.reached:
        kinds = {tuple(step.links): step.kind for step in p.steps}
        counts = []
        for kind in ("limit position", "change point", "touch"):
            rows = np.flatnonzero(locus.kind == kind)
            if not len(rows):
                continue
            text = f"{len(rows)} {words['many ' + kind]}"
            folds = sorted({locus.links[i] for i in rows if locus.links[i]})
            said = [words[kinds[f]].format(a=f[0], b=f[1]) for f in folds
                    if kinds.get(f) in ("RRR", "RRP") and len(f) == 2]
            counts.append(text + (": " + "; ".join(said) if said else ""))
        shown = np.unique(np.round(np.linspace(0, len(locus) - 1, min(len(locus), 4))).astype(int))
        lines.append(words["toggles"] + words["reached_box"].format(
            box=box, count=len(locus), grid=grid, kinds=", ".join(counts), names=names,
            points=", ".join(point(locus.q[i]) for i in shown)))
    elif np.isfinite(locus.nearest):
        lines.append(words["toggles"] + words["not_reached_box"].format(
            box=box, grid=grid, names=names, nearest=f"{locus.nearest:.3g}",
            at=point(locus.nearest_q)))
    else:
        lines.append(words["toggles"] + words["no_assembly_box"].format(box=box, grid=grid))
    lines.append(words["dead_many"].format(count=len(m.inputs)))
    return lines


def _short(x: float) -> str:
    """A refined value to nine figures, rounding noise at zero shown as 0."""
    x = float(f"{x:.9g}")
    return f"{0.0 if abs(x) < 1e-9 else x:.9g}"


# The words of check's lines on singular positions, one table per language: the notes'
# terms, "posição de travamento" (or de alinhamento) for det J = 0, "ponto morto" for K = 0.
SINGULAR_WORDS = {
    "en": {
        "toggles": "toggles (det J = 0, dead centres of the chain): ",
        "not_reached": "not reached for {name} in {span}",
        "limit position": "limit position",
        "change point": "change point",
        "RRR": "{a} and {b} in line",
        "RRP": "{a} perpendicular to the slide of {b}",
        "folds": "{label} singular",
        "dead_slide": "slide '{output}' dead centres (K = 0, it stops and turns back): ",
        "dead_link": "link '{output}' dead centres (K = 0, its angle stops and turns back): ",
        "none": "none for {name} in {span}",
        "value_slide": "slide",
        "value_link": "angle",
        "in": "in",
        "reached_box": "reached in {box}: {count} points found on a {grid} grid, {kinds}; "
                       "e.g. {names} = {points}",
        "not_reached_box": ("not reached in {box} (a {grid} grid; closest at {names} = {at}, "
                            "where the sine of the transmission angle is {nearest})"),
        "no_assembly_box": "not searched: the loops close nowhere on a {grid} grid of {box}",
        "newton_box": ("not searched: with several inputs they are searched for mechanisms "
                       "solved in closed form (dyads), and this one has a Newton-Raphson group"),
        "many limit position": ("limit positions (the loops stop closing; bisected along the "
                                "grid lines)"),
        "many change point": "change points (det J changes sign; bisected along the grid lines)",
        "many touch": "isolated points on the grid",
        "dead_many": ("dead centres (K = 0): found for mechanisms of one input; not searched "
                      "for {count} inputs"),
    },
    "pt": {
        "toggles": "posições de travamento (det J = 0, cadeia alinhada): ",
        "not_reached": "não atingidas para {name} em {span}",
        "limit position": "posição limite",
        "change point": "ponto de mudança de ramo",
        "RRR": "{a} e {b} alinhados",
        "RRP": "{a} perpendicular à guia de {b}",
        "folds": "{label} singular",
        "dead_slide": "pontos mortos do deslizamento '{output}' (K = 0, para e inverte o "
                      "sentido): ",
        "dead_link": "pontos mortos do membro '{output}' (K = 0, seu ângulo para e inverte o "
                     "sentido): ",
        "none": "nenhum para {name} em {span}",
        "value_slide": "deslocamento",
        "value_link": "ângulo",
        "in": "em",
        "reached_box": ("atingidas em {box}: {count} pontos encontrados numa grade de {grid}, "
                        "{kinds}; p. ex. {names} = {points}"),
        "not_reached_box": ("não atingidas em {box} (uma grade de {grid}; o mais próximo em "
                            "{names} = {at}, onde o seno do ângulo de transmissão é {nearest})"),
        "no_assembly_box": ("não procuradas: as malhas não fecham em nenhum ponto de uma grade "
                            "de {grid} de {box}"),
        "newton_box": ("não procuradas: com várias entradas, são procuradas em mecanismos "
                       "resolvidos em forma fechada (díades), e este tem um grupo resolvido "
                       "por Newton-Raphson"),
        "many limit position": ("posições limite (as malhas deixam de fechar; refinadas por "
                                "bisseção ao longo das linhas da grade)"),
        "many change point": ("pontos de mudança de ramo (det J muda de sinal; refinados por "
                              "bisseção ao longo das linhas da grade)"),
        "many touch": "pontos isolados na grade",
        "dead_many": ("pontos mortos (K = 0): procurados em mecanismos de uma entrada; não "
                      "procurados para {count} entradas"),
    },
}


def _probe_loads(mf, q, qd):
    """Evaluate the [dynamics] forces and torques on the sweep (inputs q, rates qd), at the
    times `kinelab dynamics` gives them: a law that is not finite there is reported now."""
    if not mf.mechanism.parameters.get("dynamics"):
        return          # no [dynamics] section: nothing to evaluate
    from kinelab import dynamics
    from kinelab.cli._dynamics import times
    loads = dynamics.DynamicsSetup.from_model(mf.mechanism).loads
    inp = mf.mechanism.inputs[0]
    t = times(q, inp.speed, inp.acceleration)
    with errors_from(mf):
        for item in loads.forces + loads.torques:
            item.value(t, np.reshape(q, (len(q), -1)), np.reshape(qd, (len(q), -1)))


def _check_range(mf, ranges, full, si_unit):
    """Refuse an input range that leaves the reachable ranges (said in the file's units:
    the error is about what the file says)."""
    inp = mf.mechanism.inputs[0]
    if inp.range is None or full:
        return
    lo, hi = sorted(inp.range)
    turns = [2 * math.pi * k for k in range(-3, 4)]
    if not any(a + t - 1e-9 <= lo and hi <= b + t + 1e-9 for a, b in ranges for t in turns):
        u = mf.units

        def num(v):
            return f"{u.convert(v, si_unit):.6g}"
        spans = ", ".join(f"[{num(a)}, {num(b)}]" for a, b in ranges)
        raise ModelError(f"{mf.source}: inputs[0].range: [{num(inp.range[0])}, "
                         f"{num(inp.range[1])}] {u.unit(si_unit)} goes where the mechanism does "
                         f"not assemble; it reaches {spans} {u.unit(si_unit)}; narrow the range")


def _check_spatial(mf: io.ModelFile, model: str) -> None:
    """``check`` of a spherical or spatial model: what the planar engine cannot sweep is
    counted, and its exact mobility must match its inputs."""
    from kinelab import structure

    m = mf.mechanism
    click.echo(f"{shown_path(model)}: {m.name}: {m.space}, {len(m.points)} points, "
               f"{len(m.links)} links, {len(m.joints)} joints, {len(m.inputs)} input(s); "
               f"units {mf.units.length}, {mf.units.angle}")
    with errors_from(mf):
        result = structure.mobility(m)
    for line in result.explanation.splitlines():
        click.echo(f"mobility: {line}")
    if result.exact != len(m.inputs):
        with errors_from(mf, "inputs"):
            raise ModelError(f"expected {result.exact} input(s), one per degree of freedom "
                             f"(the exact mobility at the sketch), got {len(m.inputs)}; "
                             f"{'add' if result.exact > len(m.inputs) else 'remove'} "
                             f"[[inputs]] tables")
    click.echo(f"inputs: {', '.join(m.input_names)}, one per degree of freedom")
    if m.space == "spherical" and len(m.links) == 4 and len(m.joints) == 4:
        _check_spherical(mf)
        click.echo("motion: kinelab analyze sweeps this spherical four-bar; analyse this "
                   "spherical one further with kinelab.spatial.SphericalFourBar")
    else:
        click.echo(f"motion: the kinematics engine sweeps planar models; analyse this "
                   f"{m.space} one with kinelab.spatial")
    click.echo("ok")


def _mobility(m) -> str:
    """Kutzbach-Gruebler's count, when the structure room provides it."""
    from kinelab import structure
    mobility = getattr(structure, "mobility", None)
    if mobility is None:
        return ""
    try:
        result = mobility(m)
    except KinelabError:      # the count is extra information; the check stands without it
        return ""
    return f"Kutzbach-Gruebler count {result.kutzbach_gruebler}, exact {result.exact}"
