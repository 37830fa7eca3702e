"""docs/verification.md: its console sample is what the program prints, but for the
disagreements (rounding, whose last digits may differ between machines), which are compared
with their bounds instead; its Python blocks run as doctests (pytest's --doctest-glob)."""
import re
import shlex
from pathlib import Path

from click.testing import CliRunner

from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
TEXT = (ROOT / "docs" / "verification.md").read_text()
NUMBER = r"(?:0|none|\d(?:\.\d)?e[-+]\d+)"
ROW = re.compile(rf"^(\s+\S.*?\s+\d+)\s+({NUMBER})\s+({NUMBER})$")


def masked(text: str) -> list[str]:
    """The lines, with each row's disagreement and the verdict's number left out."""
    out = []
    for line in text.splitlines():
        row = ROW.match(line)
        if row:
            line = f"{row.group(1)}  <largest>  {row.group(3)}"
        out.append(re.sub(rf"largest disagreement {NUMBER}$", "largest disagreement <E>", line))
    return out


def test_the_console_sample_is_the_programs(tmp_path, monkeypatch):
    block = re.search(r"```console\n\$ (.*?)\n(.*?)```", TEXT, re.S)
    command, expected = block.group(1), block.group(2)
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, shlex.split(command)[1:])
    assert result.exit_code == 0, result.output
    assert masked(result.stdout) == masked(expected)
    for line in result.stdout.splitlines():
        row = ROW.match(line)
        if row and row.group(2) != "0":
            assert float(row.group(2)) <= float(row.group(3)), line


def test_the_page_is_linked():
    for page in ("README.md", "docs/command-line.md"):
        assert "verification.md" in (ROOT / page).read_text(), page
