"""derive(model): the notes' method carried out in symbols for any planar model."""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike

from kinelab import _progress as progress
from kinelab._deadline import within
from kinelab.derive._loops import Loop, LoopEquations, _Names, loop_equations
from kinelab.derive._notation import notation_of
from kinelab.derive._simplify import READABLE_OPS, factors, simplified, size
from kinelab.dynamics._terms import flag
from kinelab.errors import ModelError, check_choice, describe
from kinelab.model import Mechanism, real_array

__all__ = ["derive", "Derivation", "DerivationValues", "Singularity", "LANGUAGES", "TIME_LIMIT"]

LANGUAGES = ("en", "pt")
TIME_LIMIT = 60.0
"""Seconds a derivation (and, apart, its document) may take by default.  The catalogue's and
the examples' take seconds; eight unknowns whose expressions stay large (four slider dyads
with their slide lines at odd angles) take from 15 s to minutes as the machine and its load
go, and past the limit stop with a message that says how to allow more."""
MAX_UNKNOWNS = 8
"""The most unknown coordinates a derivation takes: J's determinant and adjugate grow so fast
in closed form that eight (four dyads) take seconds, ten about twenty and twelve over a minute."""


@dataclass(frozen=True)
class Singularity:
    """One factor of det J that vanishes somewhere, and what it means.

    ``kind`` is ``"slide"`` (a slide is zero: ``names = (slide symbol's joint, point,
    origin)``), ``"in_line"`` or ``"perpendicular"`` (two links: ``names = (a, b)``),
    ``"angle"`` (one link at fixed angles: ``names = (link,)``) or ``"other"``.
    """

    factor: object
    kind: str
    names: tuple[str, ...] = ()
    values: tuple[float, ...] = ()     # the angles (deg) of "angle", for the words


@dataclass(frozen=True, eq=False)
class DerivationValues:
    """The derivation's matrices at N configurations, beside the engine's values.

    Every array has the samples on axis 0.  ``S``, ``K_engine`` and ``L_engine`` come from
    :func:`kinelab.analyze`; ``Phi``, ``J``, ``Q``, ``det_J``, ``K`` and ``L`` are the
    derivation's expressions evaluated there (``Phi`` is the loop closure's residual).
    """

    q: np.ndarray          # (N, M)
    S: np.ndarray          # (N, n)
    Phi: np.ndarray        # (N, n)
    J: np.ndarray          # (N, n, n)
    Q: np.ndarray          # (N, n, M)
    det_J: np.ndarray      # (N,)
    K: np.ndarray          # (N, n, M)
    L: np.ndarray          # (N, n, M, M)
    K_engine: np.ndarray   # (N, n, M)
    L_engine: np.ndarray   # (N, n, M, M)
    engine_det_J: np.ndarray   # (N,) the engine's det J, written group by group


@dataclass(frozen=True, eq=False)
class Derivation:
    """The position, velocity and acceleration equations of a model in the notes' symbols.

    Made by :func:`derive`.  The matrices are sympy objects; :meth:`to_markdown` and
    :meth:`to_latex` write them as a document, :meth:`evaluate` puts numbers in them.

    Attributes
    ----------
    model : Mechanism
    lang : {"en", "pt"}
        The language of the documents.
    q : tuple of sympy.Symbol
        The inputs (primary coordinates), in the model's order.
    S : tuple of sympy.Symbol
        The unknowns (secondary coordinates): link angles, then slides.
    unknowns : dict
        Each symbol of S -> ``("angle", link)`` or ``("slide", joint)``: the quantity
        ``sol.angle(link)`` or ``sol.slide(joint)`` of :func:`kinelab.analyze`.
    inputs : dict
        Each symbol of q -> the input's joint (for an input between two links without a
        joint, the input's name).
    parameters : dict
        Each length, offset, constant angle and fixed coordinate symbol -> its value in
        the model, SI (m, rad).
    loops : tuple of Loop
        The independent vector loops, each with its terms in the order it goes round.
    Phi : sympy.Matrix, shape (n, 1)
        The position equations Phi(q, S) = 0 (x and y of each loop; an equation that the
        others imply, as a parallelogram's, is left out: see ``redundant``).
    J, Q : sympy.Matrix, shapes (n, n) and (n, M)
        dPhi/dS and dPhi/dq.
    det_J : sympy expression
    K : sympy.Matrix, shape (n, M)
        Velocity coefficients ``-J^-1 Q``: ``S' = K q'``.
    L : sympy.Matrix of shape (n, 1) for one input, sympy.Array of shape (n, M, M) for M
        Acceleration coefficients, the total derivative ``dK/dq = dK/dq + dK/dS K``:
        ``S'' = K q'' + L q'^2`` (``q'^T L q'`` for M inputs).
    K_symbols : tuple of sympy.Symbol
        K's entries as symbols (``K_A``), in which ``L_in_K`` is written.
    L_in_K : sympy.Matrix or sympy.Array
        L written with K's entries as symbols, as the notes write it
        (``L_a = -2 K_a K_b / B + R sin(A - q) / B``).
    readable : dict of str to bool
        For ``"K"``, ``"L"``, ``"L_in_K"``, ``"det_J"``: whether the expression was small
        enough to simplify and to read; a document shows the others in matrix form with
        numbers.
    singularities : tuple of Singularity
        The factors of det J that depend on the configuration.
    redundant : tuple of int
        Loop equations (0-based rows of ``rows``) left out of Phi: the others imply them.
    dynamics : KaneDerivation or None
        The Gibbs-Appell / Kane terms when the model has masses.
    """

    model: Mechanism
    lang: str
    equations: LoopEquations = field(repr=False)
    Phi: object
    J: object
    Q: object
    det_J: object
    K: object
    L: object
    K_symbols: tuple
    L_in_K: object
    readable: dict
    singularities: tuple
    rates: dict = field(repr=False)           # symbol -> its first / second derivative symbol
    dynamics: object = None

    # -- the contract's names --------------------------------------------------------------
    @property
    def q(self) -> tuple:
        return self.equations.q

    @property
    def S(self) -> tuple:
        return self.equations.S

    @property
    def unknowns(self) -> dict:
        return dict(self.equations.unknowns)

    @property
    def inputs(self) -> dict:
        return dict(self.equations.inputs)

    @property
    def parameters(self) -> dict:
        return dict(self.equations.parameters)

    @property
    def loops(self) -> tuple[Loop, ...]:
        return self.equations.loops

    @property
    def rows(self) -> tuple:
        return self.equations.rows

    @property
    def redundant(self) -> tuple[int, ...]:
        keep = set(self.equations.independent)
        return tuple(i for i in range(len(self.rows)) if i not in keep)

    # -- rates -------------------------------------------------------------------------------
    def dot(self, s):
        """The symbol of the time derivative of a coordinate (q or S)."""
        return self.rates[s][0]

    def ddot(self, s):
        """The symbol of the second time derivative of a coordinate (q or S)."""
        return self.rates[s][1]

    def velocity_equations(self):
        """dPhi/dt = J S' + Q q' (sympy Matrix, shape (n, 1)), with the rates as symbols."""
        import sympy as sp
        Sd = sp.Matrix([self.dot(s) for s in self.S])
        qd = sp.Matrix([self.dot(s) for s in self.q])
        return self.J * Sd + self.Q * qd

    def acceleration_equations(self):
        """d2Phi/dt2 = J S'' + Q q'' + (dJ/dt S' + dQ/dt q') (sympy Matrix, shape (n, 1))."""
        import sympy as sp
        v = self.velocity_equations()
        out = sp.zeros(len(self.S), 1)
        for s in self.q + self.S:
            out += v.diff(s) * self.dot(s) + v.diff(self.dot(s)) * self.ddot(s)
        return out.applyfunc(sp.expand)

    # -- numbers -----------------------------------------------------------------------------
    @cached_property
    def _functions(self):
        import sympy as sp
        args = list(self.q) + list(self.S) + list(self.parameters)
        M = len(self.q)
        L = self.L if M > 1 else sp.Array(self.L).reshape(len(self.S), 1, 1)
        exprs = {"Phi": self.Phi, "J": self.J, "Q": self.Q, "det_J": self.det_J, "K": self.K,
                 "L": sp.Array(L)}
        return {k: sp.lambdify(args, v, modules="numpy", cse=True) for k, v in exprs.items()}

    def evaluate(self, q: ArrayLike) -> DerivationValues:
        """The derivation's matrices at inputs ``q`` (shape () or (N,) for one input, (M,) or
        (N, M) for M), with S from :func:`kinelab.analyze` and its K and L beside them.

        Raises what :func:`kinelab.analyze` raises where the model does not assemble, and a
        ModelError for ``q`` that is not real numbers of those shapes.
        """
        from kinelab.kinematics import analyze
        m = self.model
        M, n = len(self.q), len(self.S)
        q2 = inputs(q, M, "q")
        sol = analyze(m, q2 if M > 1 else q2[:, 0])
        N = q2.shape[0]
        S = np.zeros((N, n))
        K_engine = np.zeros((N, n, M))
        L_engine = np.zeros((N, n, M, M))
        for i, s in enumerate(self.S):
            kind, name = self.equations.unknowns[s]
            S[:, i] = sol.angle(name) if kind == "angle" else sol.slide(name)
            K_engine[:, i] = np.reshape(sol.K(name), (N, M))
            L_engine[:, i] = np.reshape(sol.L(name), (N, M, M))
        values = list(self.parameters.values())

        def at(name, shape):
            f = self._functions[name]
            out = np.empty((N,) + shape)
            # at a singular configuration K and L divide by det J = 0: inf or NaN there, as
            # the engine's NaN, and the document says so
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                for k in range(N):      # one configuration at a time: shapes stay plain
                    out[k] = np.asarray(f(*q2[k], *S[k], *values), float).reshape(shape)
            return out
        return DerivationValues(
            q=q2, S=S, Phi=at("Phi", (n,)), J=at("J", (n, n)), Q=at("Q", (n, M)),
            det_J=at("det_J", ()), K=at("K", (n, M)), L=at("L", (n, M, M)),
            K_engine=K_engine, L_engine=L_engine, engine_det_J=np.asarray(sol.det_J, float))

    # -- documents -----------------------------------------------------------------------------
    def to_markdown(self, *, at: ArrayLike | None = None, lang: str | None = None,
                    time_limit: float | None = TIME_LIMIT) -> str:
        """The derivation as Markdown with LaTeX maths (``$...$``), in the notes' order,
        ending with its numbers at input ``at`` (default: the model's sketch) beside
        :func:`kinelab.analyze`'s.  Stopped with a :class:`~kinelab.errors.TimeLimitError`
        after ``time_limit`` seconds (None: no limit)."""
        return self._document("md", at, lang, time_limit)

    def to_latex(self, *, at: ArrayLike | None = None, lang: str | None = None,
                 time_limit: float | None = TIME_LIMIT) -> str:
        """The same as :meth:`to_markdown`, as a standalone LaTeX file."""
        return self._document("tex", at, lang, time_limit)

    def _document(self, fmt: str, at, lang: str | None, time_limit: float | None) -> str:
        from kinelab.derive._document import document
        seconds = checked_limit(time_limit)
        return within(seconds, lambda: document(self, fmt, at=at, lang=lang or self.lang),
                      message=time_limit_message(self.model, len(self.S), seconds, "its document"))

    def __repr__(self) -> str:
        return (f"Derivation('{self.model.name}', q={list(self.q)}, S={list(self.S)}, "
                f"{len(self.loops)} loop(s))")


def inputs(q, M: int, name: str, *, one: bool = False) -> np.ndarray:
    """``q`` as an (N, M) array of real numbers, N >= 1: shape () or (N,) for one input,
    (M,) or (N, M) for M; with ``one``, a single configuration (() or (M,)), as (1, M)."""
    a = real_array(q)
    shapes = ("()" if M == 1 else f"({M},)") + ("" if one else " or (N,)" if M == 1 else f" or (N, {M})")
    if a is None:
        raise ModelError(f"{name}: expected real numbers (rad or m), shape {shapes}, got {describe(q)}")
    fits = ((a.ndim == 0 and M == 1) or a.shape == (M,)
            or (not one and ((M == 1 and a.ndim == 1) or (a.ndim == 2 and a.shape[1] == M))))
    if not fits or a.size == 0:
        what = "one configuration" if one else "configurations"
        raise ModelError(f"{name}: expected {what} of {M} input(s), shape {shapes}, got shape "
                         f"{a.shape}")
    if not np.all(np.isfinite(a)):
        raise ModelError(f"{name}: expected finite numbers, got {describe(q)}")
    return a.reshape(-1, M)


def checked_limit(time_limit) -> float | None:
    """``time_limit`` as seconds (None: no limit), or a ModelError."""
    if time_limit is None:
        return None
    if isinstance(time_limit, bool) or not isinstance(time_limit, (int, float, np.integer,
                                                                   np.floating)) \
            or not time_limit > 0:
        raise ModelError(f"time_limit: expected a number of seconds > 0 (or None: no limit), "
                         f"got {describe(time_limit)}")
    return float(time_limit)


def time_limit_message(model: Mechanism, unknowns: int | None, seconds: float | None,
                       what: str) -> str:
    """What a derivation (``what``: "it", "its document") stopped at its time limit says."""
    if seconds is None:
        return ""
    size = f" of {unknowns} unknowns" if unknowns else ""
    return (f"derivation of '{model.name}': {what} took more than {seconds:g} s, the time "
            f"limit; its expressions{size} grow too large to finish in time: derive a part of "
            "the mechanism, analyse it numerically (kinelab analyze), or allow more time "
            "(time_limit=..., kinelab derive --time-limit SECONDS)")


def derive(model: Mechanism, lang: Literal["en", "pt"] = "en", *, dynamics: bool = True,
           loads=None, masses=None, notation="notes",
           time_limit: float | None = TIME_LIMIT) -> Derivation:
    """The notes' derivation of a planar model, in symbols: position equations, J, Q,
    det J and its singular configurations, K and L (and, for a model with masses, the
    Gibbs-Appell / Kane terms).

    The position equations are one vector loop per independent circuit of the link graph
    (see :func:`kinelab.derive.loop_equations`); then J = dPhi/dS, Q = dPhi/dq,
    K = -J^-1 Q and L = dK/dq, the total derivative, as in Erthal, *Mecanismos com 1 GL:
    análise geral de velocidade e aceleração*.  Each result is simplified while it is
    small (:data:`kinelab.derive.SIMPLIFY_OPS`); a larger one is kept as derived and
    flagged in ``readable``.

    Parameters
    ----------
    model : Mechanism
        Any planar model :func:`kinelab.analyze` solves: catalogue, model file or Python.
        The catalogue's mechanisms use the notes' letters where the notes have them (R, C,
        A, B for the slotted link); other models are written with their own names.
    lang : {"en", "pt"}
        Language of the documents (:meth:`Derivation.to_markdown`).
    dynamics : bool
        Derive the Gibbs-Appell / Kane terms when the model has masses.
    loads : kinelab.dynamics.Loads, optional
        Default: the model file's ``[dynamics]`` section, else none.
    masses : kinelab.dynamics.MassProperties, optional
        Default: the links' mass data (a lumped model: ``MassProperties.lumped``).
    notation : {"notes", "names"} or mapping
        The symbols: ``"notes"``, the notes' letters of a catalogue mechanism and the
        model file's ``[notation]`` table; ``"names"``, the model's own names throughout;
        or a mapping of the names kinelab would write to the symbols to write instead
        (``{"theta_lever": "A", "s_slot": "B"}``), over the notes' ones.
    time_limit : float or None
        Seconds the derivation may take (default :data:`TIME_LIMIT`), in whichever thread
        it runs; None: no limit.

    Returns
    -------
    Derivation

    Raises
    ------
    ModelError
        The model is not one :func:`kinelab.analyze` can solve (the same error), or an
        argument is wrong (a ``notation`` naming a symbol the equations do not have).
    TimeLimitError
        The derivation took more than ``time_limit`` seconds.

    Examples
    --------
    >>> d = kl.derive.derive(kl.mechanisms.slotted_link(crank=0.1, distance=0.2))
    >>> d.Phi.T
    Matrix([[B*cos(A) - C - R*cos(q), B*sin(A) - R*sin(q)]])
    >>> d.det_J, d.K.T
    (-B, Matrix([[R*cos(A - q)/B, R*sin(A - q)]]))
    """
    check_choice("lang", lang, LANGUAGES)
    dynamics = flag(dynamics, "dynamics")
    seconds = checked_limit(time_limit)
    if not isinstance(model, Mechanism):
        raise ModelError(f"model: expected a kinelab Mechanism, got {type(model).__name__}; "
                         "build one with kinelab.mechanisms or kinelab.load")
    import sympy  # noqa: F401 -- imported before the clock starts: the limit is the derivation's
    symbols = notation_of(model, notation)
    return within(seconds, _derive, model, lang, dynamics, loads, masses, symbols,
                  message=time_limit_message(model, None, seconds, "it"))


def _derive(model: Mechanism, lang: str, dynamics: bool, loads, masses,
            symbols: dict) -> Derivation:
    import sympy as sp
    bodies = None
    progress.report("loop equations", 0.0)
    if dynamics:
        from kinelab.derive._dynamics import bodies_of
        bodies = bodies_of(model, loads, masses)
    eq = loop_equations(model, symbols, points=bodies.points if bodies else ())
    S, q = sp.Matrix(eq.S), sp.Matrix(eq.q)
    n, M = len(eq.S), len(eq.q)
    if n > MAX_UNKNOWNS:
        raise ModelError(f"model: '{model.name}' has {n} unknown coordinates; the derivation in "
                         f"closed form (det J and the adjugate of J, symbolic) is written for at "
                         f"most {MAX_UNKNOWNS} (four dyads): beyond, it takes minutes and pages; "
                         "analyse the mechanism numerically (kinelab analyze), or derive a part "
                         "of it")
    progress.report("J and Q", _SHARE["J"][0])
    Phi = sp.Matrix([eq.rows[i] for i in eq.independent]) if n else sp.zeros(0, 1)
    J = Phi.jacobian(S) if n else sp.zeros(0, 0)
    Q = Phi.jacobian(q) if n else sp.zeros(0, M)
    readable = {}
    progress.report("det J", _SHARE["det J"][0])
    det_raw = J.det(method="berkowitz") if n else sp.Integer(1)
    det_J, ok = simplified(det_raw)
    readable["det_J"] = ok and size(det_J) <= READABLE_OPS
    progress.report("adjugate of J", _SHARE["adjugate"][0])
    adj = J.adjugate(method="berkowitz") if n > 1 else (sp.Matrix([[1]]) if n else sp.zeros(0, 0))
    K_raw = -(adj * Q) / det_J if n else sp.zeros(0, M)
    with progress.part(*_SHARE["K"]):
        K, readable["K"] = _each(K_raw, "K")
    names = _Names({str(s) for s in eq.q + eq.S} | {str(s) for s in eq.parameters})
    K_symbols = tuple(names(f"K_{s}" if M == 1 else f"K_{s},{k + 1}")
                      for s in eq.S for k in range(M))
    Ks = sp.Matrix(n, M, K_symbols) if n else sp.zeros(0, M)
    # L from J L = -(dJ/dq K + dQ/dq), the total derivatives taken with K as symbols
    progress.report("dL/dq", _SHARE["dL"][0])
    L_in_K_cols = {}
    L_cols = {}
    for a in range(M):
        for b in range(M):
            total = sp.zeros(n, 1)
            g = J * Ks[:, a] + Q[:, a]                     # = 0 along the motion
            total += g.diff(q[b])
            for j in range(n):
                total += g.diff(S[j]) * Ks[j, b]
            L_in_K_cols[a, b] = (adj * -total) / det_J
            # the total derivative of K itself: dK/dq_b + dK/dS K_b
            col = K[:, a].diff(q[b]) + (K[:, a].jacobian(S) * K[:, b] if n else sp.zeros(0, 1))
            L_cols[a, b] = col
    with progress.part(*_SHARE["L in K"]):
        L_in_K, readable["L_in_K"] = _each(_assemble(L_in_K_cols, n, M), "L (in K)")
    with progress.part(*_SHARE["L"]):
        L, readable["L"] = _each(_assemble(L_cols, n, M), "L")
    if M == 1:
        L, L_in_K = sp.Matrix(L), sp.Matrix(L_in_K)
    rates = {s: (names(f"{s}_dot"), names(f"{s}_ddot")) for s in eq.q + eq.S}
    d = Derivation(model=model, lang=lang, equations=eq, Phi=Phi, J=J, Q=Q, det_J=det_J, K=K,
                   L=L, K_symbols=K_symbols, L_in_K=L_in_K, readable=readable,
                   singularities=_singularities(eq, det_J), rates=rates)
    if bodies is not None:
        progress.report("Kane's terms", _SHARE["dynamics"][0])
        from kinelab.derive._dynamics import kane_terms
        object.__setattr__(d, "dynamics", kane_terms(d, bodies))
    return d


# The share of a derivation's time each of its steps takes (measured on the six-bars), for
# the fraction done that :mod:`kinelab._progress` reports.
_SHARE = {"J": (0.05, 0.07), "det J": (0.07, 0.09), "adjugate": (0.09, 0.12),
          "K": (0.12, 0.22), "dL": (0.22, 0.28), "L in K": (0.28, 0.52), "L": (0.52, 0.90),
          "dynamics": (0.90, 1.0)}


def _each(mat, name: str = "entries"):
    """Every entry simplified within the bounds; and whether all of them were, and are
    small enough to read (each entry reported as progress, under ``name``)."""
    import sympy as sp
    if 0 in mat.shape:
        return mat, True
    ok = True
    out = []
    entries = sp.flatten(mat.tolist()) if isinstance(mat, sp.NDimArray) else list(mat)
    for k, e in enumerate(entries):
        progress.report(f"{name}: entry {k + 1} of {len(entries)}", k / len(entries))
        s, done = simplified(e)
        out.append(s)
        ok &= done and size(s) <= READABLE_OPS
    if isinstance(mat, sp.NDimArray):
        return sp.Array(out, mat.shape), ok
    return sp.Matrix(mat.rows, mat.cols, out), ok


def _assemble(cols: dict, n: int, M: int):
    """Columns (a, b) of L into the notes' shapes: (n, 1) for one input, (n, M, M) for M."""
    import sympy as sp
    if M == 1:
        return sp.Matrix(cols[0, 0])
    if n == 0:
        return sp.Array.zeros(0, M, M)
    return sp.Array([[[cols[a, b][i] for b in range(M)] for a in range(M)] for i in range(n)],
                    (n, M, M))


def _singularities(eq: LoopEquations, det_J) -> tuple[Singularity, ...]:
    """The factors of det J that depend on the configuration, read as the notes read them."""
    moving = set(eq.q) | set(eq.S)
    _, parts = factors(det_J)
    out = []
    for f, _ in parts:
        if not (f.free_symbols & moving):
            continue
        out.append(_reading(eq, f))
    return tuple(out)


def _reading(eq: LoopEquations, f) -> Singularity:
    import sympy as sp
    m = eq.model
    if f in eq.unknowns and eq.unknowns[f][0] == "slide":
        j = m.joint(eq.unknowns[f][1])
        origin = j.origin or m.link(j.links[0]).points[0]
        return Singularity(f, "slide", (j.name, j.point, origin))
    if isinstance(f, (sp.sin, sp.cos)):
        arg = f.args[0]
        links = []
        for s in arg.free_symbols & (set(eq.S) | set(eq.q)):
            link = _link_of(eq, s)
            if link is None:
                links = []
                break
            links.append((arg.coeff(s), link))
        const = arg.subs({s: 0 for s in arg.free_symbols if s in set(eq.S) | set(eq.q)})
        if len(links) == 2 and {c for c, _ in links} == {1, -1} and (const / sp.pi).is_integer:
            first = next(name for c, name in links if c == 1)
            second = next(name for c, name in links if c == -1)
            return Singularity(f, "in_line" if isinstance(f, sp.sin) else "perpendicular",
                               (first, second))
        if len(links) == 1 and abs(links[0][0]) == 1 and not const.free_symbols:
            c = float(const) * float(links[0][0])
            base = 0.0 if isinstance(f, sp.sin) else np.pi / 2
            values = tuple(sorted({round(float(np.degrees((base - c + k * np.pi + np.pi)
                                                            % (2 * np.pi) - np.pi)), 9)
                                   for k in (0, 1)}))
            return Singularity(f, "angle", (links[0][1],), values)
    return Singularity(f, "other")


def _link_of(eq: LoopEquations, s) -> str | None:
    """The link whose angle a symbol of q or S is (None for a slide)."""
    if s in eq.unknowns:
        kind, name = eq.unknowns[s]
        return name if kind == "angle" else None
    inp = eq.model.inputs[eq.q.index(s)]
    if inp.joint is not None and eq.model.joint(inp.joint).type == "P":
        return None
    a, b = eq.model.joint(inp.joint).links if inp.joint is not None else inp.links
    ground = eq.model.ground.name
    return b if a == ground else (a if b == ground else None)
