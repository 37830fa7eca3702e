"""Comparing the models the web app sends with the files kinelab writes."""
import math


def assert_same_model(a, b) -> None:
    """Two model files equal but for the numbers that a JSON float carries to within one
    unit in the last place (docs/model-format.md: the digits a float prints as)."""
    def same(x, y, where):
        if isinstance(x, float) and isinstance(y, float):
            assert math.isclose(x, y, rel_tol=3e-16, abs_tol=1e-300), (where, x, y)
        elif isinstance(x, dict) and isinstance(y, dict):
            assert x.keys() == y.keys(), where
            for k in x:
                same(x[k], y[k], f"{where}.{k}")
        elif isinstance(x, (list, tuple)) and isinstance(y, (list, tuple)):
            assert len(x) == len(y), where
            for k, (u, v) in enumerate(zip(x, y)):
                same(u, v, f"{where}[{k}]")
        else:
            assert x == y, (where, x, y)
    same(a.to_dict(), b.to_dict(), "model")
