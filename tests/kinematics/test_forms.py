"""One answer whichever form of the kernel runs: the compiled kernel and its numpy form
give the same statuses at every sample (assembled, singular), the same refusals word for
word, and the same numbers to rounding, on every catalogue mechanism and example file, over
two turns of the input (through limit positions, unreachable stretches and change points),
by both methods.

Each analysis runs twice in this process, once in each mode of ``kinelab._compiled``
("compiled" loads the kernel from its cache, or compiles it here): nothing depends on how
far the compiling helper has come.
"""
import contextlib
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab import _compiled
from kinelab.errors import KinelabError
from tests.kinematics.test_engine import CATALOGUE, _hydraulic_boom

EXAMPLES = sorted(Path(__file__).parents[2].joinpath("examples").glob("*.toml"))
MODELS = {**{f"catalogue:{k}": make for k, make in CATALOGUE.items()},
          "hydraulic_boom": _hydraulic_boom,
          "triad6": kl.mechanisms.triad6,
          **{f"example:{p.stem}": (lambda p=p: kl.load(p)) for p in EXAMPLES}}
# the (1, 1, 2, 2) kite, a change point every turn: the status at it decided by rounding in
# each form alike
MODELS["kite"] = lambda: kl.mechanisms.fourbar(1.0, 1.0, 2.0, 2.0)
# a triple rocker: limit positions and unreachable stretches every turn
MODELS["triple_rocker"] = lambda: kl.mechanisms.fourbar(3.0, 2.0, 2.0, 2.5, coupler_point=(1.0, 0.5))


@contextlib.contextmanager
def form(mode):
    before = _compiled.mode()
    _compiled.set_mode(mode)
    try:
        yield
    finally:
        _compiled.set_mode(before)


def both(f):
    """f() in each form: its result, or its error's type and message."""
    out = []
    for mode in ("numpy", "compiled"):
        with form(mode):
            try:
                out.append(f())
            except KinelabError as exc:
                out.append((type(exc).__name__, str(exc)))
    return out


def inputs(m):
    """Two turns of each revolute input about the sketch (a slide input: a size of the
    mechanism either way), (N,) or (N, M)."""
    p = kl.kinematics.plan(m)
    reach = np.array([2 * np.pi if m.joint(i.joint).type == "R" else 0.5 * p.scale
                      for i in m.inputs])
    q = p.q_sketch + np.linspace(-1.0, 1.0, 241)[:, None] * reach
    return q[:, 0] if len(m.inputs) == 1 else q


def refusal(**options):
    """What analyze says of the samples, given refusal policies: None, or its refusal."""
    def run(m, q, method):
        kl.analyze(m, q, qd=1.0, method=method, **options)
    return run


@pytest.mark.parametrize("name", sorted(MODELS))
@pytest.mark.parametrize("method", ["auto", "newton"])
def test_both_forms_give_the_same_statuses_messages_and_numbers(name, method):
    m = MODELS[name]()
    q = inputs(m)
    a, b = both(lambda: kl.analyze(m, q, qd=1.0, qdd=0.5, method=method, unreachable="mask",
                                   at_singular="flag"))
    assert type(a) is type(b)
    if isinstance(a, tuple):            # refused alike, word for word
        assert a == b
        return
    np.testing.assert_array_equal(a.assembled, b.assembled)
    np.testing.assert_array_equal(a.singular, b.singular)
    scale = kl.kinematics.plan(m).scale
    for p in m.point_names:
        for what in ("position", "velocity", "acceleration"):
            x, y = getattr(a, what)(p), getattr(b, what)(p)
            np.testing.assert_array_equal(np.isnan(x), np.isnan(y), err_msg=f"{p} {what}")
            np.testing.assert_allclose(x, y, rtol=1e-7, atol=1e-7 * scale, equal_nan=True,
                                       err_msg=f"{p} {what}")
    # the refusals of a sample that does not assemble or is singular, word for word
    for policy in ({"unreachable": "raise"}, {"at_singular": "raise", "unreachable": "mask"}):
        x, y = both(lambda: refusal(**policy)(m, q, method))
        assert x == y, policy


@pytest.mark.parametrize("link, length", [("crank", 900), ("rocker", 40), ("coupler", 10),
                                          ("crank", 50), ("rocker", 400)])
def test_a_model_edited_is_assembled_or_refused_alike(tmp_path, link, length):
    # the crank-rocker with one length changed: some close (at the sketch's input or
    # elsewhere), some cannot, by a gap that both forms say alike
    text = (Path(__file__).parents[2] / "examples" / "crank_rocker.toml").read_text()
    block = f'name = "{link}"\n'
    head, tail = text.split(block)
    old = tail.split("length = ", 1)[1].split()[0]
    path = tmp_path / "edited.toml"
    path.write_text(head + block + tail.replace(f"length = {old}", f"length = {length}", 1))

    def load():
        m = kl.load(path)
        return [tuple(p.xy) for p in m.points]
    x, y = both(load)
    if isinstance(x, tuple):
        assert x == y
    else:
        np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-9)
    fb = kl.load(Path(__file__).parents[2] / "examples" / "crank_rocker.toml")

    def edit():
        return [tuple(p.xy) for p in fb.with_lengths({link: length / 1000.0}).points]
    x, y = both(edit)
    if isinstance(x, tuple):
        assert x == y
    else:
        np.testing.assert_allclose(x, y, rtol=1e-9, atol=1e-9)
