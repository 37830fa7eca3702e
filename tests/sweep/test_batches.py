"""A chunk of designs analysed in one call of the kernel gives what one ``kl.analyze`` of
each design's own mechanism gives: the same assembly and singular flags, angles, K, slides
and positions, for the catalogue's kinds (their sketches made in array operations), model
files whose designs move points (sketches from the columns) and models that tie points
(built one by one)."""
import dataclasses
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import kinelab as kl
from kinelab.solvers import wrap_angle

EXAMPLES = Path(__file__).parents[2] / "examples"
Q = np.linspace(0.0, 2 * np.pi, 37)


def catalogue(kind, rng, n):
    u = lambda lo, hi: rng.uniform(lo, hi, n)          # noqa: E731
    return kl.sweep.family(kind), pd.DataFrame({
        "slider_crank": dict(crank=u(0.5, 1.5), rod=u(0.8, 4), offset=u(-0.5, 0.5)),
        "inverted_slider_crank": dict(ground=u(0.5, 3), crank=u(0.5, 1.5), offset=u(-0.3, 0.3)),
        "slotted_link": dict(crank=u(0.5, 1.5), distance=u(0.2, 3)),
        "whitworth": dict(crank=u(1, 2), distance=u(0.1, 1.2), lever=u(0.5, 2), rod=u(0.2, 4),
                          ram_height=u(-1, 1)),
    }[kind])


def moved(mechanism, rng, n, **roles):
    size = np.ptp([p.xy[:2] for p in mechanism.points], axis=0).max()
    columns = {f"{p.name}.{c}": getattr(p, c) + rng.normal(0.0, 0.01 * size, n)
               for p in mechanism.points for c in "xy"}
    return kl.sweep.family(mechanism, **roles), pd.DataFrame(columns)


CASES = {
    **{kind: (lambda rng, n, kind=kind: catalogue(kind, rng, n))
       for kind in ("slider_crank", "inverted_slider_crank", "slotted_link", "whitworth")},
    "stephenson6.toml": lambda rng, n: moved(kl.load(EXAMPLES / "stephenson6.toml"), rng, n),
    "triad6": lambda rng, n: moved(dataclasses.replace(kl.mechanisms.triad6(), parameters={}),
                                   rng, n),
    # the crank-rocker declares its coupler point's place: built design by design
    "crank_rocker.toml": lambda rng, n: (kl.sweep.family(kl.load(EXAMPLES / "crank_rocker.toml")),
                                         pd.DataFrame({"O4.x": rng.uniform(0.28, 0.32, n)})),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_chunk_in_one_call_is_each_design_alone(name):
    rng = np.random.default_rng(7)
    fam, table = CASES[name](rng, 12)
    problems = [""] * len(table)
    designs = fam.prepare({c: table[c].to_numpy() for c in table}, problems)
    batch = designs.batch(np.broadcast_to(Q, (len(table), len(Q))))
    analysed = 0
    for d, row in enumerate(table.to_dict("records")):
        try:
            mech = fam.build(row)
            kl.kinematics.plan(mech)
        except kl.errors.ModelError as exc:
            assert problems[d] == str(exc).splitlines()[0]
            assert not batch.assembled[d].any()
            continue
        assert problems[d] == ""
        sol = kl.analyze(mech, Q, unreachable="mask", at_singular="flag")
        np.testing.assert_array_equal(batch.assembled[d], sol.assembled, err_msg=f"design {d}")
        np.testing.assert_array_equal(batch.singular[d], sol.singular, err_msg=f"design {d}")
        scale = kl.kinematics.plan(mech).scale
        for link in mech.link_names:
            np.testing.assert_allclose(batch.angle(link)[d], wrap_angle(sol.angle(link)),
                                       atol=1e-9, equal_nan=True, err_msg=link)
            np.testing.assert_allclose(batch.K(link)[d], sol.K(link), rtol=1e-9, atol=1e-9,
                                       equal_nan=True, err_msg=link)
        for p in mech.point_names:
            np.testing.assert_allclose(batch.position(p)[d], sol.position(p),
                                       atol=1e-9 * scale, equal_nan=True, err_msg=p)
        for j in (j for j in mech.joints if j.type == "P"):
            np.testing.assert_allclose(batch.slide(j.name)[d], sol.slide(j.name),
                                       atol=1e-9 * scale, equal_nan=True, err_msg=j.name)
        analysed += sol.assembled.any()
    assert analysed >= 3          # the comparison was not vacuous


def test_designs_a_family_cannot_build_are_their_rows_problem():
    table = pd.DataFrame({"crank": [1.0, -1.0, 1.0, 1.0], "rod": [3.0, 3.0, 0.2, 3.0],
                          "offset": [0.0, 0.0, 2.0, 5.0]})
    df = kl.sweep.run("slider_crank", table, metrics=("assembles",))
    assert df["assembles"].tolist() == [True, False, False, False]
    problems = df.attrs["problems"]
    assert sorted(problems) == [1, 2, 3]
    assert problems[1].startswith("crank: expected a length")     # the table's own check
    for row in (2, 3):                        # the constructor's own words
        message = problems[row]
        with pytest.raises(kl.errors.ModelError) as info:
            kl.mechanisms.slider_crank(**table.iloc[row].to_dict())
        assert message == str(info.value).splitlines()[0]
