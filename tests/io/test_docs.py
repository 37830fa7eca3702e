"""docs/model-format.md: every complete example loads; every fragment is valid TOML; the
Python example runs."""
import re
import tomllib
from pathlib import Path

import pytest

import kinelab as kl

DOC = Path(__file__).resolve().parents[2] / "docs" / "model-format.md"
TEXT = DOC.read_text()
TOML = re.findall(r"```toml\n(.*?)```", TEXT, re.S)
# the script among the Python blocks (the others are doctests, which pytest runs itself)
PYTHON = [b for b in re.findall(r"```python\n(.*?)```", TEXT, re.S) if not b.startswith(">>>")]


def test_the_doc_has_examples():
    assert len([t for t in TOML if t.startswith("schema")]) >= 2 and len(TOML) >= 7


@pytest.mark.parametrize("text", TOML, ids=lambda t: t.splitlines()[0][:30])
def test_doc_examples_load(text):
    if text.startswith("schema"):
        m = kl.io.from_toml(text)
        assert m.inputs
    else:
        tomllib.loads(text)


def test_doc_python_example_runs(tmp_path, monkeypatch):
    root = DOC.parents[1]
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").symlink_to(root / "examples")
    exec(compile(PYTHON[0], str(DOC), "exec"), {})
    assert kl.load(tmp_path / "fourbar.toml").link_names == ("ground", "crank", "coupler", "rocker")


def test_every_field_is_documented():
    from kinelab.io import _modelfile as f
    for name in f._TOP + f._LINK + f._JOINT + f._INPUT + f._OUTPUTS:
        assert f"`{name}`" in TEXT, name
    for unit in list(f.LENGTH_UNITS) + list(f.ANGLE_UNITS):
        assert f'`"{unit}"`' in TEXT


def test_the_assembly_examples_are_what_the_program_says():
    """The section on lengths and a rough sketch quotes kinelab: its `kinelab check` line for
    crank_rocker.toml, and its refusals of that file with the coupler made 700 mm (a loop of
    bars that cannot close) and 10 mm (one that cannot close at the drawn crank angle)."""
    from click.testing import CliRunner

    from kinelab.cli import main
    from kinelab.errors import ModelError

    section = TEXT.split("## Lengths and a rough sketch")[1].split("\n## ")[0]
    blocks = re.findall(r"```text\n(.*?)\n```", section, re.S)
    assert len(blocks) == 3
    example = DOC.parents[1] / "examples" / "crank_rocker.toml"
    result = CliRunner().invoke(main, ["check", str(example)])
    assert result.exit_code == 0 and blocks[0] in result.stdout.splitlines()
    for block, length in zip(blocks[1:], (700, 10)):
        text, n = re.subn(r'(name = "coupler"\npoints = \[[^\]]*\]\nlength = )\d+', rf"\g<1>{length}",
                          example.read_text())
        assert n == 1
        with pytest.raises(ModelError) as info:
            kl.io.ModelFile.from_toml(text, source="crank_rocker.toml")
        assert str(info.value) == block
