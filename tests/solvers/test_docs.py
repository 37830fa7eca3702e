import doctest
from pathlib import Path

DOCS = Path(__file__).resolve().parents[2] / "docs" / "solvers.md"


def test_docs_solvers_examples_run():
    result = doctest.testfile(str(DOCS), module_relative=False, optionflags=(
        doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS))
    assert result.attempted > 10
    assert result.failed == 0
