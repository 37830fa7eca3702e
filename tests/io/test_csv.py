"""CSV tables in (kinelab.io._csv): the strict reader every CSV file goes through, a measured
curve's (read_curve) and a table of numbers' (read_table, designs and paths)."""
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.io import _csv
from kinelab.io._csv import read_table

ROWS = "".join(f"{k},{k * k}\n" for k in range(20))           # t = k, x = k^2


def curve(tmp_path, text: str | bytes, name: str = "c.csv"):
    path = tmp_path / name
    path.write_bytes(text.encode() if isinstance(text, str) else text)
    return kl.io.read_curve(path)


def refused(tmp_path, text, message, name="c.csv"):
    with pytest.raises(ModelError) as info:
        curve(tmp_path, text, name)
    assert len(info.value.problems) == 1, info.value.problems
    assert str(info.value).startswith((f"{tmp_path / name}: ", f"{name}: ")), str(info.value)
    assert message in str(info.value), str(info.value)
    return str(info.value)


@pytest.mark.parametrize("end", ["\n", "\r\n", "\r"])
def test_any_line_end_gives_the_same_samples(tmp_path, end):
    c = curve(tmp_path, ("# measured\nt [s],x [mm]\n\n" + ROWS).replace("\n", end))
    np.testing.assert_array_equal(c.x, np.arange(20.0))
    np.testing.assert_array_equal(c.y, np.arange(20.0) ** 2)
    assert (c.x_name, c.x_unit, c.y_name, c.y_unit) == ("t", "s", "x", "mm")


def test_mixed_line_ends_and_quoted_fields_are_read(tmp_path):
    text = '"t [s]","x [mm]"\r\n' + ROWS.replace("3,9\n", '"3","9"\r').replace("5,25\n", "5,25\r\n")
    c = curve(tmp_path, text)
    np.testing.assert_array_equal(c.y, np.arange(20.0) ** 2)


def test_blank_and_comment_lines_are_skipped_and_not_counted(tmp_path, monkeypatch):
    monkeypatch.setattr(kl.io._curves, "MAX_SAMPLES", 20)
    text = "t,x\n" + "".join(f"{k},{k}\n,,\n  # note\n \t\n" for k in range(20))
    assert len(curve(tmp_path, text).x) == 20


def test_a_stray_quote_is_refused_not_merged_with_the_next_line(tmp_path):
    """A quote opened in '10,"100' ran to the next line: t = 10, x = 100\\n11,121 (then not
    a number), or with a second quote later, two samples merged into one and one dropped."""
    text = "t,x\n" + ROWS.replace("10,100\n", '10,"100\n').replace("12,144\n", '12,144"\n')
    refused(tmp_path, text, "line 12: a quoted field that does not end on its line (a stray "
                            "quote, or a line break inside quotes)")


def test_a_line_break_inside_a_quoted_header_is_refused(tmp_path):
    refused(tmp_path, '"t\n[s]",x\n' + ROWS, "line 1: a quoted field that does not end on its line")


@pytest.mark.parametrize("text, message", [
    ('t,x\n1,2"3\n', "line 2, column 'x': expected a finite number, got '2\"3' (a stray quote"),
    ('t,"x"y\n', "line 1: a quoted field with more after its closing quote"),
    ('t,x"y\n', "header: column 'x\"y': a stray quote"),
    ('t,"x""y"\n', "header: column 'x\"y': a stray quote"),
])
def test_a_quote_inside_a_field_is_refused(tmp_path, text, message):
    refused(tmp_path, text + ROWS, message)


@pytest.mark.parametrize("name, bad", [("x\x1b[31m", "\\x1b"), ("x\x00", "\\x00"),
                                       ("x\x85", "\\x85"), ("x\u2028", "\\u2028")])
def test_control_characters_in_names_are_refused(tmp_path, name, bad):
    refused(tmp_path, f"t,{name}\n" + ROWS, f"expected printable characters in a column's name "
                                            f"and unit, got '{bad}'")
    with pytest.raises(ModelError, match="expected printable characters"):
        (tmp_path / "d.csv").write_text(f"ground,{name}\n1,2\n")
        read_table(tmp_path / "d.csv")


def test_a_long_name_is_refused(tmp_path):
    """A name labels the table and the figure: 10^5 characters took matplotlib half a minute."""
    assert curve(tmp_path, "t," + "x" * 200 + "\n" + ROWS).y_name == "x" * 200
    refused(tmp_path, "t," + "x" * 100_000 + "\n" + ROWS,
            "expected a name and unit of at most 200 characters, got 100,000; shorten it")


def test_a_name_given_twice_is_refused(tmp_path):
    refused(tmp_path, "t,x,x\n" + ROWS, "header: column 3: the name 'x' is already column 2's")


@pytest.mark.parametrize("cell", ["1_000", "\uff11\uff10", "\u0661\u0660", "1e1_0", "0x10",
                                  "nan", "inf", "-inf", "1e400", "1.2.3", "", "--1", "1e", "١"])
def test_numbers_follow_the_one_rule(tmp_path, cell):
    text = "t,x\n" + ROWS.replace("10,100\n", f"10,{cell}\n")
    refused(tmp_path, text, f"line 12, column 'x': expected a finite number, got "
                            + (f"{kl.errors.describe(cell)}; write it in decimal or scientific "
                               "notation in ASCII digits" if cell else "nothing"))


@pytest.mark.parametrize("cell, value", [(" 1e2 ", 100.0), ("+.5", 0.5), ("5.", 5.0),
                                         ("\t-2E-1", -0.2), ('"7"', 7.0)])
def test_plain_numbers_are_read(tmp_path, cell, value):
    c = curve(tmp_path, "t,x\n" + ROWS.replace("10,100\n", f"10,{cell}\n"))
    assert c.y[10] == value


def test_many_bad_cells_are_said_twenty_at_most(tmp_path):
    text = "t,x\n" + "".join(f"{k},x\n" for k in range(100))
    with pytest.raises(ModelError) as info:
        curve(tmp_path, text)
    assert len(info.value.problems) == 20
    assert info.value.problems[-1] == "and 81 more cells that are not finite numbers"


def test_rows_are_counted_as_parsed(tmp_path, monkeypatch):
    monkeypatch.setattr(_csv, "MAX_ROWS", 5)
    path = tmp_path / "d.csv"
    path.write_bytes(b"a,b\r" + b"1,2\r" * 5)
    assert read_table(path)[1].shape == (5, 2)
    path.write_bytes(b"a,b\r" + b"1,2\r" * 6)
    with pytest.raises(ModelError, match=r"d\.csv: line 7: expected at most 5 rows, got more; cut "
                                         r"the file into pieces$"):
        read_table(path)


def test_a_line_beyond_the_limit_is_refused_before_it_is_split(tmp_path, monkeypatch):
    monkeypatch.setattr(_csv, "MAX_LINE", 100)
    refused(tmp_path, "t,x\n" + ",".join(["1"] * 60) + "\n",
            "line 2: expected at most 100 characters on a line, got more")


def test_a_table_of_numbers(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("\ufeffground, crank\n3,1\n\n2.5,0.5\n")
    names, values = read_table(path)
    assert names == ["ground", "crank"] and values.tolist() == [[3.0, 1.0], [2.5, 0.5]]


@pytest.mark.parametrize("text, message", [
    ("", "expected a header row naming the columns and rows, got an empty file"),
    ("1,2\n3,4\n", "line 1: expected a header row naming the columns"),
    ("a,,b\n1,2,3\n", "line 1, column 2: expected a column's name, got nothing"),
    ("a,b\n1,2,3\n", "line 2: expected 2 cells (one per column of the header), got 3"),
    ("a,b\n1,\n", "line 2, column 'b': expected a finite number, got nothing"),
])
def test_a_table_that_is_not_one(tmp_path, text, message):
    path = tmp_path / "d.csv"
    path.write_text(text)
    with pytest.raises(ModelError, match=re.escape(f"d.csv: {message}")):
        read_table(path)


def test_a_tables_empty_cells_may_stand_for_missing_values(tmp_path):
    path = tmp_path / "d.csv"
    path.write_text("a,b\n1,\n,2\n1,2,,\n")
    values = read_table(path, missing=np.nan)[1]
    assert np.array_equal(values, [[1, np.nan], [np.nan, 2], [1, 2]], equal_nan=True)


def test_text_that_is_not_utf8_is_refused_with_its_line(tmp_path):
    refused(tmp_path, b"t,x\n" + ROWS.encode() + b"20,\xff\n", "line 22: not UTF-8 text")
