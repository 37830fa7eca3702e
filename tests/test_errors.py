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


def test_errors_that_carry_data_survive_pickling():
    """Dask's workers send errors back pickled: the data and the message must come through."""
    import pickle

    import kinelab as kl
    from kinelab.errors import AssemblyError

    rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    with pytest.raises(kl.kinematics.UnreachableInput) as info:
        kl.analyze(rocker, 2.0)
    for exc in (info.value, ModelError(["a: b", "c: d"], source="m.toml"),
                AssemblyError("open", loop="dyad", gap=0.5, reachable=[(0.0, 1.0)]),
                kl.sweep._family.DesignOffModel("B.x misses by 1 m", "(B.x = 1 m)")):
        back = pickle.loads(pickle.dumps(exc))
        assert type(back) is type(exc) and str(back) == str(exc)
        assert vars(back) == vars(exc)
    assert back.design == "(B.x = 1 m)"
    assert pickle.loads(pickle.dumps(info.value)).q == (2.0,)


def test_an_input_out_of_reach_is_said_in_a_files_units_and_names():
    import kinelab as kl
    from kinelab.model import Units

    rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    with pytest.raises(kl.kinematics.UnreachableInput) as info:
        kl.analyze(rocker, 2.0)
    exc = info.value
    # cos q >= -0.3125 reaches 108.2100...deg; the gap is said in mm, 1000 times the metres
    text = exc.saying(Units("mm", "deg"), ("crank angle",))
    assert text.startswith("dyad 'coupler'-'rocker' (RRR A-B-O4) cannot close at 'crank angle' = "
                           f"{2.0 * 180 / 3.141592653589793:.6g} deg: it misses by "
                           f"{exc.gap * 1000:.6g} mm; 'crank angle' reaches [-108.21, 108.21] deg")
    assert exc.saying() + "; narrow the input range (or pass unreachable='mask')" == str(exc)


def test_an_input_just_past_a_limit_position_does_not_read_as_the_limit():
    import math

    import kinelab as kl
    from kinelab.model import Units

    rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)  # non-Grashof
    limit = math.acos(-0.3125)                 # 108.2099569 deg
    with pytest.raises(kl.kinematics.UnreachableInput) as info:
        kl.analyze(rocker, limit + 1e-8)
    text = info.value.saying(Units("m", "deg"))
    # 6 digits would print both as 108.21; 10 tell them apart (1e-8 rad is 5.7e-7 deg)
    assert "cannot close at q = 108.2099574 deg" in text
    assert "reachable q is [-108.2099569, 108.2099569] deg" in text
