"""docs/command-line.md: every command and option is documented, and every sample output
is what the program prints today."""
import re
import shlex
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from kinelab.cli import main

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "command-line.md"
TEXT = DOC.read_text()
CONSOLE = re.findall(r"```console\n(.*?)```", TEXT, re.S)


def sections() -> dict[str, str]:
    """The text of each '### `command ...`' section, by command."""
    parts = re.split(r"^### `(\S+)[^`]*`\n", TEXT, flags=re.M)
    return {name: body.split("\n## ")[0] for name, body in zip(parts[1::2], parts[2::2])}


def samples() -> list[tuple[str, str]]:
    """(command line, expected output) of every '$ kinelab ...' in the console blocks."""
    out = []
    for block in CONSOLE:
        for chunk in re.split(r"^\$ ", block, flags=re.M)[1:]:
            command, _, expected = chunk.partition("\n")
            out.append((command, expected))
    return out


def test_every_command_is_in_the_table_and_has_its_options():
    documented = sections()
    for name, command in main.commands.items():
        assert f"\n| `{name} " in TEXT, f"{name} missing from the table"
        assert name in documented, f"no section for {name}"
        for param in command.params:
            if not isinstance(param, click.Option) or param.name == "help":
                continue
            for flag in param.opts + param.secondary_opts:
                assert f"`{flag}" in documented[name] or f"{flag} " in documented[name], \
                    f"{name}: {flag} not documented"


def test_the_doc_has_samples_of_the_main_commands():
    commands = [shlex.split(c)[1] for c, _ in samples()]
    assert {"check", "analyze", "plot", "dynamics"} <= set(commands)
    assert any("--at" in c for c, _ in samples()) and any("--si" in c for c, _ in samples())


@pytest.mark.parametrize("command, expected", samples(), ids=[c for c, _ in samples()])
def test_sample_output_is_the_programs(command, expected, tmp_path, monkeypatch):
    # run where the doc's relative paths (examples/, out/) mean what they say; nothing in
    # these samples varies from run to run, so the comparison is exact
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    args = shlex.split(command)
    assert args[0] == "kinelab"
    result = CliRunner().invoke(main, args[1:])
    assert result.exit_code == 0, result.output
    assert result.stdout == expected
