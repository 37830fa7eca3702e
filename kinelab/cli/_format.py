"""Text for people: the summary of a sweep and one configuration in full."""
from __future__ import annotations

import math

from kinelab.io import Summary
from kinelab.kinematics import KinematicSolution

__all__ = ["summary_text", "configuration_text"]


def _num(v: float, digits: int = 6) -> str:
    if not math.isfinite(v):
        return "-"
    return f"{v:.{digits}g}" if v != 0 else "0"


class _Units:
    """Converts SI values for display: angles to degrees when asked."""

    def __init__(self, degrees: bool):
        self.degrees = degrees

    def unit(self, unit: str) -> str:
        return unit.replace("rad", "deg") if self.degrees else unit

    def value(self, v: float, unit: str) -> float:
        return math.degrees(v) if self.degrees and unit.startswith("rad") else v

    def q(self, values, units) -> str:
        parts = [f"{_num(self.value(v, u))} {self.unit(u)}" for v, u in zip(values, units)]
        return parts[0] if len(parts) == 1 else "(" + ", ".join(parts) + ")"


def summary_text(s: Summary, *, degrees: bool = False) -> str:
    """The summary as lines of text (SI, or degrees for angles)."""
    u = _Units(degrees)
    qname = s.inputs[0] if len(s.inputs) == 1 else "q"
    lines = []
    spans = ", ".join(f"{n} from {_num(u.value(a, un))} to {_num(u.value(b, un))} {u.unit(un)}"
                      for n, (a, b), un in zip(s.inputs, s.input_range, s.input_units))
    lines.append(f"{s.mechanism}: {s.samples} samples, {spans}")
    if s.grashof is not None:
        g = s.grashof
        lines.append(f"Grashof: {g.kind} ({g.barker}); s + l {'<=' if g.grashof else '>'} p + q "
                     f"by {_num(abs(g.margin))} m; lengths ground, crank, coupler, rocker = "
                     + ", ".join(_num(v) for v in s.grashof_lengths) + " m")
    if s.extremes:
        rows = [("", "min", f"at {qname}", "max", f"at {qname}")]
        for e in s.extremes:
            unit = u.unit(e.unit)
            if e.full_turn:
                rows.append((f"{e.name} [{unit}]", "turns fully", "", "", ""))
                continue
            rows.append((f"{e.name} [{unit}]", _num(u.value(e.min, e.unit)), u.q(e.at_min, s.input_units),
                         _num(u.value(e.max, e.unit)), u.q(e.at_max, s.input_units)))
        widths = [max(len(r[i]) for r in rows) for i in range(5)]
        for r in rows:
            lines.append("  " + "  ".join(c.ljust(w) if i == 0 else c.rjust(w)
                                         for i, (c, w) in enumerate(zip(r, widths))).rstrip())
    for t in s.transmission:
        how = " (rod from the slide's normal)" if t.from_normal else ""
        lines.append(f"transmission angle {t.links[0]}-{t.links[1]}{how}: min "
                     f"{_num(u.value(t.min, 'rad'))} {u.unit('rad')} at {qname} = {u.q(t.at_min, s.input_units)}, "
                     f"max {_num(u.value(t.max, 'rad'))} {u.unit('rad')} at {qname} = {u.q(t.at_max, s.input_units)}")
    if s.quick_return is not None:
        r = s.quick_return
        lines.append(f"time ratio of {r.output}: {r.ratio:.4g} (slow stroke "
                     f"{_num(u.value(r.slow, 'rad'))} {u.unit('rad')}, fast stroke "
                     f"{_num(u.value(r.fast, 'rad'))} {u.unit('rad')} of input; reverses at {qname} = "
                     + ", ".join(u.q((v,), s.input_units) for v in r.dead_centres) + ")")
    if s.singular:
        lines.append("singular positions (det J = 0): at " + "; ".join(
            f"{qname} = {u.q(v, s.input_units)}" for v in s.singular[:8])
            + (f" and {len(s.singular) - 8} more" if len(s.singular) > 8 else ""))
    else:
        least, at = s.least_singularity
        lines.append(f"singular positions: none met (closest: distance {_num(least)} at {qname} = "
                     f"{u.q(at, s.input_units)})")
    if s.reachable is not None:
        if s.full_turn:
            lines.append(f"limit positions: none; {s.inputs[0]} turns fully")
        else:
            ends = "; ".join(f"{u.q((a,), s.input_units)} and {u.q((b,), s.input_units)}"
                             for a, b in s.reachable)
            lines.append(f"limit positions of {s.inputs[0]} (it cannot go past them): {ends}")
    if s.unassembled:
        lines.append(f"{s.unassembled} samples do not assemble")
    return "\n".join(lines)


def configuration_text(sol: KinematicSolution, *, degrees: bool = False) -> str:
    """Every value of a one-configuration solution, one per line, grouped by item."""
    m = sol.mechanism
    fixed = set(m.ground.points) | {m.ground.name}      # the frame: nothing to report
    columns = {n: v for n, v in sol.columns(degrees=degrees).items()
               if n.split(".")[0].split(" ")[0] not in fixed}
    width = max(len(n) for n in columns)
    lines = [f"{sol.mechanism.name}: one configuration"
             + (" (singular: det J = 0, rates undefined)" if bool(sol.singular[0]) else "")]
    last = None
    for name, values in columns.items():
        item = name.split(".")[0].split(" ")[0]
        if item != last and last is not None:
            lines.append("")
        last = item
        v = values[0]
        text = str(bool(v)).lower() if name in ("singular", "assembled") else _num(float(v), 10)
        lines.append(f"  {name.ljust(width)}  {text}")
    return "\n".join(lines)
