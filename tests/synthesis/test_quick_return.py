"""Linkages for a swing or a stroke and a time ratio: the crank-rocker (best transmission
angle), the offset slider-crank, the slotted levers.  Every design is measured here again
with the engine (kl.kinematics.time_ratio, kl.analyze), and the optima are certified by
dense scans of families written independently (law of cosines, not the construction)."""
import numpy as np
import pytest
from scipy.optimize import fsolve

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.synthesis import (crank_rocker, crank_rockers, imbalance_angle, max_time_ratio,
                               offset_slider_crank, slotted_lever, whitworth)


def measured_swing_and_ratio(model, output="rocker", slide=False):
    """Swing (rad) or stroke (m) and time ratio, by the engine."""
    tr = kl.kinematics.time_ratio(model, output)
    sol = kl.analyze(model, q=tr.dead_centres)
    if slide:
        x = sol.slide(output)
        return abs(x[1] - x[0]), tr.ratio
    th = sol.angle(output)
    return abs(np.angle(np.exp(1j * (th[1] - th[0])))), tr.ratio


def transmission_sweep(model, samples=7201):
    """Smallest folded transmission angle over a dense sweep of the full turn."""
    q = np.linspace(0.0, 2 * np.pi, samples)
    return float(kl.kinematics.transmission_angle(kl.analyze(model, q=q)).min())


# -- crank-rocker ----------------------------------------------------------------------------
CASES = [(np.radians(45), 1.25), (np.radians(30), 1.1), (np.radians(80), 1.5),
         (np.radians(120), 2.0), (np.radians(10), 1.02)]


@pytest.mark.parametrize("psi, Q", CASES)
def test_crank_rocker_swing_and_time_ratio_measured_by_the_engine(psi, Q):
    cr = crank_rocker(2.0, psi, Q)
    swing, ratio = measured_swing_and_ratio(cr.model)
    assert abs(swing - psi) < 1e-9 and abs(ratio - Q) < 1e-9
    assert abs(cr.swing - psi) < 1e-9 and abs(cr.time_ratio - Q) < 1e-9
    assert cr.grashof.kind == "crank-rocker" and cr.ground == 2.0
    assert cr.model.parameters["crank"] == cr.crank and cr.model.parameters["rocker"] == cr.rocker
    # transmission_min is the engine's over the whole turn (a dense sweep can only find more)
    dense = transmission_sweep(cr.model)
    assert 0 < cr.transmission_min <= np.pi / 2
    assert cr.transmission_min <= dense + 1e-12 and dense - cr.transmission_min < 1e-5


def closed_form(a, b, c, d=1.0):
    """Swing, imbalance angle and smallest transmission angle of a crank-rocker, from the
    law of cosines at its two limit positions (B on one side of O2O4 in both)."""
    ext, fold = b + a, b - a
    g_e = np.arccos((c * c + d * d - ext * ext) / (2 * c * d))
    g_f = np.arccos((c * c + d * d - fold * fold) / (2 * c * d))
    b_e = np.arccos((ext * ext + d * d - c * c) / (2 * ext * d))
    b_f = np.arccos((fold * fold + d * d - c * c) / (2 * fold * d))
    mus = [np.arccos(np.clip((b * b + c * c - e * e) / (2 * b * c), -1, 1)) for e in (d - a, d + a)]
    mu = min(min(m, np.pi - m) for m in mus)
    return abs(g_e - g_f), abs(b_f - b_e), mu


@pytest.mark.parametrize("psi, Q", CASES[:3])
def test_best_transmission_angle_certified_by_an_independent_scan(psi, Q):
    """For 200 cranks across the family, solve swing(b, c) = psi and delta(b, c) = delta with
    fsolve from several starts (ground 1): no crank-rocker found beats the optimum, and the
    best of the scan comes close to it."""
    best = crank_rocker(1.0, psi, Q)
    delta = imbalance_angle(Q)
    lo, hi = 0.0, np.sin(psi / 2)              # the family's crank runs below sin(psi/2)
    scan = []
    for a in np.linspace(lo, hi, 202)[1:-1]:
        for b0, c0 in [(1.0, 0.5), (1.0, 1.0), (2.0, 1.0), (0.5, 0.7), (1.5, 1.5), (3.0, 2.0)]:
            def eqs(x):
                with np.errstate(invalid="ignore"):
                    s, dl, _ = closed_form(a, x[0], x[1])
                return [s - psi, dl - delta]
            x, info, ok, _ = fsolve(eqs, [b0, c0], full_output=True)
            if ok != 1 or np.max(np.abs(eqs(x))) > 1e-10 or min(x) <= 0:
                continue
            L = sorted([a, x[0], x[1], 1.0])
            if not (L[0] == a and L[0] + L[3] < L[1] + L[2]):
                continue                       # not a crank-rocker
            fb = kl.mechanisms.fourbar(1.0, a, x[0], x[1])
            swing, ratio = measured_swing_and_ratio(fb) if len(scan) % 50 == 0 else (psi, Q)
            assert abs(swing - psi) < 1e-8 and abs(ratio - Q) < 1e-8   # the scan is right
            scan.append(closed_form(a, x[0], x[1])[2])
    assert len(scan) > 70
    assert max(scan) <= best.transmission_min + 1e-12
    assert best.transmission_min - max(scan) < 2e-3      # cranks 0.5 % of the range apart


@pytest.mark.parametrize("lengths", [(2.5, 1.0, 3.2, 3.0), (3.0, 1.0, 3.0, 2.5),
                                     (4.0, 0.7, 3.5, 2.2)])
def test_a_known_crank_rocker_is_found_again(lengths):
    """Measure a catalogue crank-rocker's swing and time ratio with the engine; the
    synthesis with its crank must give it back among its designs."""
    d, a, b, c = lengths
    swing, ratio = measured_swing_and_ratio(kl.mechanisms.fourbar(d, a, b, c))
    designs = crank_rockers(d, swing, ratio, crank=a)
    got = np.array([[s.coupler, s.rocker] for s in designs])
    assert np.min(np.abs(got - [b, c]).max(axis=1)) < 1e-8
    for s in designs:
        assert abs(s.crank - a) < 1e-12 and abs(s.swing - swing) < 1e-9
        assert abs(s.time_ratio - ratio) < 1e-9
    assert [s.transmission_min for s in designs] == sorted(
        (s.transmission_min for s in designs), reverse=True)
    # crank_rocker with the crank is the best of them
    assert crank_rocker(d, swing, ratio, crank=a).transmission_min == designs[0].transmission_min


def test_pivot_angle_places_the_crank_pivot():
    """The angle at B1 (folded limit position) from B1 -> B2 to B1 -> O2, measured on the
    engine's limit positions."""
    for angle in (100.0, 130.0, -120.0):
        cr = crank_rocker(1.0, 45, 1.25, pivot_angle=angle, degrees=True)
        assert abs(cr.pivot_angle - angle) < 1e-9
        sol = kl.analyze(cr.model, q=np.radians(cr.dead_centres))
        B1, B2 = sol.position("B")
        A1 = sol.position("A")[0]
        assert np.dot(A1, B1 - A1) < 0                      # position 1 is the folded one
        u, v = B2 - B1, -B1                                  # O2 is at the origin
        seen = np.degrees(np.arccos(u @ v / np.linalg.norm(u) / np.linalg.norm(v)))
        assert abs(seen - abs(angle)) < 1e-9
        # positive: O2 on the rocker pivot's side of the chord B1B2
        O4 = np.array([1.0, 0.0])

        def cross(x, y):
            return x[0] * y[1] - x[1] * y[0]
        side = cross(u, v) * cross(u, O4 - B1)
        assert (side > 0) == (angle > 0)
        swing, ratio = measured_swing_and_ratio(cr.model)
        assert abs(np.degrees(swing) - 45) < 1e-9 and abs(ratio - 1.25) < 1e-9


def test_unit_time_ratio():
    cr = crank_rocker(1.0, 40, 1.0, crank=0.2, degrees=True)
    swing, ratio = measured_swing_and_ratio(cr.model)
    assert abs(np.degrees(swing) - 40) < 1e-9 and abs(ratio - 1.0) < 1e-9
    assert np.isnan(cr.pivot_angle)
    with pytest.raises(ModelError, match=r"crank: with time_ratio = 1 the smallest transmission "
                                         r"angle keeps growing as the crank shrinks"):
        crank_rocker(1.0, 40, 1.0, degrees=True)
    with pytest.raises(ModelError, match=r"pivot_angle: with time_ratio = 1"):
        crank_rocker(1.0, 40, 1.0, pivot_angle=100, degrees=True)


def test_largest_time_ratio():
    """Just below (3 pi + swing)/(pi - swing) a crank-rocker exists; at it, none does."""
    top = max_time_ratio(60, degrees=True)
    assert top == pytest.approx(5.0, rel=1e-15)              # (540 + 60) / (180 - 60) deg
    near = crank_rocker(1.0, 60, top * 0.9, degrees=True)
    swing, ratio = measured_swing_and_ratio(near.model)
    assert abs(np.degrees(swing) - 60) < 1e-9 and abs(ratio - top * 0.9) < 1e-9
    assert near.transmission_min < 1.0                  # deg: the family shrinks to a lock
    # nearer still the best design locks (transmission angle ~0.02 deg)
    with pytest.raises(ModelError, match=r"time_ratio: the crank-rocker it gives has a smallest "
                                         r"transmission angle of 0\.0195 deg: it all but locks"):
        crank_rocker(1.0, 60, top * 0.99, degrees=True)
    with pytest.raises(ModelError, match=r"time_ratio: expected the slow stroke's time over the "
                                         r"fast one's, at least 1 and less than 5, got 5\.0; no "
                                         r"crank-rocker with a swing of 60 deg reaches"):
        crank_rocker(1.0, 60, 5.0, degrees=True)


def test_crank_range_is_the_family_range():
    # the family's crank runs from 0 to ground sin(swing/2) (crank pivot at B1)
    hi = np.sin(np.radians(22.5))
    ok = crank_rocker(1.0, 45, 1.25, crank=0.999 * hi, degrees=True)
    assert abs(ok.crank - 0.999 * hi) < 1e-12
    with pytest.raises(ModelError, match=r"crank: expected a crank between 0\.0\d+ m and 0\.38268\d? "
                                         r"m \(both excluded\) for ground 1 m, swing 45 deg and "
                                         r"time ratio 1\.25, got 0\.9 m"):
        crank_rocker(1.0, 45, 1.25, crank=0.9, degrees=True)


@pytest.mark.parametrize("kwargs, message", [
    (dict(swing=0.0), r"swing: expected an angle between 0 and 180 deg \(both excluded\), got 0 deg"),
    (dict(swing=180), r"swing: expected an angle between 0 and 180 deg"),
    (dict(swing=float("nan")), r"swing: expected an angle between 0 and 180 deg .*got nan"),
    (dict(time_ratio=0.8), r"time_ratio: expected the slow stroke's time over the fast one's, "
                           r"at least 1 and less than 4\.33333, got 0\.8$"),
    (dict(time_ratio="2"), r"time_ratio: .* got '2'"),
    (dict(ground=-1.0), r"ground: expected a length from 1e-09 m to 1e\+09 m, got -1 m"),
    (dict(crank=0.1, pivot_angle=100), r"crank, pivot_angle: give at most one free choice"),
    (dict(pivot_angle=10), r"pivot_angle: expected an angle in \(92\.5, 160\) or \(-160, "
                           r"-112\.5\) deg for swing 45 deg and time ratio 1\.25, got 10 deg"),
])
def test_crank_rocker_bad_input(kwargs, message):
    args = dict(ground=1.0, swing=45, time_ratio=1.25, degrees=True)
    args.update(kwargs)
    with pytest.raises(ModelError, match=message):
        crank_rocker(**args)


# -- offset slider-crank -------------------------------------------------------------------
def slider_closed_form(e, r, l):
    """Stroke, imbalance angle, smallest transmission angle of an offset slider-crank."""
    with np.errstate(invalid="ignore"):
        x_e, x_f = np.sqrt((l + r) ** 2 - e * e), np.sqrt((l - r) ** 2 - e * e)
        mu = np.pi / 2 - np.arcsin((e + r) / l)
    return x_e - x_f, np.arctan2(e, x_f) - np.arctan2(e, x_e), mu


@pytest.mark.parametrize("Q", [1.2, 1.4, 2.0])
def test_offset_slider_crank_against_the_engine_and_a_scan(Q):
    sc = offset_slider_crank(0.1, Q)
    stroke, ratio = measured_swing_and_ratio(sc.model, "slide", slide=True)
    assert abs(stroke - 0.1) < 1e-12 and abs(ratio - Q) < 1e-9
    assert abs(sc.stroke - 0.1) < 1e-12 and abs(sc.time_ratio - Q) < 1e-9
    L = sc.lengths
    # the engine's rod angle over a dense turn, against the design's transmission angle
    rod = kl.analyze(sc.model, q=np.linspace(0, 2 * np.pi, 7201)).angle("rod")
    assert abs(sc.transmission_min - (np.pi / 2 - np.abs(rod).max())) < 1e-6
    assert abs(sc.transmission_min - slider_closed_form(L["offset"], L["crank"], L["rod"])[2]) < 1e-10
    # independent family: for each offset solve stroke = 0.1 and delta, keep the best angle
    delta = imbalance_angle(Q)
    scan = []
    for e in np.linspace(0.0, 0.2, 250)[1:]:
        for seed in [(r, l) for r in (0.02, 0.04, 0.06) for l in (0.06, 0.1, 0.2, 0.4)]:
            x, _, ok, _ = fsolve(lambda v: np.subtract(slider_closed_form(e, *v)[:2],
                                                       [0.1, delta]), seed, full_output=True)
            res = np.subtract(slider_closed_form(e, *x)[:2], [0.1, delta])
            if ok == 1 and np.all(np.abs(res) < 1e-12) and 0 < x[0] < x[1] - e:
                scan.append(slider_closed_form(e, *x)[2])
                break
    assert len(scan) > 20
    assert max(scan) <= sc.transmission_min + 1e-12
    assert sc.transmission_min - max(scan) < 1e-3


def test_offset_slider_crank_with_a_rod_and_in_line():
    sc = offset_slider_crank(0.1, 1.4, rod=0.15)
    assert abs(sc.lengths["rod"] - 0.15) < 1e-12
    stroke, ratio = measured_swing_and_ratio(sc.model, "slide", slide=True)
    assert abs(stroke - 0.1) < 1e-12 and abs(ratio - 1.4) < 1e-9
    inline = offset_slider_crank(0.1, 1.0, rod=0.3)
    assert inline.lengths == {"crank": 0.05, "rod": 0.3, "offset": 0.0}
    assert abs(inline.time_ratio - 1.0) < 1e-9 and abs(inline.stroke - 0.1) < 1e-12


@pytest.mark.parametrize("kwargs, message", [
    (dict(time_ratio=3.0), r"time_ratio: expected .* at least 1 and less than 3, got 3\.0; an "
                           r"offset slider-crank's limit-position lines meet at less than 90 deg"),
    (dict(time_ratio=1.0), r"rod: with time_ratio = 1 the slider-crank is in line"),
    (dict(time_ratio=1.4, rod=0.5), r"rod: expected a rod between 0\.05 m and 0\.186603 m \(both "
                                    r"excluded\) for stroke 0\.1 m and time ratio 1\.4, got 0\.5 m"),
    (dict(stroke=0.0), r"stroke: expected a length from 1e-09 m"),
])
def test_offset_slider_crank_bad_input(kwargs, message):
    args = dict(stroke=0.1, time_ratio=1.4)
    args.update(kwargs)
    with pytest.raises(ModelError, match=message):
        offset_slider_crank(**args)


# -- slotted levers ------------------------------------------------------------------------
@pytest.mark.parametrize("Q", [1.5, 2.0, 3.0])
def test_slotted_lever_against_the_engine(Q):
    sl = slotted_lever(Q, 0.4)
    swing, ratio = measured_swing_and_ratio(sl.model, "lever")
    assert abs(ratio - Q) < 1e-9 and abs(sl.time_ratio - Q) < 1e-9
    # the lever swings the imbalance angle: pi (Q - 1)/(Q + 1)
    assert abs(swing - np.pi * (Q - 1) / (Q + 1)) < 1e-9 and abs(sl.swing - swing) < 1e-12


@pytest.mark.parametrize("Q", [1.2, 2.0, 4.0])
def test_whitworth_against_the_engine(Q):
    w = whitworth(Q, 0.05, 0.3, rod=0.4)
    stroke, ratio = measured_swing_and_ratio(w.model, "ram_slide", slide=True)
    assert abs(ratio - Q) < 1e-9 and abs(stroke - 0.3) < 1e-12
    assert w.lengths["crank"] > w.lengths["distance"]


def test_slotted_lever_bad_input():
    with pytest.raises(ModelError, match=r"time_ratio: expected .* more than 1, got 1\.0$"):
        slotted_lever(1.0, 0.4)
    with pytest.raises(ModelError, match=r"rod: expected more than half the stroke \(0\.15 m\)"):
        whitworth(2.0, 0.05, 0.3, rod=0.1)
