"""User-facing text names the lecture notes by title and author, never by their file number
("seed 000", "notes 003"): the docstrings, messages and help of the package, the docs, the
README and the example models."""
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BY_NUMBER = re.compile(r"\b(?:seeds?|notes)[ ]+00", re.I)


def user_facing_files():
    for folder in ("kinelab", "docs", "examples"):
        for path in sorted((ROOT / folder).rglob("*")):
            if path.is_file() and "__pycache__" not in path.parts and path.suffix in (
                    ".py", ".md", ".toml", ".json", ".txt", ".html", ".js", ".css"):
                yield path
    yield ROOT / "README.md"


def test_the_notes_are_cited_by_title_and_author():
    files = list(user_facing_files())
    assert ROOT / "kinelab" / "mechanisms" / "_catalogue.py" in files and len(files) > 50
    found = [f"{path.relative_to(ROOT)}:{n}: {line.strip()}"
             for path in files
             for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
             if BY_NUMBER.search(line)]
    assert not found, "cite the notes by title and author:\n" + "\n".join(found)


def test_the_pattern_catches_numbered_citations():
    for text in ("(seed 000)", "Seed 003 §5", "notes 003, Ex. 4.2", "Notes 003 eq. 76", "seeds 000-003"):
        assert BY_NUMBER.search(text), text
    for text in ("*Mecanismos*, §4.5, Ex. 4.2", "test_notes_003_planar.py", "seed=0", "run 1 (seed 0)"):
        assert not BY_NUMBER.search(text), text
