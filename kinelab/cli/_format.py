"""Text for people: the summary of a sweep and one configuration in full."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from kinelab.kinematics import KinematicSolution
from kinelab.kinematics._columns import column_name
from kinelab.model import Units

if TYPE_CHECKING:       # io's summary module is only needed by the commands that print one
    from kinelab.io import Summary

__all__ = ["summary_text", "configuration_text"]


def _num(v: float, digits: int = 6) -> str:
    if not math.isfinite(v):
        return "-"
    return f"{v:.{digits}g}" if v != 0 else "0"


def _q(u: Units, values, si_units) -> str:
    """Input values (SI, one per input) with their units: ``30 deg`` or ``(30 deg, 12 mm)``;
    rounding noise about zero (a dead centre found at 1e-13 rad) shows as 0."""
    parts = [f"{_num(_snap(u.convert(v, si)))} {u.unit(si)}" for v, si in zip(values, si_units)]
    return parts[0] if len(parts) == 1 else "(" + ", ".join(parts) + ")"


def _snap(v: float) -> float:
    return 0.0 if abs(v) < 1e-9 else v


def _angle(u: Units, v: float) -> str:
    return f"{_num(u.convert(v, 'rad'))} {u.unit('rad')}"


def summary_text(s: Summary, units: Units = Units()) -> str:
    """The summary as lines of text, in ``units`` (default SI)."""
    u = units
    qname = s.inputs[0] if len(s.inputs) == 1 else "q"
    qu = s.input_units
    lines = []
    spans = ", ".join(f"{n} from {_num(u.convert(a, si))} to {_num(u.convert(b, si))} {u.unit(si)}"
                      for n, (a, b), si in zip(s.inputs, s.input_range, qu))
    lines.append(f"{s.mechanism}: {s.samples} samples, {spans}")
    if s.grashof is not None:
        g = s.grashof
        code = f"{g.barker}, {g.form}" if g.form else g.barker
        lines.append(f"Grashof: {g.kind} ({code}); s + l {'<=' if g.grashof else '>'} p + q "
                     f"by {_num(u.convert(abs(g.margin), 'm'))} {u.length}; lengths ground, "
                     "crank, coupler, rocker = "
                     + ", ".join(_num(u.convert(v, "m")) for v in s.grashof_lengths)
                     + f" {u.length}")
    if s.extremes:
        rows = [("", "min", f"at {qname}", "max", f"at {qname}")]
        for e in s.extremes:
            label = f"{e.name}[{u.unit(e.unit)}]"
            if e.full_turn:
                rows.append((label, "turns fully", "", "", ""))
                continue
            rows.append((label, _num(u.convert(e.min, e.unit)), _q(u, e.at_min, qu),
                         _num(u.convert(e.max, e.unit)), _q(u, e.at_max, qu)))
        widths = [max(len(r[i]) for r in rows) for i in range(5)]
        for r in rows:
            lines.append("  " + "  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                                         for i, (c, w) in enumerate(zip(r, widths))).rstrip())
    for t in s.transmission:
        how = " (rod from the slide's normal)" if t.from_normal else ""
        lines.append(f"transmission angle {t.links[0]}-{t.links[1]}{how}: min "
                     f"{_angle(u, t.min)} at {qname} = {_q(u, t.at_min, qu)}, "
                     f"max {_angle(u, t.max)} at {qname} = {_q(u, t.at_max, qu)}")
    if s.quick_return is not None:
        r = s.quick_return
        lines.append(f"time ratio of {r.output}: {r.ratio:.4g} (slow stroke "
                     f"{_angle(u, r.slow)}, fast stroke {_angle(u, r.fast)} of input; reverses "
                     f"at {qname} = " + ", ".join(_q(u, (v,), qu) for v in r.dead_centres) + ")")
    steps = dict.fromkeys(c.step for c in s.change_points)
    for step in steps:
        here = [c for c in s.change_points if c.step == step]
        how = ("the branch whose K and L continue" if here[0].followed == "smooth"
               else "the other branch")
        lines.append(f"change points of {step}, where its two assembly modes meet (the sweep "
                     f"goes on along {how}): {qname} = " + ", ".join(
                         _q(u, (c.q,), qu) for c in here[:8])
                     + (f" and {len(here) - 8} more" if len(here) > 8 else ""))
    if s.singular:
        lines.append("singular positions (det J = 0; their samples are left out above): at "
                     + "; ".join(f"{qname} = {_q(u, v, qu)}" for v in s.singular[:8])
                     + (f" and {len(s.singular) - 8} more" if len(s.singular) > 8 else ""))
    else:
        least, at = s.least_singularity
        lines.append(f"singular positions: none met (closest: distance {_num(least)} at {qname} = "
                     f"{_q(u, at, qu)})")
    if s.reachable is not None:
        if s.full_turn:
            lines.append(f"limit positions: none; {s.inputs[0]} turns fully")
        else:
            ends = "; ".join(f"{_q(u, (a,), qu)} and {_q(u, (b,), qu)}" for a, b in s.reachable)
            lines.append(f"limit positions of {s.inputs[0]} (it cannot go past them): {ends}")
    if s.unassembled:
        lines.append(f"{s.unassembled} samples do not assemble")
    return "\n".join(lines)


def _item(column: str) -> str:
    return column.split("[")[0].split(".")[0]


def configuration_text(sol: KinematicSolution, units: Units = Units()) -> str:
    """Every value of a one-configuration solution, one per line, grouped by item, named
    as the columns of :meth:`KinematicSolution.columns` in ``units``."""
    m = sol.mechanism
    fixed = {column_name(n) for n in (*m.ground.points, m.ground.name)}   # the frame: nothing to report
    columns = {n: v for n, v in sol.columns(units=units).items() if _item(n) not in fixed}
    width = max(len(n) for n in columns)
    lines = [f"{sol.mechanism.name}: one configuration"
             + (" (singular: det J = 0, rates undefined)" if bool(sol.singular[0]) else "")]
    last = None
    for name, values in columns.items():
        item = _item(name)
        if item != last and last is not None:
            lines.append("")
        last = item
        v = values[0]
        text = str(bool(v)).lower() if name in ("singular", "assembled") else _num(float(v), 10)
        lines.append(f"  {name.ljust(width)}  {text}")
    return "\n".join(lines)
