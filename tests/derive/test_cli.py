"""kinelab derive MODEL: writes the document, in the format and language asked for."""
import shutil
from pathlib import Path

from click.testing import CliRunner

from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
SLOTTED = str(ROOT / "examples" / "slotted_link.toml")


def run(*args):
    return CliRunner().invoke(main, ["derive", *args])


def test_markdown_in_portuguese_at_an_input(tmp_path):
    res = run(SLOTTED, "--lang", "pt", "--at", "30", "--out", str(tmp_path))
    assert res.exit_code == 0, res.output
    path = tmp_path / "slotted_link_derivation.md"
    assert res.output == f"wrote {path}\n"
    text = path.read_text()
    assert text.startswith("# `slotted link (Erthal)`: as equações de velocidade e de aceleração")
    assert "## Valores em $q = 0.5235987756$ (30°)" in text


def test_latex_to_a_file_name(tmp_path):
    out = tmp_path / "notes.tex"
    res = run(str(ROOT / "examples" / "fivebar.toml"), "--format", "tex", "--at", "60,-80deg",
              "--out", str(out))
    assert res.exit_code == 0, res.output
    assert out.read_text().startswith("\\documentclass")


def test_pdf_without_a_tex_engine_is_one_line(tmp_path, monkeypatch):
    monkeypatch.setattr(shutil, "which", lambda name: None)
    res = run(SLOTTED, "--format", "pdf", "--out", str(tmp_path))
    assert res.exit_code == 2
    assert res.output.count("\n") == 1 and res.output.startswith(
        "kinelab: error: format: PDF needs a TeX engine")
    assert not list(tmp_path.iterdir())


def test_bad_input_and_bad_model(tmp_path):
    res = run(SLOTTED, "--at", "30,40", "--out", str(tmp_path))
    assert res.exit_code == 2 and "--at: expected 1 value(s)" in res.output
    bad = tmp_path / "bad.toml"
    bad.write_text(Path(SLOTTED).read_text().replace('joint = "jO2"\n', 'joint = "jO2"\n', 1)
                   .replace("[[inputs]]", "[[inputs]]\njoint = \"jO4\"\n[[inputs]]", 1))
    res = run(str(bad), "--out", str(tmp_path))
    assert res.exit_code == 2 and "kinelab: error:" in res.output and "Traceback" not in res.output
