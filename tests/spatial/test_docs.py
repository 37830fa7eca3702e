"""The examples in docs/spatial.md run and print what the page says."""
import doctest
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "spatial.md"


def test_spatial_md_examples():
    result = doctest.testfile(str(DOC), module_relative=False,
                              optionflags=doctest.NORMALIZE_WHITESPACE | doctest.ELLIPSIS)
    assert result.attempted > 30
    assert result.failed == 0, f"{result.failed} example(s) in {DOC.name} failed (see output)"
