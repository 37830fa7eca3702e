"""The documents: the notes' order, every symbol defined, both languages from their tables,
the numbers beside the engine's, LaTeX that escapes what it must, and large expressions said
to be large instead of printed."""
import re

import pytest

import kinelab as kl
from kinelab.derive import derive
from kinelab.derive._document import _WIDTH, _width, symbol_latex
from kinelab.derive._words import WORDS
from kinelab.model import Input, Joint, Link, Mechanism, Point
from tests.derive.cases import derivation

ORDER = ("symbols", "position", "velocity", "jacobian", "coefficients", "acceleration", "numbers")


def test_the_two_languages_have_the_same_sentences_and_fields():
    en, pt = WORDS["en"], WORDS["pt"]
    assert set(en) == set(pt)
    for key in en:
        fields = set(re.findall(r"\{([a-z_]+)\}", en[key]))
        assert fields == set(re.findall(r"\{([a-z_]+)\}", pt[key])), key


@pytest.mark.parametrize("lang", ["en", "pt"])
@pytest.mark.parametrize("name", ["slotted_link", "fivebar", "triad6", "whitworth.toml",
                                  "double_parallelogram"])
def test_sections_come_in_the_notes_order(name, lang):
    d = derivation(name)
    words = WORDS[lang]
    text = d.to_markdown(lang=lang)
    heads = [line[3:] for line in text.splitlines() if line.startswith("## ")]
    wanted = [words[k] for k in ORDER[:-1]]
    assert heads[:len(wanted)] == wanted
    assert heads[-1].startswith(words["numbers"].split("{")[0])
    other = WORDS["pt" if lang == "en" else "en"]
    assert other["position"] not in text and other["numbers_intro"][:30] not in text


@pytest.mark.parametrize("name", ["slotted_link", "whitworth", "stephenson6.toml", "slider_driven"])
def test_every_symbol_is_defined_once(name):
    d = derivation(name)
    text = d.to_markdown()
    tables = text.split("## ")[1]               # the Symbols section
    names = symbol_latex(d)
    for s in (*d.q, *d.S, *d.parameters):
        row = f"| ${names[s]}$ |"
        assert tables.count(row) == 1, s
    # and nothing else appears in the equations
    used = set().union(*(e.free_symbols for e in d.Phi)) if d.S else set()
    assert used <= set(d.q) | set(d.S) | set(d.parameters)


def test_the_numbers_are_the_engines():
    d = derivation("fourbar")
    q = 0.7
    text = d.to_markdown(at=q)
    sol = kl.analyze(d.model, q)
    for s in d.S:
        kind, name = d.unknowns[s]
        value = sol.angle(name) if kind == "angle" else sol.slide(name)
        assert f"| {float(value):.10g} |" in text
    for s in d.S:
        kind, name = d.unknowns[s]
        assert f"| {float(sol.K(name)):.10g} |" in text and f"| {float(sol.L(name)):.10g} |" in text
    assert "## Numbers at $q = 0.7$ (40.10704566°)" in text


def test_large_expressions_are_said_to_be_large():
    d = derivation("triad6")
    assert not d.readable["L"]
    text = d.to_markdown()
    assert "With $K$ substituted, $L$ is too large to read here" in text
    assert "$L$ é grande demais para ler aqui" in d.to_markdown(lang="pt")
    # the values it does not print are in the numbers section, beside the engine's
    assert re.search(r"\| \$L_\{\\theta_\{\\text\{link3\}\}\}\$ \| ", text)


def test_latex_is_a_standalone_file_that_escapes_names():
    odd = "crank #1 & 50%_{x}"
    m = Mechanism("odd $name", (Point("O", 0, 0), Point("A", 1, 0), Point("B", 3, 1), Point("C", 3, 0)),
                  (Link("ground", ("O", "C"), ground=True), Link(odd, ("O", "A")),
                   Link("rod", ("A", "B")), Link("rocker", ("C", "B"))),
                  (Joint("jO", "R", ("ground", odd), point="O"),
                   Joint("jA", "R", (odd, "rod"), point="A"),
                   Joint("jB", "R", ("rod", "rocker"), point="B"),
                   Joint("jC", "R", ("ground", "rocker"), point="C")),
                  (Input(joint="jO"),))
    tex = derive(m).to_latex()
    assert tex.startswith("\\documentclass") and tex.rstrip().endswith("\\end{document}")
    assert r"\texttt{crank \#1 \& 50\%\_\{x\}}" in tex and r"\texttt{odd \$name}" in tex
    assert r"\text{crank \#1 \& 50\%\_\{x\}}" in tex          # in the symbols too
    body = re.sub(r"\\[{}$&#%_]", "", tex)
    assert body.count("{") == body.count("}")
    for env in ("align*", "tabular", "itemize", "document"):
        assert tex.count(f"\\begin{{{env}}}") == tex.count(f"\\end{{{env}}}")
    assert "→" not in tex and "°" not in tex          # pdflatex-safe


def test_no_tex_engine_is_a_clear_error(monkeypatch, tmp_path):
    import shutil
    from kinelab.derive._document import write_pdf
    monkeypatch.setattr(shutil, "which", lambda name: None)
    with pytest.raises(kl.errors.ModelError, match=r"PDF needs a TeX engine \(lualatex, xelatex, "
                                                   r"pdflatex, tectonic\), and none is installed"):
        write_pdf("\\documentclass{article}", tmp_path / "x.pdf")
    assert not (tmp_path / "x.pdf").exists()


def test_a_model_without_loops():
    from tests.dynamics.models import pendulum
    d = derive(pendulum())
    assert d.S == () and d.Phi.shape == (0, 1) and d.K.shape == (0, 1)
    text = d.to_markdown()
    assert "The model has no closed loop" in text and "## Dynamics" in text


def test_print_ready_equations_and_words():
    engine = derive(kl.load("examples/engine.toml"))
    for lang in ("en", "pt"):
        text = engine.to_markdown(lang=lang)
        assert "(s)" not in text and "(ões)" not in text        # a count said with its number
        # dots over the letter, not over its subscript
        assert r"\dot{\theta}_{\text{rod}}" in text and r"\dot{\theta_" not in text
        # the input torque broken over lines of about a page's width, inside an alignment
        block = text[text.index(r"\tau_{"):]
        block = block[:block.index("$$")]
        lines = block.splitlines()
        assert len(lines) > 5 and max(_width(line.rstrip("\\ ")) for line in lines) <= _WIDTH
        assert all(line.startswith(r"&\quad ") for line in lines[1:-1])
        assert text.count(r"\left(") == text.count(r"\right)")
    pt = engine.to_markdown(lang="pt")
    assert "na forma das notas" in pt and "de as" not in pt
    assert "uma malha independente" in pt


def test_a_sketch_drawn_at_a_whole_degree_is_shown_there():
    # assembly leaves the Whitworth's crank within rounding of the 0 drawn: 0, not -8e-10
    text = derive(kl.load("examples/whitworth.toml")).to_markdown()
    assert "Numbers at $q = 0$ (0°)" in text
