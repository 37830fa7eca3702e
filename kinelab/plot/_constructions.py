"""Figures of the graphical constructions drawn step by step, as the velocity notes teach
them (Flores & Claro, *Cinemática de Mecanismos — 4. Análise de Velocidades*, §4.6.2-4.6.4):
graphical differentiation by tangents and a polar distance, the velocity image by similar
triangles, and Kennedy's construction of the instant centres with its circle diagram.

Each figure numbers its steps, in English or in the notes' Portuguese (``lang="pt"``).  The
numbers come from :mod:`kinelab.kinematics` (``tangent_construction``, ``velocity_image``,
``kennedy_steps``); these functions only draw them.
"""
from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from kinelab.errors import ModelError, describe
from kinelab.kinematics import KinematicSolution
from kinelab.model import Units
from kinelab.plot._figures import plain
from kinelab.plot._words import LANGUAGES

__all__ = ["tangent_construction", "velocity_image", "kennedy_steps", "LANGUAGES"]


_TEXT = {
    "en": {
        "diff_title": "graphical differentiation: tangents, pole and polar distance",
        "curve": "curve", "points": "chosen points A", "tangent": "tangent (triangle BCD, BD = H)",
        "pole": "pole P", "polar": "polar distance H = {H}",
        "ray": "rays from P parallel to the tangents", "intercept": "intercepts on the ordinate axis",
        "derived": "derivative from the construction (A')",
        "numerical": "numerical derivative (local least squares)",
        "diff_steps": ["1: tangent at each chosen point A",
                       "2: pole P at the polar distance H left of O",
                       "3: ray from P parallel to each tangent",
                       "4: its intercept on the ordinate axis, carried across to A'",
                       "5: the derivative curve through the points A'"],
        "scale": "1 unit of ordinate = 1/H = {s} {u}",
        "chord": "tangent from the chord between neighbouring samples",
        "fitted": "tangent from the fitted slope",
        "image_title": "velocity image by similar triangles",
        "link_title": "{link}: triangle {ABC}",
        "steps_image": ["1: o{a} = V_{A}", "2: o{b} = V_{B}", "3: {a}{b} = V_{B}{A}"],
        "similar": "{n}: triangle {abc} similar to {ABC}", "result": "{n}: o{c} = V_{C}",
        "pole_v": "pole o", "velocities": "velocities [{u}]",
        "kennedy_title": "instant centres: Kennedy's construction, step by step",
        "primary": "0: primary centres (the joints)",
        "step": "{n}: {c} = ({n}a) {c1}-{c2} \u00d7 ({n}b) {c3}-{c4}",
        "circle": "circle diagram\n(a side drawn when its centre is known)",
        "theorem": "Kennedy's theorem: the three centres of three bodies lie on one line",
        "infinity": "at infinity",
        "velocities_taken": "from the velocities: {pairs}",
    },
    "pt": {
        "diff_title": "diferenciação gráfica: tangentes, polo e distância polar",
        "curve": "curva", "points": "pontos escolhidos A", "tangent": "tangente (triângulo BCD, BD = H)",
        "pole": "polo P", "polar": "distância polar H = {H}",
        "ray": "rectas por P paralelas às tangentes",
        "intercept": "intersecções com o eixo das ordenadas",
        "derived": "derivada pela construção (A')",
        "numerical": "derivada numérica (mínimos quadrados locais)",
        "diff_steps": ["1: tangente em cada ponto escolhido A",
                       "2: polo P à distância polar H à esquerda de O",
                       "3: recta por P paralela a cada tangente",
                       "4: a sua intersecção com o eixo das ordenadas, transportada para A'",
                       "5: a curva da derivada pelos pontos A'"],
        "scale": "1 unidade de ordenada = 1/H = {s} {u}",
        "chord": "tangente pela corda entre os pontos vizinhos",
        "fitted": "tangente pelo declive ajustado",
        "image_title": "imagem de velocidades por triângulos semelhantes",
        "link_title": "{link}: triângulo {ABC}",
        "steps_image": ["1: o{a} = V_{A}", "2: o{b} = V_{B}", "3: {a}{b} = V_{B}{A}"],
        "similar": "{n}: triângulo {abc} semelhante a {ABC}", "result": "{n}: o{c} = V_{C}",
        "pole_v": "polo o", "velocities": "velocidades [{u}]",
        "kennedy_title": "centros instantâneos de rotação: teorema de Kennedy, passo a passo",
        "primary": "0: centros primários (as juntas)",
        "step": "{n}: {c} = ({n}a) {c1}-{c2} \u00d7 ({n}b) {c3}-{c4}",
        "circle": "diagrama circular\n(um lado traçado quando o seu centro é conhecido)",
        "theorem": "teorema de Kennedy: os três centros de três corpos estão alinhados",
        "infinity": "no infinito",
        "velocities_taken": "pelas velocidades: {pairs}",
    },
}


def _words(lang: str) -> dict:
    if lang not in _TEXT:
        raise ModelError(f"lang: expected one of 'en', 'pt', got {describe(lang)}")
    return _TEXT[lang]


def _steps_box(fig, lines, *, x=0.01, y=0.005, gid="steps"):
    """The numbered steps, one per line, in a box at the foot of the figure; each line its
    own Text (gid ``step <k>``) so that a reader (and a test) finds them."""
    n = len(lines)
    for k, line in enumerate(lines):
        fig.text(x, y + _LINE_IN * (n - 1 - k) / fig.get_figheight(),
                 plain(line), fontsize=8, ha="left", va="bottom", gid=f"{gid} {k}")


_LINE_IN = 0.2          # inches per line of the steps' box


def _bottom(fig, lines: int, axis_in: float = 0.75) -> float:
    """The figure fraction the axes must start above to leave room for ``lines`` steps and
    the lowest axes' labels (``axis_in`` inches)."""
    return (0.1 + _LINE_IN * lines + axis_in) / fig.get_figheight()


# -- graphical differentiation -------------------------------------------------------------------
def tangent_construction(tc, *, numerical=None, x_label: str = "t", y_label: str = "x",
                         x_unit: str = "s", y_unit: str = "m", lang: str = "en",
                         drawn: int = 6):
    """Graphical differentiation drawn as the notes draw it (Flores & Claro, §4.6.4,
    Fig. 4.22): above, the curve, the chosen points A and their tangents (with the triangle
    BCD, BD = H, of the first ``drawn``); below, the derivative diagram on the same
    abscissa: the pole P at the polar distance H left of the origin O, the rays from P
    parallel to the tangents, their intercepts on the ordinate axis carried across to the
    points A', and the derivative curve through them beside the numerical derivative.

    Parameters
    ----------
    tc : TangentConstruction
        From :func:`kinelab.kinematics.tangent_construction`.
    numerical : Derivatives, optional
        The numerical derivative to draw beside (default: :func:`kinelab.solvers.differentiate`
        of the curve, when it has enough samples).
    x_label, y_label, x_unit, y_unit : str
        The abscissa's and the curve's names and units.
    lang : {"en", "pt"}
    drawn : int
        How many of the tangents get their triangle BCD and their ray labelled (all are
        drawn).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels: the curve with its tangents, the derivative diagram.  The ordinate of the
        second is in y's unit (the intercepts); its right-hand axis reads the derivative.

    Examples
    --------
    >>> t = np.linspace(0.0, 1.0, 61)
    >>> tc = kl.kinematics.tangent_construction(t, np.sin(3 * t), points=8)
    >>> fig = kl.plot.tangent_construction(tc, lang="pt")
    >>> steps = [t.get_text() for t in fig.texts if (t.get_gid() or "").startswith("steps")]
    >>> steps[1]
    '2: polo P à distância polar H à esquerda de O'
    """
    import matplotlib.pyplot as plt
    w = _words(lang)
    if numerical is None:
        from kinelab.solvers import differentiate
        from kinelab.solvers._differentiate import MIN_SAMPLES
        if len(tc.x) >= MIN_SAMPLES:
            try:
                numerical = differentiate(tc.x, tc.y)
            except ModelError:
                numerical = None
    H = tc.polar_distance
    fig, (ax_c, ax_d) = plt.subplots(2, 1, figsize=(8, 9.2), sharex=True)
    fig.subplots_adjust(left=0.12, right=0.86, top=0.93, bottom=_bottom(fig, 5), hspace=0.12)
    # 1: the curve, the chosen points, the tangents and their triangles
    ax_c.plot(tc.x, tc.y, color="black", lw=1.2, label=w["curve"])
    ax_c.plot(*tc.points.T, "o", color="tab:blue", ms=4, label=w["points"])
    for k, ((B, C), tri) in enumerate(zip(tc.tangents, tc.triangles)):
        d = C - B
        ax_c.plot(*np.array([B - 0.4 * d, C + 0.4 * d]).T, color="tab:blue", lw=0.9,
                  label=w["tangent"] if k == 0 else None, gid=f"tangent {k + 1}")
        if k < drawn:
            ax_c.plot(*np.vstack([tri, tri[:1]]).T, color="tab:blue", lw=0.6, ls=":")
            ax_c.annotate(f"A{k + 1}", tc.points[k], xytext=(-4, 6), textcoords="offset points",
                          fontsize=7, color="tab:blue", ha="right")
    ax_c.set_ylabel(plain(f"{y_label} [{y_unit}]"))
    ax_c.legend(fontsize="small", loc="best")
    ax_c.set_title(plain(f"{w['diff_title']}\n{w[tc.method]}"), fontsize=10)
    # 2-5: the derivative diagram
    O, P = tc.origin, tc.pole
    ax_d.axhline(0.0, color="black", lw=0.8)
    ax_d.axvline(O[0], color="black", lw=0.8)
    ax_d.plot(*P, "s", color="tab:red", ms=5, label=w["pole"])
    ax_d.annotate("P", P, xytext=(-4, -12), textcoords="offset points", color="tab:red", fontsize=9)
    ax_d.annotate("O", O, xytext=(3, -12), textcoords="offset points", fontsize=9)
    ax_d.annotate("", xy=O, xytext=P, arrowprops=dict(arrowstyle="<->", color="tab:red", lw=0.9))
    ax_d.annotate(plain(w["polar"].format(H=f"{H:.4g} {x_unit}")), 0.5 * (P + O),
                  xytext=(0, 8), textcoords="offset points", ha="center", fontsize=8,
                  color="tab:red", gid="polar distance")
    for k, ((start, end), a) in enumerate(zip(tc.rays, tc.derived)):
        ax_d.plot(*np.array([start, end]).T, color="tab:orange", lw=0.7,
                  label=w["ray"] if k == 0 else None, gid=f"ray {k + 1}")
        ax_d.plot([end[0], a[0]], [end[1], a[1]], color="0.6", lw=0.6, ls=":")
    ax_d.plot(np.full(len(tc.intercepts), O[0]), tc.intercepts, "_", color="tab:orange", ms=9,
              mew=1.5, label=w["intercept"])
    ax_d.plot(*tc.derived.T, "o-", color="tab:blue", ms=4, lw=1.2, label=w["derived"])
    for k, a in enumerate(tc.derived[:drawn]):
        ax_d.annotate(f"A'{k + 1}", a, xytext=(3, 5), textcoords="offset points", fontsize=7,
                      color="tab:blue")
    if numerical is not None:
        ax_d.plot(numerical.x, H * numerical.velocity, color="black", lw=0.9, ls="--",
                  label=w["numerical"])
    ax_d.set_ylabel(plain(f"H d{y_label}/d{x_label} [{y_unit}]"))
    ax_d.set_xlabel(plain(f"{x_label} [{x_unit}]"))
    ax_d.legend(fontsize="small", loc="best")
    right = ax_d.twinx()
    right.set_ylim(*(np.array(ax_d.get_ylim()) / H))
    right.set_ylabel(plain(f"d{y_label}/d{x_label} [{y_unit}/{x_unit}]"))
    ax_d.callbacks.connect("ylim_changed",
                           lambda ax: right.set_ylim(*(np.array(ax.get_ylim()) / H)))
    ax_d.set_title(plain(w["scale"].format(s=f"{1 / H:.4g}", u=f"{y_unit}/{x_unit} per {y_unit}"
                                           if lang == "en" else f"{y_unit}/{x_unit} por {y_unit}")),
                   fontsize=9)
    lo = min(P[0], float(tc.x[0])) - 0.03 * float(tc.x[-1] - P[0])
    ax_d.set_xlim(lo, float(tc.x[-1]) + 0.03 * float(tc.x[-1] - P[0]))
    for ax in (ax_c, ax_d):
        ax.grid(True, alpha=0.25)
    _steps_box(fig, w["diff_steps"])
    return fig


# -- the velocity image --------------------------------------------------------------------------
def _mechanism(ax, sol, i, u, extra=()):
    from kinelab.plot._figures import mechanism
    mechanism(sol, i, ax=ax, units=u)
    pos = np.array([np.reshape(sol.position(p), (-1, 2))[i] for p in sol.point_names])
    for p, xy in zip(sol.point_names, pos):
        ax.annotate(plain(p), u.convert(xy, "m"), xytext=(4, 4), textcoords="offset points",
                    fontsize=8)
    pts = np.vstack([pos, *extra]) if len(extra) else pos
    pts = u.convert(pts, "m")
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    pad = 0.12 * max(float(np.max(hi - lo)), 1e-300)
    mid, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo)) + pad
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel(f"x [{u.length}]")
    ax.set_ylabel(f"y [{u.length}]")
    ax.grid(True, alpha=0.25)
    return pos


def _badge(ax, xy, number, color):
    ax.annotate(str(number), xy, fontsize=7, color=color, ha="center", va="center",
                bbox=dict(boxstyle="circle,pad=0.15", fc="white", ec=color, lw=0.6),
                gid=f"badge {number}", zorder=7)


def _arrow(ax, start, end, color, ls="-", lw=1.5):
    ax.annotate("", xy=end, xytext=start, annotation_clip=False,
                arrowprops=dict(arrowstyle="-|>", color=color, lw=lw, ls=ls, shrinkA=0,
                                shrinkB=0, mutation_scale=12))


def velocity_image(sol: KinematicSolution, link: str, *, known: tuple[str, str] | None = None,
                   sample: int = 0, units: Units | Mapping[str, str] | None = None,
                   lang: str = "en"):
    """The velocity image of ``link`` built by similar triangles, with numbered steps
    (Flores & Claro, §4.6.2): 1 oa = V_A, 2 ob = V_B, 3 ab, 4 the triangle abc similar to
    ABC with the same orientation, 5 oc = V_C (then 6, 7 for a fourth point, ...); beside,
    the mechanism with the link's triangle ABC shaded.

    Parameters
    ----------
    sol : KinematicSolution
    link : str
    known : (str, str), optional
        A and B (default: the link's first two points).
    sample : int
    units : Units or mapping, optional
    lang : {"en", "pt"}

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ModelError, SingularityError, AssemblyError
        As :func:`kinelab.kinematics.velocity_image`.

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    >>> fig = kl.plot.velocity_image(kl.analyze(fb, q=np.radians(60.0), qd=10.0), "coupler")
    >>> [t.get_text() for t in fig.texts if (t.get_gid() or "").startswith("steps")][3:]
    ['4: triangle abp similar to ABP', '5: op = V_P']
    """
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon as Patch
    from kinelab.kinematics import velocity_image as image_data
    w = _words(lang)
    vi = image_data(sol, link, known=known, sample=sample)
    u = Units.resolve(units)
    i = vi.sample
    A, B = vi.known
    fig, (ax_m, ax_p) = plt.subplots(1, 2, figsize=(11, 5.2 + _LINE_IN * (3 + 2 * len(vi.points))))
    fig.subplots_adjust(left=0.07, right=0.98, top=1 - 0.7 / fig.get_figheight(),
                        bottom=_bottom(fig, 3 + 2 * len(vi.points)), wspace=0.25)
    _mechanism(ax_m, sol, i, u)
    names = [A, B, *vi.points]
    for c in vi.points:
        tri = u.convert(np.array([vi.positions[p] for p in (A, B, c)]), "m")
        ax_m.add_patch(Patch(tri, closed=True, alpha=0.25, color="tab:green", lw=1.2))
    ax_m.set_title(plain(w["link_title"].format(link=link, ABC="".join(names))), fontsize=9)
    v = {p: np.asarray(u.convert(vi.vertices[p], "m/s"), float) for p in names}
    low = {p: plain(p.lower()) for p in names}
    o = np.zeros(2)
    _arrow(ax_p, o, v[A], "black")
    _badge(ax_p, 0.5 * v[A], 1, "black")
    _arrow(ax_p, o, v[B], "black")
    _badge(ax_p, 0.5 * v[B], 2, "black")
    _arrow(ax_p, v[A], v[B], "tab:gray", ls="--", lw=1.2)
    _badge(ax_p, 0.5 * (v[A] + v[B]), 3, "tab:gray")
    lines = [s.format(a=low[A], b=low[B], A=plain(A), B=plain(B)) for s in w["steps_image"]]
    n = 4
    for c in vi.points:
        tri = np.array([v[A], v[B], v[c]])
        ax_p.add_patch(Patch(tri, closed=True, alpha=0.25, color="tab:green", lw=1.2,
                             gid=f"triangle {c}"))
        ax_p.plot(*np.vstack([tri, tri[:1]]).T, color="tab:green", lw=1.0)
        _badge(ax_p, tri.mean(axis=0), n, "tab:green")
        lines.append(w["similar"].format(n=n, abc=low[A] + low[B] + low[c],
                                         ABC=plain(A + B + c)))
        _arrow(ax_p, o, v[c], "tab:blue", lw=1.8)
        _badge(ax_p, 0.5 * v[c], n + 1, "tab:blue")
        lines.append(w["result"].format(n=n + 1, c=low[c], C=plain(c)))
        n += 2
    ax_p.plot(0.0, 0.0, "ko", ms=4)
    ax_p.annotate(w["pole_v"], (0.0, 0.0), xytext=(-10, -12), textcoords="offset points", fontsize=8)
    for p in names:
        ax_p.plot(*v[p], "o", ms=3, color="black")
        ax_p.annotate(low[p], v[p], xytext=(4, 4), textcoords="offset points", fontsize=10)
    pts = np.vstack([o, *v.values()])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    half = 0.5 * max(float(np.max(hi - lo)), 1e-300) * 1.15
    mid = 0.5 * (lo + hi)
    ax_p.set_xlim(mid[0] - half, mid[0] + half)
    ax_p.set_ylim(mid[1] - half, mid[1] + half)
    ax_p.set_aspect("equal", adjustable="box")
    ax_p.grid(True, alpha=0.25)
    unit = u.unit("m/s")
    ax_p.set_xlabel(f"vx [{unit}]")
    ax_p.set_ylabel(f"vy [{unit}]")
    ax_p.set_title(plain(w["velocities"].format(u=unit)), fontsize=9)
    fig.suptitle(plain(f"{sol.mechanism.name}: {w['image_title']}"), fontsize=11)
    _steps_box(fig, lines)
    return fig


# -- Kennedy's construction ----------------------------------------------------------------------
def _circle(ax, ks, known, new=None, number=None, w=None):
    n = len(ks.numbers)
    angle = {lk: np.pi / 2 - 2 * np.pi * (k - 1) / n for lk, k in ks.numbers.items()}
    xy = {lk: np.array([np.cos(a), np.sin(a)]) for lk, a in angle.items()}
    order = {s.pair: s.number for s in ks.steps}
    for pair in known:
        a, b = pair
        line = np.array([xy[a], xy[b]])
        if pair == new:
            style = dict(color="tab:red", lw=1.8, ls="--")
        elif pair in ks.primary:
            style = dict(color="black", lw=1.4, ls="-")
        else:
            style = dict(color="tab:gray", lw=1.0, ls="--")
        ax.plot(*line.T, **style, gid=ks.label(pair))
        if pair in order:
            _badge(ax, line.mean(axis=0), order[pair], "tab:red" if pair == new else "tab:gray")
    for lk, p in xy.items():
        ax.plot(*p, "o", ms=14, mfc="white", mec="black", zorder=3)
        ax.annotate(str(ks.numbers[lk]), p, ha="center", va="center", fontsize=8, zorder=4)
        ax.annotate(plain(lk), 1.3 * p, ha="center", va="center", fontsize=7)
    ax.set_xlim(-1.7, 1.7)
    ax.set_ylim(-1.7, 1.7)
    ax.set_aspect("equal")
    ax.set_axis_off()


def kennedy_steps(sol: KinematicSolution, sample: int = 0, *,
                  units: Units | Mapping[str, str] | None = None, lang: str = "en"):
    """Kennedy's construction of the instant centres drawn step by step (Flores & Claro,
    §4.6.3): a row for the primary centres (the joints), then a row for each secondary
    centre in the order found, with the two lines of known centres that fix it (numbered
    na and nb), their intersection (numbered n), and the circle diagram with a side drawn
    for each centre known so far, the new one in red.

    Parameters
    ----------
    sol : KinematicSolution
    sample : int
    units : Units or mapping, optional
    lang : {"en", "pt"}

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    >>> fig = kl.plot.kennedy_steps(kl.analyze(fb, q=np.radians(60.0)))
    >>> [t.get_text() for t in fig.texts if (t.get_gid() or "").startswith("steps")]
    ['0: primary centres (the joints)', '1: O13 = (1a) O12-O23 × (1b) O14-O34', '2: O24 = (2a) O12-O14 × (2b) O23-O34']
    """
    import matplotlib.pyplot as plt
    from kinelab.kinematics import kennedy_steps as steps_data
    w = _words(lang)
    ks = steps_data(sol, sample)
    u = Units.resolve(units)
    i = ks.sample
    rows = 1 + len(ks.steps)
    count = rows + (1 if ks.from_velocities else 0)
    height = 3.9 * rows + 1.6 + _LINE_IN * count
    fig, axes = plt.subplots(rows, 2, figsize=(10, height), squeeze=False,
                             gridspec_kw=dict(width_ratios=(1.6, 1.0)))
    fig.subplots_adjust(left=0.07, right=0.98, top=1 - 1.2 / height,
                        bottom=_bottom(fig, count), hspace=0.35)
    pos = np.array([np.reshape(sol.position(p), (-1, 2))[i] for p in sol.point_names])
    size = float(np.ptp(pos, axis=0).max())
    centre = pos.mean(axis=0)
    finite = {}
    for pair in ks.construction.centers:
        xy, inf, d = ks.center(pair)
        if not inf and np.all(np.isfinite(xy)) and np.linalg.norm(xy - centre) <= 3 * size:
            finite[pair] = xy
    extra = [np.array(list(finite.values()))] if finite else []

    def draw_centre(ax, pair, color, filled, text):
        xy, inf, d = ks.center(pair)
        if pair in finite:
            p = u.convert(xy, "m")
            ax.plot(*p, "o", ms=6, color=color, mfc=color if filled else "white", mew=1.4,
                    zorder=6, gid=ks.label(pair))
            ax.annotate(plain(text), p, xytext=(5, -11), textcoords="offset points", fontsize=8,
                        color=color, annotation_clip=False)
        elif inf:
            ax.annotate(plain(f"{text} {w['infinity']} \u2192 ({d[0]:.2f}, {d[1]:.2f})"),
                        (0.02, 0.96 - 0.07 * len([t for t in ax.texts if w["infinity"] in t.get_text()])),
                        xycoords="axes fraction", fontsize=7, color=color, va="top")
    lines_text = [w["primary"]]
    known = list(ks.primary)
    for row in range(rows):
        ax_m, ax_c = axes[row]
        _mechanism(ax_m, sol, i, u, extra=extra)
        if row == 0:
            for pair in ks.primary:
                draw_centre(ax_m, pair, "tab:red", True, ks.label(pair))
            _circle(ax_c, ks, known)
            ax_m.set_title(plain(w["primary"]), fontsize=9)
            ax_c.set_title(plain(w["circle"]), fontsize=8)
            continue
        s = ks.steps[row - 1]
        for pair in ks.primary:
            draw_centre(ax_m, pair, "0.35", True, ks.label(pair))
        for earlier in ks.steps[:row - 1]:
            draw_centre(ax_m, earlier.pair, "0.35", False, ks.label(earlier.pair))
        for tag, line in zip("ab", s.lines):
            if not np.all(np.isfinite(line.direction)):
                continue
            p = u.convert(line.point, "m")
            ax_m.axline(p, p + line.direction, color="tab:orange", lw=0.9, ls="-", zorder=2,
                        gid=f"line {s.number}{tag}")
            # the line's number beside its first finite centre
            ax_m.annotate(f"{s.number}{tag}", p, xytext=(-14, 6), textcoords="offset points",
                          fontsize=8, color="tab:orange")
        draw_centre(ax_m, s.pair, "tab:red", False, f"{ks.label(s.pair)} ({s.number})")
        c = [ks.label(q) for line in s.lines for q in line.through]
        text = w["step"].format(n=s.number, c=ks.label(s.pair), c1=c[0], c2=c[1], c3=c[2], c4=c[3])
        lines_text.append(text)
        ax_m.set_title(plain(text), fontsize=9)
        _circle(ax_c, ks, s.known, new=s.pair)
    fig.suptitle(plain(f"{sol.mechanism.name}: {w['kennedy_title']}\n{w['theorem']}"), fontsize=10)
    if ks.from_velocities:
        lines_text.append(w["velocities_taken"].format(
            pairs=", ".join(ks.label(p) for p in ks.from_velocities)))
    _steps_box(fig, lines_text)
    return fig
