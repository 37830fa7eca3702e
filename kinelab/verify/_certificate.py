"""The certificate: every reported quantity, the routes that recomputed it, and how far apart
they came, each against the bound it must meet."""
from __future__ import annotations

import json
import math
import os
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Certificate", "Comparison", "Quantity"]


@dataclass(frozen=True)
class Comparison:
    """One route against the reported numbers of one quantity.

    Attributes
    ----------
    route : str
        The independent route ("Newton engine", "finite differences", ...).
    samples : int
        How many samples (or task points, polygon sides) the route checked.
    disagreement : float
        The largest difference between the route and the reported numbers, divided by the
        quantity's unit (see :class:`Quantity`): a pure number.  NaN where the route
        produced no number it should have (which fails).
    bound : float
        The largest disagreement the route may show, in the same unit.
    reason : str
        Why the bound is what it is (rounding, conditioning, truncation, tolerance).
    """

    route: str
    samples: int
    disagreement: float
    bound: float
    reason: str = ""

    @property
    def passed(self) -> bool:
        return bool(self.disagreement <= self.bound)          # NaN fails


@dataclass(frozen=True)
class Quantity:
    """A reported quantity (link angles, K, the actuators' efforts, ...) and its checks.

    Attributes
    ----------
    name : str
    reported : str
        The route the reported numbers come from ("closed form", "Kane's equations", ...).
    unit : str
        What its disagreements are relative to, in words ("the mechanism's size, 0.3 m").
    comparisons : tuple of Comparison
    """

    name: str
    reported: str
    unit: str
    comparisons: tuple[Comparison, ...]

    @property
    def routes(self) -> tuple[str, ...]:
        """The reported route, then every route that recomputed it."""
        return (self.reported,) + tuple(c.route for c in self.comparisons)

    @property
    def largest(self) -> float:
        """The largest disagreement of any route (NaN when one produced no number)."""
        return _largest(c.disagreement for c in self.comparisons)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.comparisons)

    @property
    def failures(self) -> tuple[Comparison, ...]:
        return tuple(c for c in self.comparisons if not c.passed)


@dataclass(frozen=True)
class Certificate(Mapping):
    """Proof, by independent routes, of the numbers of one result.

    A mapping from each quantity's name to ``(routes, largest_disagreement)``: the routes
    that computed it (the reported one first) and the largest disagreement between any of
    them and the reported numbers, relative to the quantity's unit.  The details -- each
    route's samples, disagreement and bound, and what was skipped and why -- are in
    :attr:`quantities` and :attr:`notes`.

    Attributes
    ----------
    subject : str
        What was checked ("kinematics of 'crank-rocker', 361 samples").
    quantities : tuple of Quantity
    notes : tuple of str
        Routes or samples left out, each with its reason.
    passed : bool
        Every route of every quantity within its bound.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    >>> cert = kl.analyze(fb, q=np.linspace(0, 2 * np.pi, 73), qd=10.0, verify=True).certificate
    >>> routes, largest = cert["K"]
    >>> routes
    ('closed form', 'Newton engine', 'symbolic derivation', 'finite differences')
    >>> cert.passed, largest < 1e-6
    (True, True)
    >>> print(cert.verdict())                        # the last of cert.lines()
    verified: 6 quantities, largest disagreement ...
    """

    subject: str
    quantities: tuple[Quantity, ...]
    notes: tuple[str, ...] = ()
    _index: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "_index", {q.name: q for q in self.quantities})

    # -- the mapping: quantity -> (routes, largest disagreement) ----------------------------
    def __getitem__(self, name: str) -> tuple[tuple[str, ...], float]:
        q = self._index[name]
        return q.routes, q.largest

    def __iter__(self) -> Iterator[str]:
        return iter(self._index)

    def __len__(self) -> int:
        return len(self._index)

    def quantity(self, name: str) -> Quantity:
        """The details of one quantity."""
        return self._index[name]

    # -- verdict ------------------------------------------------------------------------------
    @property
    def passed(self) -> bool:
        return all(q.passed for q in self.quantities)

    @property
    def largest(self) -> float:
        """The largest disagreement of the certificate (NaN when a route produced none)."""
        return _largest(q.largest for q in self.quantities)

    def verdict(self) -> str:
        """The last line: ``verified: N quantities, largest disagreement E``, or ``NOT
        verified: ...`` naming each quantity, route and bound that failed."""
        if self.passed:
            return (f"verified: {len(self)} quantities, largest disagreement "
                    f"{_number(self.largest)}")
        failed = [f"{q.name} by {c.route} ({_number(c.disagreement)} > bound "
                  f"{_number(c.bound)})" for q in self.quantities for c in q.failures]
        return "NOT verified: " + "; ".join(failed)

    def lines(self) -> list[str]:
        """The certificate as lines of text for people, the verdict last."""
        rows = [("quantity", "route", "samples", "largest", "bound")]
        for q in self.quantities:
            rows.append((q.name, f"{q.reported} (reported)", "", "", ""))
            for c in q.comparisons:
                mark = "" if c.passed else "  <- exceeds its bound"
                rows.append(("", c.route, str(c.samples), _number(c.disagreement),
                             _number(c.bound) + mark))
        out = [f"certificate: {self.subject}"] + _table(rows, left=2)
        out.append("disagreements relative to:")
        out += _table([(q.name, q.unit) for q in self.quantities], left=2)
        out += [f"note: {n}" for n in self.notes]
        out.append(self.verdict())
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())

    def __repr__(self) -> str:
        state = "passed" if self.passed else "failed"
        return f"Certificate({self.subject!r}, {len(self)} quantities, {state})"

    @classmethod
    def merge(cls, certificates: list[Certificate], subject: str, each: str) -> Certificate:
        """One certificate of several results (the runs of a batch, the linkages of a
        task): each quantity's routes with the samples of all and the worst disagreement
        of any (a failed one first), its unit that of each ``each``."""
        if len(certificates) == 1:
            one = certificates[0]
            return cls(subject, one.quantities, one.notes)
        by: dict[str, dict[str, Comparison]] = {}
        first: dict[str, Quantity] = {}
        for c in certificates:
            for q in c.quantities:
                first.setdefault(q.name, q)
                routes = by.setdefault(q.name, {})
                for new in q.comparisons:
                    old = routes.get(new.route)
                    if old is None:
                        routes[new.route] = new
                        continue
                    worse = new if _rank(new) > _rank(old) else old
                    routes[new.route] = Comparison(new.route, old.samples + new.samples,
                                                   worse.disagreement, worse.bound, worse.reason)
        quantities = tuple(Quantity(name, q.reported, f"{q.unit} (each {each}'s own)",
                                    tuple(by[name].values())) for name, q in first.items())
        notes = tuple(dict.fromkeys(n for c in certificates for n in c.notes))
        return cls(subject, quantities, notes)

    # -- plain data and files -----------------------------------------------------------------
    def to_dict(self) -> dict:
        """The certificate as plain data (strict JSON: a NaN disagreement becomes null)."""
        def num(v: float):
            return v if math.isfinite(v) else None
        return {
            "subject": self.subject, "verified": self.passed,
            "largest_disagreement": num(self.largest),
            "quantities": {q.name: {
                "reported": q.reported, "routes": list(q.routes), "unit": q.unit,
                "largest_disagreement": num(q.largest), "passed": q.passed,
                "comparisons": [{"route": c.route, "samples": c.samples,
                                 "disagreement": num(c.disagreement), "bound": num(c.bound),
                                 "reason": c.reason, "passed": c.passed}
                                for c in q.comparisons]} for q in self.quantities},
            "notes": list(self.notes), "verdict": self.verdict()}

    @classmethod
    def from_dict(cls, data: Mapping) -> Certificate:
        """The certificate :meth:`to_dict` wrote."""
        def num(v):
            return math.nan if v is None else float(v)
        quantities = tuple(
            Quantity(name, q["reported"], q["unit"], tuple(
                Comparison(c["route"], int(c["samples"]), num(c["disagreement"]),
                           num(c["bound"]), c.get("reason", "")) for c in q["comparisons"]))
            for name, q in data["quantities"].items())
        return cls(data["subject"], quantities, tuple(data.get("notes", ())))

    def to_json(self, path: str | os.PathLike | None = None) -> str:
        """The certificate as JSON text; with ``path``, also written there atomically (to a
        temporary file beside it, then renamed)."""
        text = json.dumps(self.to_dict(), indent=2, allow_nan=False) + "\n"
        if path is not None:
            from kinelab._files import atomic_write
            atomic_write(Path(path), lambda f: f.write(text))
        return text


def _largest(values) -> float:
    """The largest of ``values`` (0 for none), NaN if one is NaN: it produced no number."""
    values = list(values)
    return math.nan if any(math.isnan(v) for v in values) else max(values, default=0.0)


def _rank(c: Comparison) -> tuple:
    """Failed before passed; then the larger share of its bound (NaN: failed, first)."""
    share = c.disagreement / c.bound if c.bound > 0 else math.inf
    return (not c.passed, math.inf if math.isnan(share) else share)


def _table(rows: list[tuple[str, ...]], left: int) -> list[str]:
    """Rows as aligned lines: the first ``left`` columns to the left, the others right."""
    widths = [max(len(r[k]) for r in rows) for k in range(len(rows[0]))]
    return ["  " + "  ".join(c.ljust(w) if k < left else c.rjust(w)
                             for k, (c, w) in enumerate(zip(r, widths))).rstrip() for r in rows]


def _number(v: float) -> str:
    return "none" if math.isnan(v) else f"{v:.2g}" if v else "0"
