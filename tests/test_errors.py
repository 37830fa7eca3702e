"""The wording every message shares: names escaped and cut, lists and problems bounded."""
import pytest

from kinelab.errors import (NAME_SHOWN, NAMES_SHOWN, PROBLEMS_SHOWN, ModelError, check_choice,
                            describe, expected_one_of, quoted, shown, suggest)


@pytest.mark.parametrize("name, text", [
    ("coupler", "'coupler'"),
    ("a\nb", r"'a\nb'"),
    ("tab\there", r"'tab\there'"),
    ("\x1b[31mred", r"'\x1b[31mred'"),
    ("nul\x00", r"'nul\x00'"),
    ("\ud800", r"'\ud800'"),
    ("it's", r"'it\'s'"),
    ("Öse", "'Öse'"),                   # printable letters stay as they are
])
def test_a_name_is_shown_escaped_on_one_line(name, text):
    assert shown(name) == text


def test_a_long_name_is_cut_with_an_ellipsis():
    text = shown("x" * 100_000)
    assert len(text) == NAME_SHOWN and text.endswith("\u2026'")
    assert shown("x" * (NAME_SHOWN - 2)) == "'" + "x" * (NAME_SHOWN - 2) + "'"   # fits: not cut


def test_describe_survives_deep_nesting_and_huge_numbers():
    deep = []
    for _ in range(400):                # deeper than Python's recursion would go in a repr
        deep = [deep]
    assert describe(deep) == "[[[...]]]"
    assert describe(7 * 10 ** 4999) == "a whole number of 5000 digits"
    assert "\n" not in describe(__import__("numpy").zeros((5, 5)))


def test_a_list_of_choices_is_bounded():
    names = [f"p{i}" for i in range(100_000)]
    text = quoted(names)
    assert text.endswith(f"'p{NAMES_SHOWN - 1}' and {100_000 - NAMES_SHOWN:,} more")
    assert quoted([]) == "none"


def test_no_empty_list_of_choices():
    assert expected_one_of("x", []) == "got 'x', but there is nothing to choose from"
    with pytest.raises(ModelError, match=r"^branch: got 'x', but there is nothing to choose from$"):
        check_choice("branch", "x", ())


def test_suggestions_stay_cheap():
    assert suggest("rockr", ["rocker", "crank"]) == " (did you mean 'rocker'?)"
    assert suggest("p1", [f"p{i}" for i in range(100_000)]) == ""   # too many to compare


def test_a_model_error_shows_a_bounded_number_of_problems():
    exc = ModelError([f"points.p{i}: bad" for i in range(1000)], source="big.toml")
    lines = str(exc).splitlines()
    assert len(lines) == PROBLEMS_SHOWN + 1 and len(exc.problems) == 1000
    assert lines[-1] == f"big.toml: and {1000 - PROBLEMS_SHOWN} more problems; fix these first"
