"""Tables as text, column by column: the very files csv.writer and json.dumps write, row by
row, whatever the values (not finite, the extremes of float64, booleans, whole numbers) and
the names (quotes, %, non-ASCII), in blocks of any size."""
import csv
import io
import json

import numpy as np
import pytest

from kinelab import _tables
from kinelab._tables import csv_blocks, json_blocks
from kinelab.io._results import MAX_TABLE_VALUES, json_ready, table_too_large


def columns(n):
    rng = np.random.default_rng(1)
    return {"a.x[mm]": rng.standard_normal(n) * 1e6,
            "b%s.q[deg]": rng.standard_normal(n),
            'é"name\\': np.where(rng.random(n) < 0.1, np.nan, rng.standard_normal(n) * 1e-7),
            "inf": np.where(rng.random(n) < 0.1, np.inf, -np.inf),
            "singular": rng.random(n) < 0.3,
            "count": rng.integers(-5, 5, n),
            "extremes": np.resize([5e-324, 1.7976931348623157e308, -0.0, 1e16, 1e-5, 0.1], n)}


def by_rows_json(cols) -> str:
    """What kinelab wrote before: one json.dumps of a dictionary per row."""
    names = list(cols)
    data = [np.asarray(cols[k]) for k in names]
    n = len(data[0]) if data else 0
    rows = ["  " + json.dumps({k: json_ready(c[i]) for k, c in zip(names, data)}, allow_nan=False)
            for i in range(n)]
    return "[\n" + "".join(r + (",\n" if i < n - 1 else "\n") for i, r in enumerate(rows)) + "]\n"


def by_rows_csv(cols) -> str:
    names = list(cols)
    data = np.column_stack([np.asarray(cols[k], float) for k in names]) if names else np.zeros((0, 0))
    f = io.StringIO()
    w = csv.writer(f)
    w.writerow(names)
    w.writerows(data.tolist())
    return f.getvalue()


@pytest.mark.parametrize("block", [1, 7, 1 << 20])
@pytest.mark.parametrize("n", [0, 1, 500])
def test_the_text_is_what_csv_and_json_write_row_by_row(monkeypatch, n, block):
    monkeypatch.setattr(_tables, "BLOCK_VALUES", block)
    cols = columns(n)
    assert "".join(json_blocks(cols)) == by_rows_json(cols)
    json.loads("".join(json_blocks(cols)))          # strict JSON
    f = io.StringIO()
    csv.writer(f).writerow(list(cols))
    for text in csv_blocks(np.column_stack([np.asarray(c, float) for c in cols.values()])):
        f.write(text)
    assert f.getvalue() == by_rows_csv(cols)


def test_no_columns():
    assert "".join(json_blocks({})) == by_rows_json({}) == "[\n]\n"


def test_a_table_past_its_bound_says_how_many_rows_fit():
    most = MAX_TABLE_VALUES["csv"]
    assert table_too_large("csv", most // 76, 76) is None
    assert table_too_large("parquet", 10 ** 9, 76) is None
    assert table_too_large("csv", most // 76 + 1, 76) == (
        f"a CSV table of {most // 76 + 1:,} rows x 76 columns is {(most // 76 + 1) * 76:,} values; "
        f"kinelab writes at most {most:,} as CSV (about 30 s): ask for at most {most // 76:,} rows")
