"""Retrieval from an atlas of coupler curves: a curve of the atlas, moved, turned, scaled,
mirrored or backwards, finds its design; refinement reaches the path."""
import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from tests.sweep.atlases import sobol_atlas

COLUMNS = ("ground", "crank", "coupler", "rocker", "coupler_point_along", "coupler_point_perpendicular")


@pytest.fixture(scope="module")
def atlas():
    return sobol_atlas(1024)


def curve_of(row, n=120):
    g, c, b, r, u, v = (float(row[k]) for k in COLUMNS)
    fb = kl.mechanisms.fourbar(g, c, b, r, coupler_point=(u, v))
    return kl.analyze(fb, np.linspace(0, 2 * np.pi, n, endpoint=False)).position("P")


def test_only_designs_whose_crank_turns_fully(atlas):
    kinds = kl.mechanisms.grashof_kinds(*atlas.table[list(COLUMNS[:4])].to_numpy().T)
    assert set(kinds) <= {"crank-rocker", "double-crank", "change-point"}
    assert 0 < len(atlas) < 1024


@pytest.mark.parametrize("mirror, backwards", [(1, False), (-1, False), (1, True), (-1, True)])
def test_a_moved_curve_finds_its_design(atlas, mirror, backwards):
    row = atlas.table.iloc[37]
    P = curve_of(row)
    turn = np.array([[np.cos(2.0), -np.sin(2.0)], [np.sin(2.0), np.cos(2.0)]])
    target = (P @ turn.T) * 0.25 * [1, mirror] + [3.0, -4.0]
    if backwards:
        target = target[::-1]
    near = atlas.nearest(np.roll(target, 31, axis=0), k=4)
    assert near.index[0] == 37 and near["distance"].iloc[0] < 1e-3 < near["distance"].iloc[1]
    placed = atlas.placed(target, k=1)[0]
    Q, _, _, ok = kl.synthesis.coupler_curves(placed[None], np.linspace(0, 2 * np.pi, 1440))
    gap = np.linalg.norm(Q[0][:, None] - target[None], axis=-1).min(axis=0)
    assert ok.all() and gap.max() < 0.01 * 0.25 * np.ptp(P, axis=0).max()


def test_refined_linkage_passes_through_the_path(atlas):
    target = curve_of(atlas.table.iloc[5]) * 2.0 + [1.0, 1.0]
    sols = atlas.refine(target, k=2)
    assert len(sols) >= 1 and sols[0].valid and sols[0].max_error < 1e-6 * np.ptp(target)
    for points in (2, 31):          # path synthesis takes 3 to MAX_PATH_POINTS targets
        with pytest.raises(ModelError, match=rf"^points: expected a whole number from 3 to 30, "
                                             rf"got {points}$"):
            atlas.refine(target, points=points)


def test_atlas_round_trip_and_errors(atlas, tmp_path):
    atlas.to_parquet(tmp_path / "a.parquet")
    back = kl.sweep.Atlas.from_parquet(tmp_path / "a.parquet")
    assert back.harmonics == atlas.harmonics and back.branch == atlas.branch
    assert np.array_equal(back.table.to_numpy(), atlas.table.to_numpy())
    with pytest.raises(ModelError, match=r"path: expected more than 16 finite points"):
        atlas.nearest(np.zeros((5, 2)))
    with pytest.raises(ModelError, match=r"descriptors. needs the family.s coupler point: add the columns"):
        kl.sweep.atlas({"ground": [3.0], "crank": [1.0], "coupler": [3.0], "rocker": [2.5]})


@pytest.fixture(scope="module")
def small_atlas_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("atlas") / "a.parquet"
    sobol_atlas(64).to_parquet(path)
    return path


def _rewritten(source, tmp_path, name, attrs=None, change=None):
    import pandas as pd
    df = pd.read_parquet(source)
    original = dict(df.attrs)
    df = change(df) if change else df
    df.attrs = {**original, **(attrs or {})}
    df.to_parquet(tmp_path / name)
    return tmp_path / name


@pytest.mark.parametrize("name, attrs, change, message", [
    ("branch.parquet", {"branch": "weird"}, None,
     r"branch in its metadata: expected one of 'open', 'crossed', got 'weird'"),
    ("harmonics.parquet", {"harmonics": "abc"}, None,
     r"harmonics in its metadata: expected a whole number from 1 to 1000, got 'abc'"),
    ("column.parquet", None, lambda df: df.drop(columns=["crank"]),
     r"not an atlas of 8 harmonics: no column 'crank'"),
    ("nan.parquet", None, lambda df: df.assign(**{"fd+1": np.nan}),
     r"column 'fd\+1': expected finite numbers, got nan in row 0"),
])
def test_an_atlas_file_is_checked_when_read(small_atlas_file, tmp_path, name, attrs, change, message):
    bad = _rewritten(small_atlas_file, tmp_path, name, attrs, change)
    with pytest.raises(ModelError, match=message + r"; rebuild it with kinelab atlas$"):
        kl.sweep.Atlas.from_parquet(bad)


def test_an_atlas_file_that_is_not_one(small_atlas_file, tmp_path):
    assert len(kl.sweep.Atlas.from_parquet(small_atlas_file)) > 0
    with pytest.raises(ModelError, match=r"missing\.parquet: cannot read an atlas: no such file; check the path$"):
        kl.sweep.Atlas.from_parquet(tmp_path / "missing.parquet")
    with pytest.raises(ModelError, match=r"cannot read an atlas: a directory, not a file"):
        kl.sweep.Atlas.from_parquet(small_atlas_file.parent)
    (tmp_path / "text.parquet").write_text("not parquet")
    with pytest.raises(ModelError, match=r"text\.parquet: cannot read an atlas: not a Parquet file"):
        kl.sweep.Atlas.from_parquet(tmp_path / "text.parquet")
    for path in (None, 5, b"a.parquet"):
        with pytest.raises(ModelError, match=r"^path: expected a file's path"):
            kl.sweep.Atlas.from_parquet(path)


@pytest.mark.parametrize("path", [5, b"x.parquet", ""])
def test_a_study_path_is_checked_before_the_study(path):
    d = {"ground": [3.0], "crank": [1.0], "coupler": [3.0], "rocker": [2.5]}
    with pytest.raises(ModelError, match=r"^path: expected a file's path"):
        kl.sweep.run("fourbar", d, path=path)
    with pytest.raises(ModelError, match=r"^path: expected a file's path"):
        kl.sweep._run.write_parquet(kl.sweep.run("fourbar", d), path)
    with pytest.raises(ModelError, match=r"^df: expected a pandas DataFrame"):
        kl.sweep._run.write_parquet(d, "x.parquet")


# -- refinement is measured against every point of the path given --------------------------
def distances_to_sampled_curve(model, points, samples=2**16):
    """Independently of the code under test: the engine's coupler curve at ``samples`` crank
    angles over a turn (where it closes), as a polyline, and the distance from each point to
    it; with the bound on how far that polyline strays from the curve (the largest distance
    from the engine's point halfway between two samples to their chord)."""
    q = np.linspace(-np.pi, np.pi, samples + 1)
    sol = kl.analyze(model, q=q, unreachable="mask", at_singular="flag")
    mid = kl.analyze(model, q=q[:-1] + np.pi / samples, unreachable="mask", at_singular="flag")
    P, ok = sol.position("P"), sol.assembled
    use = ok[:-1] & ok[1:] & mid.assembled             # chords between samples that close
    a, b, m = P[:-1][use], P[1:][use], mid.position("P")[use]
    e = b - a
    ee = np.sum(e * e, axis=1)

    def to_chords(X):
        t = np.clip(np.sum((X[:, None] - a) * e, axis=-1) / ee, 0.0, 1.0)
        return np.linalg.norm(X[:, None] - a - t[..., None] * e, axis=-1)

    sagitta = float(np.max(np.abs(e[:, 0] * (m - a)[:, 1] - e[:, 1] * (m - a)[:, 0])
                           / np.sqrt(ee)))
    return to_chords(np.asarray(points, float)).min(axis=1), sagitta


def twenty_four_points(atlas, distorted):
    """24 points of an atlas design's coupler curve, 100 wide; ``distorted``: stretched by
    1.4 across and jittered by 3 (standard deviation)."""
    P = curve_of(atlas.table.iloc[5], n=24)
    P = (P - P.mean(axis=0)) / np.ptp(P, axis=0).max() * 100.0
    if distorted:
        P = P * [1.0, 1.4] + np.random.default_rng(3).normal(scale=3.0, size=P.shape)
    return P


@pytest.mark.parametrize("distorted, points", [(False, None), (True, None), (True, 8)])
def test_refine_reports_its_error_against_every_point_given(atlas, distorted, points):
    path = twenty_four_points(atlas, distorted)
    sols = atlas.refine(path, k=3, points=points)
    assert len(sols) >= 1
    best = sols[0]
    assert isinstance(best, kl.sweep.RefinedPath) and best.path.shape == (24, 2)
    # fitted through every point given, unless told to take 8 along the path
    assert best.points.shape == ((24, 2) if points is None else (8, 2))
    expected, sagitta = distances_to_sampled_curve(best.model, path)
    size = np.hypot(*np.ptp(path, axis=0))
    # the polyline of 2^16 samples strays from the curve by at most its largest sagitta
    tolerance = sagitta + 1e-12 * size
    np.testing.assert_allclose(best.path_errors, expected, rtol=0, atol=tolerance)
    assert best.max_error == pytest.approx(expected.max(), abs=tolerance)
    assert best.rms_error == pytest.approx(np.sqrt(np.mean(expected ** 2)), abs=tolerance)
    if not distorted:
        assert best.max_error < 1e-9 * size          # the curve itself: met everywhere
    else:
        assert best.max_error > 0.01 * size          # 24 jittered points: no four-bar meets them
    assert best.valid and best.meets_transmission_limit


def test_refine_leaves_a_closing_repeat_out_of_the_fit(atlas):
    path = twenty_four_points(atlas, False)
    closed = np.vstack([path, path[:1]])              # the first point again, to close it
    best = atlas.refine(closed, k=2)[0]
    assert best.points.shape == (24, 2) and best.path.shape == (25, 2)
    assert best.max_error < 1e-9 * np.ptp(path)
