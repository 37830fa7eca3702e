"""A derivation as a document a teacher can hand out: Markdown with LaTeX maths, or LaTeX.

One function walks the notes' order (symbols, position equations, their time derivative,
the matrix form, J, Q, det J and the singular configurations, K, the accelerations and L,
the dynamics, the numbers at one input); two small writers turn its headings, paragraphs,
equations and tables into Markdown or LaTeX.  The sentences come from :mod:`._words`, in
the language asked for; the maths comes from sympy's LaTeX printer.
"""
from __future__ import annotations

import math
import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

from kinelab._files import atomic_write
from kinelab.derive._errata import marks
from kinelab.derive._simplify import READABLE_OPS, size
from kinelab.derive._words import WORDS
from kinelab.errors import ModelError, check_choice

__all__ = ["document", "symbol_latex", "write_pdf", "compile_latex", "tex_engine", "TEX_ENGINES"]

TEX_ENGINES = ("lualatex", "xelatex", "pdflatex", "tectonic")
_GREEK = {"alpha", "beta", "gamma", "delta", "theta", "phi", "psi", "omega", "tau", "rho", "sigma",
          "lambda", "mu", "nu", "eta", "xi", "zeta", "kappa", "chi", "epsilon"}
_TEX_TEXT = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&",
             "#": r"\#", "%": r"\%", "_": r"\_", "^": r"\textasciicircum{}",
             "~": r"\textasciitilde{}"}


def _tex_text(s: str) -> str:
    return "".join(_TEX_TEXT.get(c, c) for c in s)


def _fmt(v: float) -> str:
    """A number as the documents show it: 10 significant digits, no '-0'."""
    v = float(v)
    if not math.isfinite(v):
        return str(v)
    out = f"{v:.10g}"
    return "0" if out in ("-0", "0") else out


# -- symbols in LaTeX -------------------------------------------------------------------------
def _name_latex(name: str) -> str:
    """``theta_coupler`` -> ``\\theta_{\\text{coupler}}``, ``L_2`` -> ``L_{2}``, ``x_O2`` ->
    ``x_{O_{2}}``; a name kinelab made unique with primes keeps them."""
    primes = len(name) - len(name.rstrip("'"))
    name = name.rstrip("'")
    base, _, sub = name.partition("_")

    def part(s: str) -> str:
        if s in _GREEK:
            return "\\" + s
        if re.fullmatch(r"[A-Za-z]|\d+", s):
            return s
        m = re.fullmatch(r"([A-Za-z])(\d+)", s)
        if m:
            return f"{m.group(1)}_{{{m.group(2)}}}"
        return r"\text{" + _tex_text(s) + "}"
    out = part(base) if base else r"\text{}"
    if sub:
        out += "_{" + ",".join(part(p) for p in sub.split(",")) + "}"
    return out + "'" * primes


def _over(accent: str, tex: str) -> str:
    """An accent over a symbol's letter, not over its subscript: ``\\dot{\\theta}_{\\text{rod}}``."""
    depth = 0
    for i, ch in enumerate(tex):
        depth += (ch == "{") - (ch == "}")
        if ch == "_" and depth == 0:
            return f"\\{accent}{{{tex[:i]}}}{tex[i:]}"
    return f"\\{accent}{{{tex}}}"


# -- lines that fit the page -------------------------------------------------------------------
_WIDTH = 76          # the width of a displayed line, in characters of maths (about 0.5 em each)
_SMALL = 0.7         # a subscript's or superscript's size
_COMMAND_WIDTH = {"sin": 2.6, "cos": 2.6, "tan": 2.6, "det": 2.6, "quad": 2.0, "qquad": 4.0,
                  ",": 0.3, ";": 0.5, "!": 0.0, " ": 0.5, "cdot": 1.2, "to": 2.0,
                  "partial": 1.0, "infty": 1.4, "circ": 0.6}
_AS_WIDE_AS_ARGUMENT = {"dot", "ddot", "hat", "bar", "tilde", "vec", "mathrm", "mathbf", "mathit",
            "operatorname", "text", "texttt", "emph", "sqrt", "displaystyle"}
_TOKEN = re.compile(r"\\[A-Za-z]+|\\.|\s+|.", re.S)


def _width(tex: str) -> float:
    """About how wide a line of LaTeX maths is set, in characters (about 0.5 em each): a
    fraction as wide as its wider part, a matrix as its columns, scripts smaller, markup
    nothing.  What decides where a long expression is broken: near enough to keep every
    line of a document inside the page."""
    tokens = [t for t in _TOKEN.findall(tex) if not t.isspace()]
    width, _ = _width_of(tokens, 0, ())
    return width


def _width_of(tokens: list[str], i: int, stop: tuple) -> tuple[float, int]:
    """The width of ``tokens`` from ``i`` up to one of ``stop`` (not taken), and where it
    stopped."""
    total = 0.0
    while i < len(tokens) and tokens[i] not in stop:
        w, i = _width_of_item(tokens, i)
        total += w
    return total, i


def _width_of_item(tokens: list[str], i: int) -> tuple[float, int]:
    """The width of one item at ``i`` (a group, a command with its arguments, a character)
    and the index after it."""
    t = tokens[i]
    if t == "{":
        w, i = _width_of(tokens, i + 1, ("}",))
        return w, i + 1
    if t in ("^", "_"):
        if i + 1 >= len(tokens):
            return 0.0, i + 1
        w, i = _width_of_item(tokens, i + 1)
        return _SMALL * w, i
    if t.startswith("\\") and len(t) > 1:
        name = t[1:]
        if name == "frac":
            a, i = _width_of_item(tokens, i + 1)
            b, i = _width_of_item(tokens, i)
            return max(a, b) + 0.6, i
        if name in ("left", "right"):
            return (0.0 if i + 1 < len(tokens) and tokens[i + 1] == "." else 0.7), i + 2
        if name == "begin":
            return _width_of_matrix(tokens, i)
        if name in _AS_WIDE_AS_ARGUMENT:
            return _width_of_item(tokens, i + 1) if i + 1 < len(tokens) else (0.0, i + 1)
        return _COMMAND_WIDTH.get(name, 1.0), i + 1
    if t in "+-=<>":
        return 2.0, i + 1
    if t in "()[]|,.;:'":
        return 0.6, i + 1
    return 1.0, i + 1


def _width_of_matrix(tokens: list[str], i: int) -> tuple[float, int]:
    """A ``\\begin{...} ... \\end{...}``: its columns' widths and the space between them."""
    j = tokens.index("}", i) + 1 if "}" in tokens[i:] else len(tokens)   # past \begin{matrix}
    columns: list[float] = []
    col, cell = 0, 0.0
    while j < len(tokens):
        t = tokens[j]
        if t == "\\end":
            j = tokens.index("}", j) + 1 if "}" in tokens[j:] else len(tokens)
            break
        if t in ("&", "\\\\"):
            while len(columns) <= col:
                columns.append(0.0)
            columns[col] = max(columns[col], cell)
            col, cell = (col + 1 if t == "&" else 0), 0.0
            j += 1
            continue
        w, j = _width_of_item(tokens, j)
        cell += w
    while len(columns) <= col:
        columns.append(0.0)
    columns[col] = max(columns[col], cell)
    return sum(columns) + 2.0 * (len(columns) - 1) + 1.4, j


def _broken(e, tex, width: float = _WIDTH) -> list[str]:
    """The LaTeX of a sum as pieces to set on lines one after the other: its terms, gathered
    up to ``width`` (see :func:`_width`) a line, each line but the first starting with its
    sign; a term longer than a line that is a factor times a sum, ``c (a + b + ...)``, is
    broken inside its brackets (``\\left( ... \\right.`` on one line, ``\\left. ... \\right)``
    on the last), after the factor alone when the factor is itself long; a longer product
    of factors goes on over lines that start with ``\\cdot``."""
    import sympy as sp

    pieces: list[str] = []
    for term in (e.as_ordered_terms() if isinstance(e, sp.Add) else [e]):
        text = tex(term)
        sums = [f for f in sp.Mul.make_args(term) if isinstance(f, sp.Add)]
        if _width(text) > width and isinstance(term, sp.Mul) and len(sums) == 1:
            factor = tex(sp.Mul(*(f for f in sp.Mul.make_args(term) if f is not sums[0])))
            alone = _width(factor) > width / 3
            inner = _broken(sums[0], tex, width - (4 if alone else _width(factor) + 4))
            if (len(inner) > 1 or alone) and _width(factor) < width - 4:
                if alone:
                    pieces.append(factor + r" \left( \right.")
                last = len(inner) - 1
                pieces += [("" if k or alone else factor + " ")
                           + (r"\left(" if k == 0 and not alone else r"\left.")
                           + " " + line + " " + (r"\right)" if k == last else r"\right.")
                           for k, line in enumerate(inner)]
                continue
        if _width(text) > width and isinstance(term, sp.Mul):
            pieces += _fraction(term, tex, width) or _product(term, tex, width) or [text]
            continue
        pieces.append(text)
    lines: list[str] = []
    for piece in pieces:
        goes_on = piece.startswith((r"\left.", r"\cdot"))
        signed = piece if not lines else (piece if piece.startswith("- ") or goes_on
                                          else "+ " + piece)
        if lines and not goes_on and not lines[-1].endswith(r"\left( \right.") \
                and _width(lines[-1]) + _width(signed) < width:
            lines[-1] += " " + signed
        else:
            lines.append(signed)
    return lines


def _fraction(term, tex, width: float) -> list[str]:
    """A fraction too long for a line with its numerator and denominator each broken over
    lines (a ``gathered`` block over another); empty where it is not a fraction."""
    import sympy as sp
    sign = ""
    if term.could_extract_minus_sign():
        sign, term = "- ", -term
    top, bottom = sp.fraction(term)
    if bottom == 1:
        return []

    def block(e) -> str:
        lines = _broken(e, tex, width - 3)
        return lines[0] if len(lines) == 1 else (
            r"\begin{gathered}" + r" \\ ".join(lines) + r"\end{gathered}")
    return [sign + r"\frac{" + block(top) + "}{" + block(bottom) + "}"]


def _product(term, tex, width: float) -> list[str]:
    """A product too long for a line as lines of its factors, each but the first starting
    with ``\\cdot``; empty where the product has a denominator (it is set as a fraction)."""
    import sympy as sp
    factors = term.as_ordered_factors()
    if any(f.is_Pow and f.exp.is_negative for f in factors) or any(
            f.is_Rational and not f.is_Integer for f in factors):
        return []
    groups: list[list] = [[]]
    for f in factors:
        if groups[-1] and _width(tex(sp.Mul(*groups[-1], f))) > width - 2:
            groups.append([])
        groups[-1].append(f)
    if len(groups) < 2:
        return []
    return [("" if k == 0 else r"\cdot ") + tex(sp.Mul(*g)) for k, g in enumerate(groups)]


def _equation(lhs: str, e, tex, rhs: bool = True) -> list[str]:
    """The lines of ``lhs = e`` in an alignment, broken where the right side is long (with
    ``rhs`` False, of ``e = lhs``: set from the left margin, broken where long, ``= lhs`` on
    its last line)."""
    if rhs:
        lines = _broken(e, tex, _WIDTH - max(_width(lhs), 10.0) - 4)
        return [lhs + " &= " + lines[0]] + [r"&\quad " + line for line in lines[1:]]
    text = tex(e)
    if _width(text) + _width(lhs) + 2 <= _WIDTH:
        return ["& " + text + " = " + lhs]
    lines = _broken(e, tex, _WIDTH - 6)
    return (["& " + lines[0]] + [r"&\quad " + line for line in lines[1:-1]]
            + [r"&\quad " + lines[-1] + " = " + lhs])


def _equation_of_sums(left, right, tex) -> list[str]:
    """The lines of ``left = right``, two sums, set from the left margin: the left side,
    broken where long, then ``= right``, broken where long."""
    lhs, rhs = tex(left), tex(right)
    if _width(lhs) + _width(rhs) + 2 <= _WIDTH:
        return ["& " + lhs + " = " + rhs]
    lines = _broken(left, tex, _WIDTH - 6)
    rhs = _broken(right, tex, _WIDTH - 6)
    return (["& " + lines[0]] + [r"&\quad " + line for line in lines[1:]]
            + ["&= " + rhs[0]] + [r"&\quad " + line for line in rhs[1:]])


def _numbers_lines(name: str, a: np.ndarray) -> tuple[list[str], bool]:
    """``name = a``, a matrix of numbers, as display lines: whole where it fits the page,
    else row by row its entries that are not 0 (``name_{ij} = ...``); and whether it was
    written by entries."""
    whole = name + " &= " + _matrix(a)
    if _width(whole) <= _WIDTH:
        return [whole], False
    a = _rounded(a)
    lines = []
    for i, row in enumerate(a):
        line = ""
        for j, x in enumerate(row):
            if x == 0:
                continue
            entry = f"{name}_{{{i + 1}{j + 1}}} = {_fmt(x)}"
            if line and _width(line + entry) + 3 > _WIDTH:
                lines.append("& " + line)
                line = ""
            line += (r",\quad " if line else "") + entry
        if line:
            lines.append("& " + line)
    return lines, True


def _matrix_lines(name: str, A, tex) -> tuple[list[str], bool]:
    """``name = A`` as display lines: the matrix whole where it fits the page, else its
    entries one by one (``name_{ij} = ...``, broken where long, the zeros left out); and
    whether it was written by entries."""
    whole = f"{name} &= {tex(A)}"
    if _width(whole) <= _WIDTH:
        return [whole], False
    lines = []
    for i in range(A.rows):
        for j in range(A.cols):
            if A[i, j] != 0:
                lines += _equation(f"{name}_{{{i + 1}{j + 1}}}" if A.rows < 10 and A.cols < 10
                                   else f"{name}_{{{i + 1},{j + 1}}}", A[i, j], tex)
    return lines, True


def symbol_latex(d) -> dict:
    """The LaTeX of every symbol of a derivation (and of its dynamics)."""
    eq = d.equations
    names = {}
    for s in tuple(eq.q) + tuple(eq.S) + tuple(eq.parameters):
        names[s] = _name_latex(str(s))
    for s in tuple(eq.q) + tuple(eq.S):
        names[d.dot(s)] = _over("dot", names[s])
        names[d.ddot(s)] = _over("ddot", names[s])
    M = len(eq.q)
    for i, s in enumerate(eq.S):
        for k in range(M):
            names[d.K_symbols[i * M + k]] = ("K_{" + names[s] + "}" if M == 1
                                             else "K_{" + names[s] + f",{k + 1}}}")
    if d.dynamics is not None:
        kd = d.dynamics
        for i, s in enumerate(eq.S):
            for a in range(M):
                for b in range(M):
                    names[kd.L_symbols[i * M * M + a * M + b]] = (
                        "L_{" + names[s] + "}" if M == 1 else "L_{" + names[s] + f",{a + 1}{b + 1}}}")
        for s in list(kd.parameters) + list(kd.load_values) + list(kd.tau):
            names[s] = _name_latex(str(s))
    return names


# -- writers --------------------------------------------------------------------------------
class _Markdown:
    fmt = "md"
    arrow = " → "
    degree = "°"

    def __init__(self):
        self.out: list[str] = []

    def name(self, s: str) -> str:
        ticks = "``" if "`" in s else "`"
        pad = " " if "`" in s else ""
        return f"{ticks}{pad}{s}{pad}{ticks}"

    def text(self, template: str, **fields) -> str:
        return template.format(**fields)

    def heading(self, text: str, level: int = 2) -> None:
        self.out.append("#" * level + " " + text)

    def para(self, text: str) -> None:
        self.out.append(text)

    def display(self, lines: list[str]) -> None:
        body = lines[0] if len(lines) == 1 and "&" not in lines[0] else (
            "\\begin{aligned}\n" + " \\\\\n".join(lines) + "\n\\end{aligned}")
        self.out.append("$$\n" + body + "\n$$")

    def items(self, rows: list[str]) -> None:
        self.out.append("\n".join(f"- {r}" for r in rows))

    def table(self, header: list[str], rows: list[list[str]]) -> None:
        def cell(c):
            return c.replace("|", "\\|")
        lines = ["| " + " | ".join(map(cell, header)) + " |",
                 "|" + "|".join(" --- " for _ in header) + "|"]
        lines += ["| " + " | ".join(map(cell, r)) + " |" for r in rows]
        self.out.append("\n".join(lines))

    def finish(self, title: str) -> str:
        return "# " + title + "\n\n" + "\n\n".join(self.out) + "\n"


class _Latex:
    fmt = "tex"
    arrow = " $\\to$ "
    degree = "$^\\circ$"

    def __init__(self, lang: str):
        self.out: list[str] = []
        self.lang = lang

    def name(self, s: str) -> str:
        return r"\texttt{" + _tex_text(s) + "}"

    def text(self, template: str, **fields) -> str:
        """A sentence of the words table in LaTeX: text escaped, maths kept, fields (already
        LaTeX) filled in."""
        out = []
        for piece in re.split(r"(\$[^$]*\$)", template):
            if len(piece) > 1 and piece.startswith("$") and piece.endswith("$"):
                out.append(piece.format(**fields))
                continue
            parts = re.split(r"\{([a-z_]+)\}", piece)       # text, field, text, field ...
            esc = "".join(_tex_text(p) if k % 2 == 0 else f"\0{p}\0" for k, p in enumerate(parts))
            esc = re.sub(r"\*([^*]+)\*", r"\\emph{\1}", esc)
            esc = re.sub(r"`([^`]+)`", r"\\texttt{\1}", esc)
            out.append(re.sub(r"\0([a-z_]+)\0", lambda mt: str(fields[mt.group(1)]), esc))
        return "".join(out)

    def heading(self, text: str, level: int = 2) -> None:
        self.out.append(("\\section*{" if level <= 2 else "\\subsection*{") + text + "}")

    def para(self, text: str) -> None:
        self.out.append(text)

    def display(self, lines: list[str]) -> None:
        if len(lines) == 1 and "&" not in lines[0]:
            self.out.append("\\[\n" + lines[0] + "\n\\]")
        else:
            self.out.append("\\begin{align*}\n" + " \\\\\n".join(lines) + "\n\\end{align*}")

    def items(self, rows: list[str]) -> None:
        self.out.append("\\begin{itemize}\n" + "\n".join(f"\\item {r}" for r in rows)
                        + "\n\\end{itemize}")

    def table(self, header: list[str], rows: list[list[str]]) -> None:
        cols = "l" * len(header)
        lines = [" & ".join(header) + r" \\ \hline"] + [" & ".join(r) + r" \\" for r in rows]
        self.out.append("\\begin{tabular}{" + cols + "}\n" + "\n".join(lines) + "\n\\end{tabular}")

    def finish(self, title: str) -> str:
        head = ["\\documentclass[11pt]{article}", "\\usepackage[T1]{fontenc}",
                "\\usepackage[utf8]{inputenc}", "\\usepackage{amsmath,amssymb}",
                "\\usepackage[margin=2cm]{geometry}", "\\allowdisplaybreaks",
                "\\setlength{\\emergencystretch}{3em}",
                "\\begin{document}", "\\section*{" + title + "}"]
        return "\n".join(head) + "\n\n" + "\n\n".join(self.out) + "\n\n\\end{document}\n"


# -- the document ---------------------------------------------------------------------------
def document(d, fmt: str, *, at=None, lang: str = "en") -> str:
    """The whole document of derivation ``d`` in format ``"md"`` or ``"tex"``."""
    import sympy as sp
    from kinelab.derive._derivation import LANGUAGES
    check_choice("lang", lang, LANGUAGES)
    check_choice("format", fmt, ("md", "tex"))
    words = WORDS[lang]
    w = _Markdown() if fmt == "md" else _Latex(lang)
    eq, m = d.equations, d.model
    names = symbol_latex(d)

    def tex(e) -> str:
        return sp.latex(e, symbol_names=names, fold_func_brackets=True)

    def T(key: str, **fields) -> str:
        return w.text(words[key], **fields)

    def N(s: str) -> str:
        return w.name(s)

    def M_(e) -> str:
        return "$" + tex(e) + "$"

    def notes_differ(section: str) -> None:
        for entry, sentence in marks(d, section, lang):
            text = T("notes_differ", entry=entry) + " " + w.text(sentence)
            # ragged right: the inline maths of a mark leaves TeX few places to break a line
            w.para(text if w.fmt == "md" else "{\\raggedright " + text + "\\par}")
    Mn, n = len(eq.q), len(eq.S)
    title = w.text(words["title"], name=N(m.name))
    w.para(T("intro"))
    _symbols(d, w, T, N, M_)
    # -- position equations
    w.heading(T("position"))
    nl = len(m.links)
    nj = len(m.joints)
    if not eq.loops:
        w.para(T("no_loops"))
    else:
        w.para(T("loops_count_one" if len(eq.loops) == 1 else "loops_count", links=nl,
                 joints=nj, loops=len(eq.loops)))
        row = 0
        for k, lp in enumerate(eq.loops, start=1):
            path = w.arrow.join(N(x) for x in lp.links)
            w.para(T("loop", k=k, path=path))
            lines = []
            for _ in range(2):
                lines += _equation("0", eq.rows[row], tex, rhs=False)
                lines[-1] += " && (" + str(row + 1) + ")"
                row += 1
            w.display(lines)
        if d.redundant:
            w.para(T("redundant_one" if len(d.redundant) == 1 else "redundant",
                     rows=", ".join(f"({i + 1})" for i in d.redundant)))
        notes_differ("position")
    if n:
        _velocity(d, w, T, N, tex)
        notes_differ("jacobian")
        _singular_positions(d, w, T, tex)
        _coefficients(d, w, T, tex)
        notes_differ("coefficients")
        _accelerations(d, w, T, tex)
    if d.dynamics is not None:
        _dynamics(d, w, T, N, tex)
        notes_differ("dynamics")
    _numbers(d, w, T, N, tex, at)
    return w.finish(title)


def _symbols(d, w, T, N, M_) -> None:
    eq, m = d.equations, d.model
    w.heading(T("symbols"))
    w.para(T("symbols_intro"))
    head = [T("col_symbol"), T("col_meaning")]
    rows = []
    ground = m.ground.name
    for k, (s, inp) in enumerate(zip(eq.q, m.inputs)):
        if inp.joint is not None and m.joint(inp.joint).type == "P":
            rows.append([M_(s), T("input_slide", joint=N(inp.joint), name=N(inp.label))])
        else:
            a, b = m.joint(inp.joint).links if inp.joint is not None else inp.links
            key = "input_angle_ground" if a == ground else "input_angle"
            rows.append([M_(s), T(key, a=N(a), b=N(b), name=N(inp.label))])
    w.para(T("inputs_head"))
    w.table(head, rows)
    if eq.S:
        rows = []
        for s in eq.S:
            kind, name = eq.unknowns[s]
            if kind == "angle":
                pts = m.link(name).points
                rows.append([M_(s), T("unknown_angle", link=N(name), p=N(pts[0]), r=N(pts[1]))
                             if len(pts) > 1 else T("unknown_angle_one", link=N(name))])
            else:
                j = m.joint(name)
                origin = j.origin or m.link(j.links[0]).points[0]
                rows.append([M_(s), T("unknown_slide", joint=N(name), point=N(j.point),
                                      origin=N(origin))])
        w.para(T("unknowns_head"))
        w.table(head, rows)
    if eq.parameters:
        rows = []
        for s, v in eq.parameters.items():
            rows.append([M_(s), _meaning(eq.meaning[s], d, T, N), _fmt(v)])
        w.para(T("parameters_head"))
        w.table(head + [T("col_value")], rows)


def _meaning(meaning: tuple, d, T, N) -> str:
    m = d.model
    kind = meaning[0]
    if kind == "length":
        pts = m.link(meaning[1]).points
        return T("length", link=N(meaning[1]), a=N(pts[0]), b=N(pts[1]))
    if kind == "distance":
        return T("distance", link=N(meaning[1]), a=N(meaning[2]), b=N(meaning[3]))
    if kind == "direction":
        root = d.equations.roots[meaning[1]]
        if root == m.ground.name:
            return T("direction_ground", a=N(meaning[2]), b=N(meaning[3]))
        return T("direction", a=N(meaning[2]), b=N(meaning[3]), root=N(root))
    if kind == "link_offset":
        root = d.equations.roots[meaning[1]]
        if root == m.ground.name:
            return T("link_offset_ground", link=N(meaning[1]))
        return T("link_offset", link=N(meaning[1]), root=N(root))
    if kind == "axis":
        j = m.joint(meaning[1])
        root = d.equations.roots[j.links[0]]
        if root == m.ground.name:
            return T("axis_ground", joint=N(j.name))
        return T("axis", joint=N(j.name), root=N(root))
    if kind == "offset":
        j = m.joint(meaning[1])
        return T("offset", joint=N(j.name), origin=N(j.origin or m.link(j.links[0]).points[0]))
    return T(kind, point=N(meaning[1]))


def _velocity(d, w, T, N, tex) -> None:
    import sympy as sp
    eq = d.equations
    w.heading(T("velocity"))
    w.para(T("velocity_intro"))
    v = d.velocity_equations().applyfunc(sp.expand)
    w.display([line for e in v for line in _equation("0", e, tex, rhs=False)])
    w.para(T("matrix_form"))
    Sd = sp.Matrix([d.dot(s) for s in eq.S])
    qd = sp.Matrix([d.dot(s) for s in eq.q])
    whole = (tex(d.J) + tex(Sd) + " + " + tex(d.Q) + tex(qd if len(eq.q) > 1 else qd[0])
             + " = " + tex(sp.zeros(len(eq.S), 1)))
    if _width(whole) <= _WIDTH:
        w.display([whole])
    else:                      # J and Q one after the other, each whole or entry by entry
        (J, J_entries), (Q, Q_entries) = _matrix_lines("J", d.J, tex), _matrix_lines("Q", d.Q, tex)
        w.display(J + Q)
        if J_entries or Q_entries:
            w.para(T("zeros_left_out"))
    w.para(T("matrix_names"))
    w.heading(T("jacobian"))
    w.para(T("det"))
    if d.readable["det_J"]:
        w.display(_equation(r"\det J", d.det_J, tex))
    else:
        w.para(T("det_large", ops=size(d.det_J)))
    if not d.singularities:
        w.para(T("sing_none"))
        return
    w.para(T("singular_intro"))
    w.items([_singular_words(s, d, w, T, N, tex) for s in d.singularities])


def _singular_words(s, d, w, T, N, tex) -> str:
    m = d.model
    f = "$" + tex(s.factor) + " = 0$"
    if s.kind == "slide":
        joint, point, origin = s.names
        j = m.joint(joint)
        pivot = ""
        guide = j.links[0]
        if any(k.type == "R" and k.point == origin for k in m.joints_of(guide)):
            pivot = T("sing_pivot", link=N(guide))
        return T("sing_slide", factor=f, point=N(point), origin=N(origin), joint=N(joint),
                 pivot=pivot)
    if s.kind in ("in_line", "perpendicular"):
        return T("sing_" + s.kind, factor=f, a=N(s.names[0]), b=N(s.names[1]))
    if s.kind == "angle":
        values = f" {T('or')} ".join(f"{_fmt(v)}{w.degree}" for v in s.values)
        return T("sing_angle", factor=f, link=N(s.names[0]), values=values)
    return T("sing_other", factor=f)


def _singular_positions(d, w, T, tex) -> None:
    """Over the model's input range, which conditions det J = 0 are reached and where (the
    toggles), and where each secondary coordinate turns back (its dead centres, K = 0): the
    numbers of :func:`kinelab.kinematics.toggles` and :func:`kinelab.kinematics.dead_centres`."""
    import sympy as sp
    from kinelab import kinematics
    from kinelab.errors import KinelabError
    eq, m = d.equations, d.model
    w.heading(T("reach"), level=3)
    if len(eq.q) != 1:
        _singular_positions_of_several(d, w, T, tex)
        return
    q_sym = eq.q[0]
    slide_input = m.inputs[0].joint is not None and m.joint(m.inputs[0].joint).type == "P"

    def at(v: float) -> str:
        v = 0.0 if abs(v) < 1e-9 * max(1.0, abs(hi - lo)) else v
        shown = f"${tex(q_sym)} = {_fmt(v)}$"
        return shown + (" m" if slide_input else f" ({_fmt(round(math.degrees(v), 7))}{w.degree})")

    def value(s, v: float, kind: str) -> str:
        if kind == "angle":
            return f"${tex(s)} = {_fmt(v)}$ ({_fmt(round(math.degrees(v), 7))}{w.degree})"
        return f"${tex(s)} = {_fmt(v)}$ m"
    try:
        lo, hi = kinematics.input_span(m)
        found = kinematics.toggles(m, lo, hi)
        turns = []
        for s in eq.S:
            kind, name = eq.unknowns[s]
            if kind == "angle" or name in kinematics.plan(m).slide_item:
                turns.append((s, kinematics.dead_centres(m, name, lo, hi)))
        reached = _factors_reached(d, found, lo, hi) if d.singularities else []
    except KinelabError as exc:
        w.para(T("reach_failed", why=_tex_or_md(w, str(exc))))
        return
    span = f"${tex(q_sym)} \\in [{_fmt(lo)}, {_fmt(hi)}]$" + (
        " m" if slide_input else
        f" ([{_fmt(round(math.degrees(lo), 7))}, {_fmt(round(math.degrees(hi), 7))}]{w.degree})")
    w.para(T("reach_intro", span=span))
    rows = []
    for s, hits in zip(d.singularities, reached):
        f = "$" + tex(s.factor) + " = 0$"
        if hits:
            where = "; ".join(f"{at(t.q)}, {T(t.kind)}" for t in hits)
            rows.append(T("toggle_reached", factor=f, where=where))
        else:
            rows.append(T("toggle_not_reached", factor=f))
    if rows:
        w.para(T("toggle_intro"))
        w.items(rows)
    else:
        w.para(T("toggle_none"))
    w.para(T("dead_intro"))
    rows = []
    for s, dc in turns:
        if len(dc):
            where = "; ".join(T("dead_where", q=at(a), value=value(s, b, dc.kind))
                              for a, b in zip(dc.q, dc.value))
            rows.append(T("dead_at", symbol=f"${tex(s)}$", where=where))
        else:
            rows.append(T("dead_none", symbol=f"${tex(s)}$"))
    w.items(rows)


def _singular_positions_of_several(d, w, T, tex) -> None:
    """:func:`_singular_positions` of a model of several inputs: over the box of the inputs'
    ranges, which conditions det J = 0 are reached, at how many of the points
    :func:`kinelab.kinematics.toggles` finds, and a few of them."""
    from kinelab import kinematics
    from kinelab.errors import KinelabError
    eq, m = d.equations, d.model
    p = kinematics.plan(m)
    angle = [kind == "angle" for kind in p.input_kinds]

    def value(k: int, v: float) -> str:
        shown = f"${tex(eq.q[k])} = {_fmt(v)}$"
        return shown + (f" ({_fmt(round(math.degrees(v), 7))}{w.degree})" if angle[k] else " m")

    def at(q) -> str:
        return ", ".join(value(k, v) for k, v in enumerate(q))
    try:
        locus = kinematics.toggles(m)
        reached = _factors_reached_in_box(d, locus) if d.singularities else []
    except KinelabError as exc:
        w.para(T("reach_failed", why=_tex_or_md(w, str(exc))))
        return
    span = ", ".join(
        f"${tex(q)} \\in [{_fmt(a)}, {_fmt(b)}]$" + (
            f" ([{_fmt(round(math.degrees(a), 7))}, {_fmt(round(math.degrees(b), 7))}]"
            f"{w.degree})" if is_angle else " m")
        for q, a, b, is_angle in zip(eq.q, locus.lo, locus.hi, angle))
    w.para(T("reach_intro_many", span=span, count=len(eq.q),
             grid=" \\times ".join(str(n) for n in locus.samples)))
    rows = []
    for s, hits in zip(d.singularities, reached):
        f = "$" + tex(s.factor) + " = 0$"
        if len(hits):
            shown = hits[np.unique(np.round(np.linspace(0, len(hits) - 1,
                                                        min(len(hits), 3))).astype(int))]
            where = "; ".join(f"{at(locus.q[i])}, {T('many ' + locus.kind[i])}" for i in shown)
            rows.append(T("toggle_reached_many", factor=f, count=len(hits), where=where))
        else:
            rows.append(T("toggle_not_reached_box", factor=f))
    if rows:
        w.para(T("toggle_intro"))
        w.items(rows)
    elif not locus.reached:
        w.para(T("toggle_none_box"))
    w.para(T("dead_many"))


def _factor_values(d):
    """The function of inputs ``q`` ((N,) for one input, (N, M) for M) that gives the
    absolute value of each factor of det J the derivation lists there, (factors, N), with S
    from :func:`kinelab.kinematics.analyze` (NaN where the loops do not close)."""
    import sympy as sp
    from kinelab.kinematics import analyze
    eq = d.equations
    f = sp.lambdify(list(eq.q) + list(eq.S) + list(d.parameters),
                    [s.factor for s in d.singularities], modules="numpy")
    constants = list(d.parameters.values())

    def values(q: np.ndarray) -> np.ndarray:
        sol = analyze(d.model, q, unreachable="mask", at_singular="flag")
        S = [sol.angle(name) if kind == "angle" else sol.slide(name)
             for kind, name in (eq.unknowns[s] for s in eq.S)]
        inputs = q.T if q.ndim == 2 else (q,)
        with np.errstate(invalid="ignore"):
            out = [np.broadcast_to(np.asarray(v, float), q.shape[:1])
                   for v in f(*inputs, *S, *constants)]
        return np.abs(np.array(out))              # (factors, N)
    return values


def _factors_reached_in_box(d, locus) -> list[np.ndarray]:
    """For each factor of det J the derivation lists, the indices of the points of
    ``locus`` (a :class:`~kinelab.kinematics.ToggleLocus`) at which it is zero: its value
    there, against its largest over a coarse grid of the box, below 1e-4 (as
    :func:`_factors_reached`)."""
    M = len(d.equations.q)
    values = _factor_values(d)
    side = max(3, int(round(4096 ** (1.0 / M))))
    axes = [np.linspace(a, b, side) for a, b in zip(locus.lo, locus.hi)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, M)
    with np.errstate(invalid="ignore"):
        scale = np.nanmax(np.where(np.isnan(values(grid)), -np.inf, values(grid)), axis=1)
    if not len(locus):
        return [np.empty(0, int) for _ in d.singularities]
    there = values(locus.q)
    return [np.flatnonzero(row <= 1e-4 * big) for row, big in zip(there, scale)]


def _factors_reached(d, found, lo: float, hi: float) -> list[list]:
    """For each factor of det J the derivation lists, the toggles of ``found`` at which it is
    zero: its value there, against its largest over a sweep of the range, below 1e-4 (at a
    limit position a factor falls like the square root of the distance to it)."""
    values = _factor_values(d)
    scale = np.nanmax(values(np.linspace(lo, hi, 181)), axis=1)
    if not found:
        return [[] for _ in d.singularities]
    there = values(np.array([t.q for t in found]))
    return [[t for t, v in zip(found, row) if v <= 1e-4 * big] for row, big in zip(there, scale)]


def _tex_or_md(w, text: str) -> str:
    return text if w.fmt == "md" else _tex_text(text)


def _coefficients(d, w, T, tex) -> None:
    eq = d.equations
    w.heading(T("coefficients"))
    if d.readable["K"]:
        w.para(T("K_intro"))
        lines = []
        for i in range(len(eq.S)):
            for k in range(len(eq.q)):
                sym = d.K_symbols[i * len(eq.q) + k]
                lines += _equation(tex(sym), d.K[i, k], tex)
        w.display(lines)
    else:
        w.para(T("K_large", ops=size(d.K)))


def _accelerations(d, w, T, tex) -> None:
    import sympy as sp
    eq = d.equations
    M = len(eq.q)
    w.heading(T("acceleration"))
    acc = d.acceleration_equations()
    Sdd = sp.Matrix([d.ddot(s) for s in eq.S])
    rhs = (-(acc - d.J * Sdd)).applyfunc(sp.expand)
    if max(size(e) for e in rhs) <= READABLE_OPS:
        whole = tex(d.J) + tex(Sdd) + " = " + tex(rhs)
        if _width(whole) <= _WIDTH:
            w.para(T("acceleration_intro"))
            w.display([whole])
        else:
            w.para(T("acceleration_rows"))
            w.display([line for i in range(len(eq.S))
                       for line in _equation_of_sums(sp.expand((d.J * Sdd)[i]), rhs[i], tex)])
    else:
        w.para(T("acceleration_large", ops=size(rhs)))
    w.para(T("L_intro" if M == 1 else "L_intro_many"))

    def lines_of(L):
        out = []
        for i, s in enumerate(eq.S):
            for a in range(M):
                for b in range(M):
                    e = L[i] if M == 1 else L[i, a, b]
                    label = ("L_{" + tex(s) + "}" if M == 1
                             else "L_{" + tex(s) + f",{a + 1}{b + 1}}}")
                    out += _equation(label, e, tex)
        return out
    if d.readable["L_in_K"]:
        w.display(lines_of(d.L_in_K))
    else:
        w.para(T("L_in_K_large", ops=size(d.L_in_K)))
    if d.readable["L"]:
        w.para(T("L_explicit"))
        w.display(lines_of(d.L))
    else:
        w.para(T("L_large", ops=size(d.L)))


def _dynamics(d, w, T, N, tex) -> None:
    import sympy as sp
    kd = d.dynamics
    w.heading(T("dynamics"))
    w.para(T("dynamics_intro", bodies=len(kd.bodies)))
    rows = []
    for b in kd.bodies:
        if not b.turns:
            rows.append(T("body_point", m=_quantity(kd, f"m_{b.name}", tex), point=N(b.point),
                          link=N(b.link)))
        elif b.mass or b.inertia:
            rows.append(T("body_link", link=N(b.link), m=_quantity(kd, f"m_{b.name}", tex),
                          I=_quantity(kd, f"I_{b.name}", tex), point=N(b.point)))
        else:
            rows.append(T("body_loaded", link=N(b.link), point=N(b.point)))
    w.items(rows)
    loads = []
    for s, (kind, obj, law) in kd.load_values.items():
        if kind != "tension":
            loads.append(T("load_force", symbol="$" + tex(s) + "$", law=N(str(law))))
        else:
            loads.append(T("load_force", symbol="$" + tex(s) + "$", law="$" + tex(law) + "$"))
    gsym = next((s for s in kd.parameters if str(s) == "g"), None)
    if gsym is not None:
        g = np.asarray(kd.loads.gravity, float)
        loads.insert(0, T("gravity", g=f"${tex(gsym)} = {_fmt(kd.parameters[gsym])}$",
                          direction=f"$({_fmt(g[0] / np.hypot(*g))}, {_fmt(g[1] / np.hypot(*g))})$"))
    if loads:
        w.para(T("loads_head", items="; ".join(loads)))
    Ks = sp.Matrix(len(d.S), len(d.q), d.K_symbols) if d.S else sp.zeros(0, len(d.q))
    C = sp.eye(len(d.q)).col_join(Ks) if d.S else sp.eye(len(d.q))
    w.para(T("C_intro"))
    C_lines, C_entries = _matrix_lines("C", C, tex)
    w.display(C_lines)
    if C_entries:
        w.para(T("zeros_left_out"))
    w.para(T("D_intro"))
    if max((size(e) for e in kd.D), default=0) <= READABLE_OPS and kd.D.cols <= 12:
        D_lines, D_entries = _matrix_lines("D", kd.D, tex)
        w.display(D_lines)
        if D_entries:
            w.para(T("zeros_left_out"))
    else:
        w.para(T("matrix_large", what="$D$", ops=size(kd.D)))
    w.para(T("f_intro"))
    if max((size(e) for e in kd.f), default=0) <= READABLE_OPS:
        w.display([line for k, e in enumerate(kd.f) for line in _equation(f"f_{{{k + 1}}}", e, tex)])
    else:
        w.para(T("matrix_large", what="$f$", ops=size(kd.f)))
    w.para(T("tau_intro"))
    if max(size(e) for e in kd.equations) <= 6 * READABLE_OPS:
        w.display([line for t, e in zip(kd.tau, kd.equations) for line in _equation(tex(t), e, tex)])
    else:
        w.para(T("tau_large", ops=size(kd.equations)))


def _quantity(kd, name: str, tex) -> str:
    s = next((s for s in kd.parameters if str(s) == name), None)
    if s is None:
        return "$0$"
    return f"${tex(s)} = {_fmt(kd.parameters[s])}$"


def _numbers(d, w, T, N, tex, at) -> None:
    eq, m = d.equations, d.model
    M, n = len(eq.q), len(eq.S)
    if at is None:
        # the sketch's inputs, assembled: an angle within rounding of a whole degree (the
        # sketch drew 0, assembly left -8e-10) is that degree
        q = np.array([eq.sketch[s] for s in eq.q])
        whole = np.radians(np.round(np.degrees(q)))
        angles = np.array([inp.joint is None or m.joint(inp.joint).type != "P" for inp in m.inputs])
        q = np.where(angles & (np.abs(q - whole) < 1e-9), whole, q)
    else:
        from kinelab.derive._derivation import inputs
        q = inputs(at, M, "at", one=True)[0]
    kinds = [("slide" if inp.joint is not None and m.joint(inp.joint).type == "P" else "angle")
             for inp in m.inputs]
    def value(s, v, kind):
        unit = f" ({_fmt(math.degrees(v))}{w.degree})" if kind == "angle" else " m"
        return f"${tex(s)} = {_fmt(v)}$" + unit
    shown = ", ".join(value(s, v, k) for s, v, k in zip(eq.q, q, kinds))
    w.heading(T("numbers", at=shown))
    v = d.evaluate(q if M > 1 else q[0])
    w.para(T("numbers_intro"))
    if n:
        w.table([T("col_symbol"), T("col_engine")],
                [["$" + tex(s) + "$", _fmt(v.S[0, i])] for i, s in enumerate(eq.S)])
        w.para(T("residual", r=_fmt(np.abs(v.Phi[0]).max())))
        w.para(T("J_value"))
        J, Q = "J = " + _matrix(v.J[0]), "Q = " + _matrix(v.Q[0])
        if _width(J + Q) + 3 <= _WIDTH:
            w.display([J + ",\\quad " + Q])
        else:
            (J, J_entries), (Q, Q_entries) = _numbers_lines("J", v.J[0]), _numbers_lines("Q", v.Q[0])
            w.display(J + Q)
            if J_entries or Q_entries:
                w.para(T("zeros_left_out"))
        w.para(T("det_value", det=_fmt(v.det_J[0]), engine=_fmt(v.engine_det_J[0])))
        if not np.all(np.isfinite(v.K_engine[0])):
            w.para(T("singular_here"))
            return
        rows = []
        for i, s in enumerate(eq.S):
            for k in range(M):
                sym = d.K_symbols[i * M + k]
                a, b = v.K[0, i, k], v.K_engine[0, i, k]
                rows.append(["$" + tex(sym) + "$", _fmt(a), _fmt(b), _fmt(a - b)])
        for i, s in enumerate(eq.S):
            for a_ in range(M):
                for b_ in range(M):
                    label = "L_{" + tex(s) + ("}" if M == 1 else f",{a_ + 1}{b_ + 1}}}")
                    a, b = v.L[0, i, a_, b_], v.L_engine[0, i, a_, b_]
                    rows.append(["$" + label + "$", _fmt(a), _fmt(b), _fmt(a - b)])
        w.table([T("col_symbol"), T("col_derived"), T("col_engine"), T("col_difference")], rows)
    if d.dynamics is not None:
        from kinelab.dynamics import inverse
        kd = d.dynamics
        qd = np.array([inp.speed or 1.0 for inp in m.inputs])
        qdd = np.array([inp.acceleration for inp in m.inputs])
        pick = (lambda a: a) if M > 1 else (lambda a: a[0])
        mine = kd.efforts(pick(q), pick(qd), pick(qdd))[0]
        ref = np.reshape(inverse(m, pick(q), pick(qd), pick(qdd), loads=kd.loads,
                                 masses=kd.masses, reactions=False).input_forces, (M,))
        w.para(T("efforts_head", qd=", ".join(_fmt(x) for x in qd),
                 qdd=", ".join(_fmt(x) for x in qdd)))
        w.table([T("col_symbol"), T("col_derived"), "kinelab.dynamics.inverse", T("col_difference")],
                [["$" + tex(t) + "$", _fmt(a), _fmt(b), _fmt(a - b)]
                 for t, a, b in zip(kd.tau, mine, ref)])
        w.para(T("efforts_note"))


def _rounded(a: np.ndarray) -> np.ndarray:
    """A matrix of numbers, 2-D, with 0 for an entry within rounding of 0 against the largest
    (the cosine of a right angle, 6e-17)."""
    a = np.atleast_2d(np.asarray(a, float))
    finite = np.abs(a[np.isfinite(a)])
    big = finite.max() if finite.size else 0.0
    return np.where(np.abs(a) <= 1e-13 * big, 0.0, a)


def _matrix(a: np.ndarray) -> str:
    """A matrix of numbers in LaTeX (see :func:`_rounded`)."""
    rows = [" & ".join(_fmt(x) for x in row) for row in _rounded(a)]
    return r"\left[\begin{matrix}" + r" \\ ".join(rows) + r"\end{matrix}\right]"


# -- PDF ----------------------------------------------------------------------------------------
def tex_engine() -> str | None:
    """The first TeX engine found on the PATH, or None."""
    return next((e for e in TEX_ENGINES if shutil.which(e)), None)


def write_pdf(tex: str, path: str | Path) -> Path:
    """Compile a LaTeX document to ``path`` with the first TeX engine found that compiles it
    (an engine may be on the PATH without its packages: lualatex without texlive-luatex).

    Raises
    ------
    ModelError
        No TeX engine is installed (a clear message, no traceback at the command line), or
        every engine found fails (the first one's last lines of log).
    """
    engines = [e for e in TEX_ENGINES if shutil.which(e)]
    if not engines:
        raise ModelError(f"format: PDF needs a TeX engine ({', '.join(TEX_ENGINES)}), and none is "
                         "installed; write --format tex (or md) and compile it elsewhere")
    failures = []
    for engine in engines:
        try:
            data, _ = compile_latex(tex, engine)
        except ModelError as exc:
            failures.append(exc)
            continue
        return atomic_write(Path(path), lambda f: f.write(data), binary=True)
    raise failures[0]


def compile_latex(tex: str, engine: str) -> tuple[bytes, str]:
    """A LaTeX document compiled by ``engine``: the PDF and the engine's log (its warnings,
    such as an overfull line)."""
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "derivation.tex"
        src.write_text(tex, encoding="utf-8")
        cmd = ([engine, "--keep-logs", "derivation.tex"] if engine == "tectonic"
               else [engine, "-interaction=nonstopmode", "-halt-on-error", "derivation.tex"])
        run = subprocess.run(cmd, cwd=tmp, capture_output=True, text=True, timeout=300)
        pdf = Path(tmp) / "derivation.pdf"
        if run.returncode != 0 or not pdf.exists():
            tail = " / ".join((run.stdout + run.stderr).strip().splitlines()[-3:])
            raise ModelError(f"format: {engine} could not compile the document: {tail}")
        log = Path(tmp) / "derivation.log"
        return pdf.read_bytes(), (log.read_text(errors="replace") if log.exists() else run.stdout)
