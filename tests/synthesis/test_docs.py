import doctest
from pathlib import Path

DOCS = Path(__file__).resolve().parents[2] / "docs" / "synthesis.md"


def test_docs_synthesis_examples_run():
    result = doctest.testfile(str(DOCS), module_relative=False, optionflags=(
        doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS))
    assert result.attempted > 20
    assert result.failed == 0
