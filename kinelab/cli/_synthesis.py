"""``kinelab synth TASK``: dimensional synthesis from a task file.

A click command of the main ``kinelab`` group.  It reads a TOML task file (the format is in
``docs/synthesis.md``) and solves it with :func:`kinelab.io.load_task` and
:func:`~kinelab.io.solve_task`,
prints a table of the linkages found and writes each as a model file (``kinelab.io``) with
a figure, all in the task's units (SI with ``--si``).  Everything is computed before anything
is written, and the files are written as one set (:func:`kinelab._files.outputs`): all of
them, or none; the group turns kinelab errors into one-line messages with exit status 2.
"""
from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

import click
import numpy as np

from kinelab.cli._main import DEGREES, LANG, SI, VERIFY, output_units, report
from kinelab.cli._words import SAID, formatted
from kinelab.plot._words import kind_words
from kinelab.errors import shown_path
from kinelab.io import Task, load_task, solve_task, task_summary
from kinelab.model import Units

__all__ = ["synth"]


def _figures(task: Task, sols: list, extra: dict, u: Units, lang: str = "en") -> dict[str, bytes]:
    """The figures of a solved task, PNG bytes by file name, in ``u`` and ``lang``."""
    from kinelab import plot
    from kinelab.cli._draw import _agg
    plt = _agg()

    out: dict[str, bytes] = {}

    def grab(name, ax):
        buf = io.BytesIO()
        ax.figure.savefig(buf, format="png", dpi=120, bbox_inches="tight")
        plt.close(ax.figure)
        out[name] = buf.getvalue()

    if task.kind in ("crank-rocker", "quick-return"):
        for i, s in enumerate(sols, 1):
            grab(f"solution_{i}.png", plot.limit_positions(s, units=u, lang=lang))
        return out
    if task.positions is not None:
        grab("positions.png", plot.prescribed_positions(task.positions, units=u, lang=lang))
    if extra.get("five"):
        grab("curves.png", plot.five_positions(task.positions, sols, units=u, lang=lang))
    if "curves" in extra:
        grab("curves.png", plot.burmester_curves(extra["curves"], positions=task.positions,
                                                 solutions=sols, units=u, lang=lang))
    for i, s in enumerate(sols, 1):
        if task.kind == "function":
            grab(f"solution_{i}.png", plot.structural_error(s, lang=lang))
        elif task.kind == "path":
            grab(f"solution_{i}.png", plot.path_solution(s, units=u, lang=lang))
        else:
            grab(f"solution_{i}.png", plot.motion_solution(s, units=u, lang=lang))
    return out


def _fmt_xy(v, u: Units, lang: str = "en"):
    """A point in ``u``, ``(1.0000, 2.0000)``; in Portuguese ``(1,0000; 2,0000)``."""
    between = "; " if lang == "pt" else ", "     # a decimal comma's list: with ;
    return "(" + between.join(formatted(c, ".4f", lang)
                              for c in u.convert(np.asarray(v), "m")) + ")"


@click.command("synth")
@click.argument("task_file", metavar="TASK", type=click.Path(exists=True, dir_okay=False))
@click.option("--out", "out_dir", type=click.Path(file_okay=False), default=None,
              help="Directory for the model files and figures [default: TASK's name + "
                   "'_solutions', beside it].")
@click.option("--figures/--no-figures", default=True, show_default=True,
              help="Write a figure of each solution (and of the positions and curves).")
@click.option("--json", "as_json", is_flag=True, help="Print the summary as JSON.")
@SI
@DEGREES
@LANG
@VERIFY
def synth(task_file: str, out_dir: str | None, figures: bool, as_json: bool, si: bool,
          degrees: bool, lang: str, verify_: bool) -> None:
    """Dimensional synthesis from the TOML task file TASK: a four-bar through positions,
    a function or path generator, a crank-rocker for a swing and a time ratio, a quick
    return.

    Writes each linkage found as a model file solution_<i>.toml and, unless --no-figures,
    a figure solution_<i>.png, with summary.json: all in the task's units (--si for m and
    rad), as the printed table.  With --verify, each linkage is analysed again at every task
    point and compared with the task and with the table; the certificate is printed last
    (with --json, it is in the JSON) and written as certificate.json and in summary.json.
    """
    from kinelab._files import atomic_write, outputs, safe_name
    from kinelab.io import to_toml

    task = load_task(task_file)
    u = output_units(task.units, si, degrees)
    sols, extra = solve_task(task, verify=verify_)
    summary = task_summary(task, sols, extra, u)
    certificate = extra.get("certificate")
    rows = summary["solutions"]
    files: dict[str, bytes | str] = {}
    for i, s in enumerate(sols, 1):
        files[f"solution_{i}.toml"] = to_toml(s.model, units=u)
    if certificate is not None:
        summary["certificate"] = certificate.to_dict()
        files["certificate.json"] = certificate.to_json()
    # the summary holds no inf or NaN (task_summary writes null): allow_nan=False keeps it so
    files["summary.json"] = json.dumps(summary, indent=2, allow_nan=False)
    if figures and sols:
        files.update(_figures(task, sols, extra, u, lang))
    out = Path(out_dir) if out_dir else Path(task_file).with_name(
        safe_name(Path(task_file).stem) + "_solutions")
    with outputs(out) as written:        # every file, or none
        for name, content in files.items():
            binary = isinstance(content, bytes)
            written.write(name, lambda p, c=content, b=binary: atomic_write(
                p, lambda f: f.write(c), binary=b))
    if as_json:
        click.echo(files["summary.json"])
        if certificate is not None and not certificate.passed:
            click.get_current_context().exit(1)
        return
    said = SAID[lang]

    def f(v, spec):
        return formatted(v, spec, lang)
    what = task.kind if task.kind in ("crank-rocker", "quick-return") else f"{task.kind} generation"
    click.echo(said["solved"].format(name=task.name, what=kind_words(what, lang), n=len(sols))
               + (f" ({summary['reason']})" if summary["reason"] else ""))
    for s, row in zip(sols, rows):
        head = f"  {row['solution']}: "
        if "mechanism" in row:
            click.echo(head + _design_line(row, u, lang))
            continue
        if hasattr(s, "A0"):
            head += (f"A0 {_fmt_xy(s.A0, u, lang)} B0 {_fmt_xy(s.B0, u, lang)} "
                     f"A1 {_fmt_xy(s.A1, u, lang)} B1 {_fmt_xy(s.B1, u, lang)} {u.length}, ")
        else:
            head += ", ".join(f"{k} {f(v, '.4f')}" for k, v in row["lengths"].items()) + \
                f" {u.length}, "
        if "transmission_limit" in row:
            head += _transmission(row, u, lang) + ", "
        if "rms_error" in row:
            head += f"{said['rms error']} {_error(row['rms_error'], u.length, lang)}, "
        if "max_structural_error" in row:
            head += f"{said['max structural error']} {_error(row['max_structural_error'], '', lang)}, "
        head += f"{kind_words(s.grashof.kind, lang)}, {kind_words(s.state, lang)}"
        click.echo(head)
    click.echo(said["wrote files"].format(n=len(files), path=shown_path(out)))
    if certificate is not None:
        report(certificate)


def _transmission(row: dict[str, Any], u: Units, lang: str = "en") -> str:
    """The smallest transmission angle of a linkage over its travel, and whether it meets the
    task's limit, in ``u`` and ``lang``."""
    said = SAID[lang]
    limit = said["limit"].format(limit=formatted(row["transmission_limit"], ".3g", lang),
                                 unit=u.angle)
    if "min_transmission_angle" not in row:
        return said["not measured"].format(limit=limit)
    verdict = "meets" if row["meets_transmission_limit"] else "below"
    return said[verdict].format(mu=formatted(row["min_transmission_angle"], ".3g", lang),
                                unit=u.angle, limit=limit)


def _error(value: float | None, unit: str = "", lang: str = "en") -> str:
    """An error for the table; None (null in the summary) where the linkage cannot close at
    some sample, so that the error there has no bound."""
    if value is None:
        return SAID[lang]["unbounded"]
    return formatted(value, ".3g", lang) + (f" {unit}" if unit else "")


def _design_line(row: dict[str, Any], u: Units, lang: str = "en") -> str:
    """One printed line of a crank-rocker or quick return, in ``u`` and ``lang``."""
    said = SAID[lang]

    def f(v, spec):
        return formatted(v, spec, lang)
    parts = [kind_words(row["mechanism"], lang),
             ", ".join(f"{k} {f(v, '.4f')}" for k, v in row["lengths"].items()) + f" {u.length}"]
    if "swing" in row:
        parts.append(f"{said['swing']} {f(row['swing'], '.6g')} {u.angle}")
    if "stroke" in row:
        parts.append(f"{said['stroke']} {f(row['stroke'], '.6g')} {u.length}")
    parts.append(f"{said['time ratio']} {f(row['time_ratio'], '.6g')}")
    if "transmission_min" in row:
        parts.append(f"{said['min transmission']} {f(row['transmission_min'], '.3g')} {u.angle}")
    if "pivot_angle" in row:
        parts.append(f"{said['pivot angle']} {f(row['pivot_angle'], '.4g')} {u.angle}")
    return ", ".join(parts)
