"""Print-ready derivations: every example and catalogue mechanism compiles to a PDF in both
languages with no line past the page's margin; dots over the letter; numbers within rounding
of 0 shown as 0; symbols of the user's choice from the model file and the command line."""
import os
import re
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab.cli import main
from kinelab.derive import derive
from kinelab.derive._document import TEX_ENGINES, compile_latex, tex_engine
from tests.derive.cases import CATALOGUE, EXAMPLES, derivation

ROOT = Path(__file__).resolve().parents[2]
SLOTTED = ROOT / "examples" / "slotted_link.toml"
ERTHAL = {"theta_lever": "A", "s_slot": "B", "L_crank": "R", "x_O2": "C"}
OVERFULL = 1.0          # points a line may run past the margin: TeX's rounding, no more


@pytest.fixture(scope="module")
def engine():
    found = tex_engine()
    if found is None:
        if os.environ.get("CI"):
            pytest.fail(f"no TeX engine ({', '.join(TEX_ENGINES)}): .ci/run installs Debian's "
                        "texlive; the PDF tests must run in CI")
        pytest.skip("no TeX engine found (apt-get install texlive-latex-base "
                    "texlive-latex-recommended texlive-fonts-recommended)")
    return found


def overfull(log: str) -> list[str]:
    """The log's lines past the margin by more than :data:`OVERFULL` points."""
    return [m.group(0) for m in re.finditer(r"Overfull \\hbox \(([0-9.]+)pt too wide\)[^\n]*", log)
            if float(m.group(1)) > OVERFULL]


@pytest.mark.parametrize("name", list(CATALOGUE) + EXAMPLES)
def test_every_document_compiles_inside_the_page(name, engine):
    d = derivation(name)
    texts = [d.to_latex(lang=lang) for lang in ("en", "pt")]
    with ThreadPoolExecutor(2) as pool:             # the engine once per document, two at once
        results = list(pool.map(lambda tex: compile_latex(tex, engine), texts))
    for lang, (pdf, log) in zip(("en", "pt"), results):
        assert pdf.startswith(b"%PDF"), lang
        assert overfull(log) == [], (lang, overfull(log))


def test_the_engine_pdf_from_the_command_line(engine, tmp_path):
    # the engine's input torque, a sum some five metres long on one line, is set over lines
    for lang in ("en", "pt"):
        res = CliRunner().invoke(main, ["derive", str(ROOT / "examples" / "engine.toml"),
                                        "--format", "pdf", "--lang", lang, "--out",
                                        str(tmp_path / f"engine_{lang}.pdf")])
        assert res.exit_code == 0, res.output
        assert (tmp_path / f"engine_{lang}.pdf").read_bytes().startswith(b"%PDF")
    tex = derivation("engine.toml").to_latex()
    torque = tex[tex.index(r"\tau_{"):]
    torque = torque[:torque.index(r"\end{align*}")].splitlines()
    assert len(torque) > 5 and all(line.startswith(r"&\quad ") for line in torque[1:])
    _, log = compile_latex(tex, engine)
    assert overfull(log) == []


def test_dots_over_the_letter_in_both_orders():
    text = derivation("engine.toml").to_latex()
    assert r"\dot{\theta}_{\text{rod}}" in text and r"\ddot{\theta}_{\text{rod}}" in text
    assert r"\dot{s}_{\text{slide}}" in text
    assert not re.search(r"\\d?dot\{[^{}]*_", text)          # never a subscript under the dot


def test_numbers_within_rounding_of_zero_are_zero():
    # at q = 90 degrees cos q is 6e-17 in floating point: J and Q show 0
    text = derivation("engine.toml").to_markdown()
    numbers = text[text.index("## Numbers at $q = 1.570796327$ (90°)"):]
    matrices = numbers[numbers.index("J = "):numbers.index("$$", numbers.index("J = "))]
    assert not re.search(r"\de-\d", matrices) and "0.1729161647 & 0" in matrices
    assert "Valores em $q = 0$ (0°)" in derive(kl.load(ROOT / "examples" / "whitworth.toml"),
                                               "pt").to_markdown()


def test_a_wide_matrix_is_given_by_its_entries():
    text = derivation("engine.toml").to_markdown()
    assert "D_{14} &= - L_{\\text{crank}} \\sin {q}" in text
    assert "The entries not written are 0." in text
    assert "As entradas não escritas são nulas." in derivation("engine.toml").to_markdown(lang="pt")


def with_notation(tmp_path, table: dict) -> Path:
    path = tmp_path / "slotted_link.toml"
    path.write_text(SLOTTED.read_text() + "\n[notation]\n"
                    + "".join(f'{k} = "{v}"\n' for k, v in table.items()))
    return path


def test_the_model_files_notation_table(tmp_path):
    path = with_notation(tmp_path, ERTHAL)
    mf = kl.io.ModelFile.read(path)
    assert mf.mechanism.parameters["notation"] == ERTHAL
    assert "[notation]" in mf.to_toml() and kl.io.from_toml(mf.to_toml()) == mf.mechanism
    d = derive(mf.mechanism)
    assert str(d.Phi.T) == "Matrix([[B*cos(A) - C - R*cos(q), B*sin(A) - R*sin(q)]])"
    assert str(d.det_J) == "-B"
    # the same numbers as with the model's own names
    own = derive(mf.mechanism, notation="names")
    assert [str(s) for s in own.S] == ["theta_lever", "s_slot"]
    assert own.evaluate(0.5).K.tolist() == d.evaluate(0.5).K.tolist()
    with pytest.raises(kl.errors.ModelError, match=r"notation.s_slot: expected a non-empty name"):
        kl.io.ModelFile.read(with_notation(tmp_path, {"s_slot": " "}))


def test_the_notation_option(tmp_path):
    def run(*args):
        return CliRunner().invoke(main, ["derive", *args, "--out", str(tmp_path)])
    res = run(str(SLOTTED), "--notation", ",".join(f"{k}={v}" for k, v in ERTHAL.items()))
    assert res.exit_code == 0, res.output
    text = (tmp_path / "slotted_link_derivation.md").read_text()
    assert r"& B \cos {A} - C - R \cos {q} = 0 && (1)" in text
    # the file's table, then set aside with --notation names
    path = with_notation(tmp_path, ERTHAL)
    assert run(str(path)).exit_code == 0
    assert r"B \cos {A}" in (tmp_path / "slotted_link_derivation.md").read_text()
    assert run(str(path), "--notation", "names").exit_code == 0
    assert r"\theta_{\text{lever}}" in (tmp_path / "slotted_link_derivation.md").read_text()
    # the catalogue's letters, as its constructors give them, unless names are asked for
    letters = derive(kl.mechanisms.slotted_link(crank=1.0, distance=2.0), notation="names")
    assert [str(s) for s in letters.S] == ["theta_lever", "s_slot"]
    res = run(str(SLOTTED), "--notation", "theta_levr=A")
    assert res.exit_code == 2 and res.output.count("\n") == 1
    assert "notation: theta_levr: not a symbol of the equations" in res.output
    assert "its symbols are L_crank, q, s_slot, theta_lever, x_O2" in res.output
    res = run(str(SLOTTED), "--notation", "A")
    assert res.exit_code == 2 and "expected notes, names or NAME=SYMBOL" in res.output


def test_an_engine_that_cannot_run_gives_way_to_the_next(tmp_path, monkeypatch):
    import shutil
    from kinelab.derive._document import write_pdf
    if not shutil.which("pdflatex"):
        if os.environ.get("CI"):
            pytest.fail("no pdflatex: .ci/run installs Debian's texlive-latex-base")
        pytest.skip("needs pdflatex")
    # lualatex on the PATH without its packages (texlive-luatex) fails: pdflatex compiles
    broken = tmp_path / "bin"
    broken.mkdir()
    (broken / "lualatex").write_text("#!/bin/sh\necho 'luaotfload.sty not found'\nexit 1\n")
    (broken / "lualatex").chmod(0o755)
    monkeypatch.setenv("PATH", f"{broken}{os.pathsep}{os.environ['PATH']}")
    out = write_pdf(derivation("slotted_link").to_latex(), tmp_path / "slotted.pdf")
    assert out.read_bytes().startswith(b"%PDF")
    # a document no engine compiles: the first engine's error
    with pytest.raises(kl.errors.ModelError, match=r"lualatex could not compile the document: "
                                                   r"luaotfload.sty not found"):
        write_pdf("\\documentclass{article}\\begin{document}\\undefined\\end{document}",
                  tmp_path / "bad.pdf")
    assert not (tmp_path / "bad.pdf").exists()


@pytest.mark.parametrize("name", ["engine.toml", "triad6"])
def test_the_markdown_compiles_with_pandoc(name, engine, tmp_path):
    import shutil
    import subprocess
    if not shutil.which("pandoc"):
        pytest.skip("pandoc is not installed")
    for lang in ("en", "pt"):
        md = tmp_path / f"{lang}.md"
        md.write_text(derivation(name).to_markdown(lang=lang), encoding="utf-8")
        run = subprocess.run(["pandoc", md.name, "-o", f"{lang}.pdf", f"--pdf-engine={engine}",
                              "-V", "geometry:margin=2cm"], cwd=tmp_path, capture_output=True,
                             text=True, timeout=300)
        assert run.returncode == 0, run.stderr[-2000:]
