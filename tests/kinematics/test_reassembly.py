"""Re-assembly after an edit of a length, a place, an offset or a pivot: at the sketch's
inputs, on the sketch's branch when it exists (else the nearest other, said), every declared
dimension exact; and where no configuration exists at those inputs, a refusal whose gap is
the true one.  Checked against ``reassembly_cases`` (independent geometry), over 10,000
seeded random edits of every catalogue mechanism and example file, from one part in a
million to several times a length (crossing Grashof boundaries on the way)."""
import collections
import math
import re

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import AssemblyError, ModelError
from tests.kinematics.reassembly_cases import ROOT, cases, cross, norm, triangle, unit

EDITS = 10_000
SEED = 20240601
TRIAD_EDITS = 200          # the triad's independent check is a brute-force search: fewer


def random_edits(case, rng, n):
    """n edits of one dimension (four in five) or two, each by a size drawn log-uniformly
    from 1e-6 to 3 (relative to a length, or to the mechanism's size), either way."""
    names = list(case.editable)
    edits = []
    for _ in range(n):
        chosen = rng.choice(len(names), size=1 if rng.random() < 0.8 else 2, replace=False)
        edit = {}
        for i in chosen:
            name = names[i]
            kind = case.editable[name]
            size = 10.0 ** rng.uniform(-6.0, math.log10(3.0))
            sign = rng.choice([-1.0, 1.0])
            v0 = case.dims[name]
            if kind == "length":
                edit[name] = v0 * math.exp(sign * size)
            elif kind == "offset":
                edit[name] = v0 + sign * size * case.size
            else:
                edit[name] = v0 + size * case.size * unit(rng.uniform(-math.pi, math.pi))
        edits.append(edit)
    return edits


def measured(case, m, edit):
    """(problems) of an assembled mechanism: every dimension as declared or as it was, the
    inputs as drawn."""
    out = []
    P = {p.name: np.array(p.xy) for p in m.points}
    dims = case.effective(edit)
    base = case.mechanism
    scale = case.size
    for link in m.links:
        if link.ground or len(link.points) < 2:
            continue
        a, b = link.points[:2]
        L = norm(P[b] - P[a])
        want = dims.get(link.name, norm(case.P0[b] - case.P0[a]))
        if abs(L - want) > 1e-12 * want:
            out.append(f"{link.name}: length {L!r}, expected {want!r}")
        e = (P[b] - P[a]) / L
        e0 = (case.P0[b] - case.P0[a]) / norm(case.P0[b] - case.P0[a])
        for p in link.points[2:]:
            place = np.array([(P[p] - P[a]) @ e, cross(e, P[p] - P[a])])
            key = f"{link.name}.{p}"
            if key in dims:
                want = np.asarray(dims[key])
            elif base.link(link.name).local and p in base.link(link.name).local:
                want = np.array(base.link(link.name).local[p])
            elif base.link(link.name).sides and p in base.link(link.name).sides:
                want = triangle(base.link(link.name).sides[p], L)
            else:                   # as drawn: its place relative to its first two points
                r0 = case.P0[p] - case.P0[a]
                rel = np.array([r0 @ e0, cross(e0, r0)]) / norm(case.P0[b] - case.P0[a])
                want = rel * L
            if np.max(np.abs(place - want)) > 1e-12 * max(L, norm(want)):
                out.append(f"{key}: place {place}, expected {want}")
    for j in m.joints:
        if j.type != "P":
            continue
        o = P[j.origin or m.link(j.links[0]).points[0]]
        u = np.array(j.axis) / norm(np.array(j.axis))
        off = cross(u, P[j.point] - o)
        want = dims.get(j.name, case.dims.get(j.name))
        if want is not None and abs(off - want) > 1e-12 * scale:
            out.append(f"{j.name}: offset {off!r}, expected {want!r}")
    for g in m.ground.points:
        want = dims.get(g, case.P0[g])
        if np.max(np.abs(P[g] - want)) > 1e-15 * scale:
            out.append(f"pivot {g} at {P[g]}, expected {want}")
    q = math.atan2(*(P["A"] - P[case.pivot])[::-1])
    if abs(math.remainder(q - case.q, 2 * math.pi)) > 1e-12:
        out.append(f"the crank turned from {case.q!r} to {q!r}")
    return out


def test_ten_thousand_random_edits_against_independent_geometry():
    rng = np.random.default_rng(SEED)
    all_cases = cases()
    others = [c for c in all_cases if c.name != "triad6"]
    counts = {c.name: (EDITS - TRIAD_EDITS) // len(others) for c in others}
    counts["triad6"] = EDITS - sum(counts.values())
    tally = collections.Counter()
    failures = []
    for case in all_cases:
        edits = random_edits(case, rng, counts[case.name])
        expected = case.expect(case.batch(edits))
        for k, edit in enumerate(edits):
            where = f"{case.name} {edit}"
            gap = float(expected["gap"][k])
            borderline = gap <= 1e-9 * case.size and expected["refused"][k]
            try:
                a = kl.kinematics.reassemble(case.mechanism, **case.kwargs(case, edit))
            except AssemblyError as exc:
                tally["refused"] += 1
                text = str(exc)
                if "\n" in text or not text.startswith("no assembly"):
                    failures.append(f"{where}: unclear refusal {text!r}")
                if not expected["refused"][k]:
                    if not _near_boundary(case, expected, k):
                        failures.append(f"{where}: refused, but it closes: {text}")
                    continue
                if expected["bars"][k] != ("its longest bar is longer" in text):
                    kind = "a loop of bars" if expected["bars"][k] else "a gap at the input"
                    failures.append(f"{where}: expected {kind}: {text}")
                tol = (1e-6 if case.name == "triad6" else 1e-9) * case.size
                if np.isfinite(gap) and abs(exc.gap - gap) > tol:
                    failures.append(f"{where}: gap {exc.gap!r}, expected {gap!r}: {text}")
                continue
            except ModelError as exc:
                if "invalid" in expected and expected["invalid"][k] and "sides" in str(exc):
                    tally["not a link"] += 1       # a triangle of sides that cannot be
                else:
                    failures.append(f"{where}: {type(exc).__name__}: {exc}")
                continue
            tally["assembled"] += 1
            if "invalid" in expected and expected["invalid"][k]:
                failures.append(f"{where}: assembled a triangle of sides that cannot be")
                continue
            if expected["refused"][k] and not borderline:
                failures.append(f"{where}: assembled, expected a refusal by {gap!r}")
                continue
            failures += [f"{where}: {p}" for p in measured(case, a.mechanism, edit)]
            P = {p.name: np.array(p.xy) for p in a.mechanism.points}
            if case.name == "triad6":
                failures += _on_a_root(case, expected, k, P, where)
                continue
            tally["switched"] += bool(a.switched)
            if len(a.switched) != int(expected["switched"][k]) and not _near_boundary(case, expected, k):
                failures.append(f"{where}: switched {a.switched}, expected "
                                f"{'the first dyad' if expected['switched'][k] else 'none'}")
                continue
            for name, xy in expected["points"].items():
                if np.max(np.abs(P[name] - xy[k])) > 1e-9 * case.size:
                    failures.append(f"{where}: {name} at {P[name]}, expected {xy[k]}")
    print(f"\n{sum(tally.values()) - tally['switched']} edits: {dict(tally)}")
    assert not failures, f"{len(failures)} failures, the first:\n" + "\n".join(failures[:15])
    assert tally["refused"] > 500 and tally["assembled"] > 5000 and tally["switched"] > 5


def _near_boundary(case, expected, k):
    """An edit whose gap is within rounding of 0 (either verdict is right)."""
    return float(expected["gap"][k]) <= 1e-9 * case.size


def _on_a_root(case, expected, k, P, where):
    """The triad assembled where the brute-force search finds a root (link3's angle)."""
    roots = expected["roots"][k]
    roots = roots[np.isfinite(roots[:, 0])]
    if not len(roots):
        return [f"{where}: assembled, but the search found no configuration"]
    angles = np.array([math.atan2(*(P["C"] - P["A"])[::-1]), math.atan2(*(P["D"] - P["C"])[::-1])])

    def off(x):
        return np.abs(np.remainder(x - angles + math.pi, 2 * math.pi) - math.pi).max(-1)
    if np.min(off(roots)) > 1e-7:
        return [f"{where}: link3 and the triad at {angles} rad, not at a configuration found: {roots}"]
    followed = expected["continued"][k]
    if np.isfinite(followed).all() and off(followed) > 1e-7:
        return [f"{where}: at {angles} rad, but the sketch's branch continues to {followed}"]
    return []


# -- the cases reported for crank_rocker.toml -------------------------------------------------
CRANK_ROCKER = (ROOT / "examples" / "crank_rocker.toml").read_text()


def crank_rocker_with(link: str, length: float):
    """crank_rocker.toml with one link's length changed (the file's other lines as they are)."""
    text, n = re.subn(rf'(name = "{link}"\npoints = \[[^\]]*\]\nlength = )\d+', rf"\g<1>{length:g}",
                      CRANK_ROCKER)
    assert n == 1
    return text


@pytest.mark.parametrize("link, length", [("crank", 50), ("rocker", 400), ("coupler", 100)])
def test_crank_rocker_edits_that_close_assemble_at_the_drawn_crank_angle(link, length):
    """Each closes at the drawn crank angle (90 deg, A straight up), by the law of cosines:
    B is where the coupler and the rocker meet, left of A -> O4 as drawn."""
    mf = kl.io.ModelFile.from_toml(crank_rocker_with(link, length), source="crank_rocker.toml")
    m = mf.mechanism
    L = {"crank": 0.1, "coupler": 0.3, "rocker": 0.25, link: length / 1000}
    A, O4 = np.array([0.0, L["crank"]]), np.array([0.3, 0.0])
    d = norm(O4 - A)
    assert abs(L["coupler"] - L["rocker"]) < d < L["coupler"] + L["rocker"]   # it closes there
    alpha = math.acos((L["coupler"] ** 2 + d ** 2 - L["rocker"] ** 2) / (2 * L["coupler"] * d))
    e = (O4 - A) / d
    B = A + L["coupler"] * (math.cos(alpha) * e + math.sin(alpha) * np.array([-e[1], e[0]]))
    np.testing.assert_allclose(m.point("A").xy, A, rtol=0, atol=1e-15)
    np.testing.assert_allclose(m.point("B").xy, B, rtol=0, atol=1e-13)
    assert mf.assembly.switched == ()


def test_a_coupler_of_10_mm_cannot_close_at_the_drawn_crank_angle():
    """At 90 deg A = (0, 100) is sqrt(300^2 + 100^2) = 316.228 mm from O4, and a coupler of 10
    and a rocker of 250 reach only 240 to 260 mm: it misses by 56.2278 mm.  The crank reaches
    where 300^2 + 100^2 - 2 300 100 cos q is within [240^2, 260^2]: cos q from 0.54 to
    0.70667, q from 45.04 to 57.32 deg either way; at 90 deg the coupler must be at least
    316.228 - 250 = 66.2278 mm."""
    d = math.hypot(300.0, 100.0)
    lo = math.degrees(math.acos((300 ** 2 + 100 ** 2 - 240 ** 2) / (2 * 300 * 100)))
    hi = math.degrees(math.acos((300 ** 2 + 100 ** 2 - 260 ** 2) / (2 * 300 * 100)))
    with pytest.raises(ModelError) as info:
        kl.io.ModelFile.from_toml(crank_rocker_with("coupler", 10), source="crank_rocker.toml")
    text = str(info.value)
    assert "\n" not in text
    assert text.startswith("crank_rocker.toml: links[2].length: no assembly at 'crank angle' = 90 deg")
    assert f"misses by {d - 260:.6g} mm" in text
    assert f"reaches [{-hi:.6g}, {-lo:.6g}] and [{lo:.6g}, {hi:.6g}] deg" in text
    assert f"make 'coupler' at least {d - 250:.6g} mm" in text
    again = pytest.raises(ModelError, kl.io.ModelFile.from_toml, crank_rocker_with("coupler", 10),
                          source="crank_rocker.toml")
    assert str(again.value) == text                            # the same, every time


def test_a_crank_longer_than_the_other_bars_together_misses_by_the_excess():
    """crank 1000 mm against 300 + 300 + 250 = 850: it misses by 150 mm at any input."""
    with pytest.raises(ModelError, match=r"links\[1\]\.length: no assembly: the loop [-\w]+ cannot "
                                         r"close; it misses by 150 mm: its longest bar is longer "
                                         r"than the others together: crank 1000 mm > "):
        kl.io.ModelFile.from_toml(crank_rocker_with("crank", 1000), source="crank_rocker.toml")


def test_an_edit_refused_by_the_page_names_the_field_and_the_gap():
    from kinelab.web import _api
    model = kl.io.ModelFile.read(ROOT / "examples" / "crank_rocker.toml").to_dict()
    model["links"][2]["length"] = 10.0
    with pytest.raises(ModelError,
                       match=r"^crank_rocker\.toml: links\[2\]\.length: no assembly at 'crank "
                             r"angle' = 90 deg: .* misses by 56\.2278 mm"):
        _api.study({"model": model, "source": "crank_rocker.toml"})
    model["links"][2]["length"] = 100.0
    answer = _api.study({"model": model, "source": "crank_rocker.toml"})
    A, B = (np.array(answer["model"]["points"][p]) for p in "AB")
    assert A.tolist() == [0.0, 100.0] and norm(B - A) == pytest.approx(100.0, rel=1e-13)


# -- the same in other units, and at other scales --------------------------------------------
def test_a_model_in_mm_and_the_same_in_m_assemble_alike_and_say_the_same():
    mm = kl.io.ModelFile.read(ROOT / "examples" / "crank_rocker.toml")
    m_units = kl.io.ModelFile(mechanism=mm.mechanism, units=kl.model.Units("m", "deg"),
                              samples=mm.samples, outputs=mm.outputs).to_dict()
    in_mm = mm.to_dict()
    for length, expect_error in ((100.0, False), (10.0, True), (700.0, True)):
        a, b = dict(in_mm), dict(m_units)
        a["links"] = [dict(x) for x in in_mm["links"]]
        b["links"] = [dict(x) for x in m_units["links"]]
        a["links"][2]["length"] = length
        b["links"][2]["length"] = length / 1000
        got = []
        for data in (a, b):
            try:
                got.append(kl.io.ModelFile.from_dict(data, source="cr.toml"))
            except ModelError as exc:
                got.append(str(exc))
        if not expect_error:
            for p in ("A", "B", "P"):
                assert got[0].mechanism.point(p).xy == pytest.approx(got[1].mechanism.point(p).xy,
                                                                     rel=1e-12, abs=1e-15)
            continue
        same_but_lengths(got[0].replace(" mm", " m"), got[1], 1000.0)


def same_but_lengths(a: str, b: str, factor: float):
    """The same words, and each number the same (an angle, a field's index) or ``factor``
    times the other (a length, to the 6 digits a message shows)."""
    number = re.compile(r"-?\d+\.?\d*(?:e[-+]?\d+)?")
    assert number.sub("#", a) == number.sub("#", b)
    pairs = [(float(x), float(y)) for x, y in zip(number.findall(a), number.findall(b))]
    assert pairs and all(x == y or x == pytest.approx(factor * y, rel=1e-5) for x, y in pairs)
    assert factor == 1.0 or any(x != y for x, y in pairs)


@pytest.mark.parametrize("scale", [1e-4, 1.0, 1e4])
def test_edits_at_any_scale_assemble_alike_and_refuse_alike(scale):
    base = kl.mechanisms.watt6()
    m = kl.model.Mechanism(base.name, tuple(kl.model.Point(p.name, p.x * scale, p.y * scale)
                                            for p in base.points), base.links, base.joints,
                           base.inputs)
    ref = kl.kinematics.reassemble(base, lengths={"link5": 1.4})
    a = kl.kinematics.reassemble(m, lengths={"link5": 1.4 * scale})
    for p in base.point_names:
        np.testing.assert_allclose(np.array(a.mechanism.point(p).xy) / scale,
                                   ref.mechanism.point(p).xy, rtol=0, atol=1e-12)
    assert a.switched == ref.switched
    with pytest.raises(AssemblyError) as big:
        kl.kinematics.reassemble(base, lengths={"link5": 0.2})
    with pytest.raises(AssemblyError) as scaled:
        kl.kinematics.reassemble(m, lengths={"link5": 0.2 * scale})
    assert scaled.value.gap / scale == pytest.approx(big.value.gap, rel=1e-12)
    same_but_lengths(str(scaled.value), str(big.value), scale)


# -- the edit methods --------------------------------------------------------------------------
def test_edits_of_unknown_names_or_values_that_are_not_dimensions_are_refused_all_at_once():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    with pytest.raises(ModelError) as info:
        fb.with_dimensions(lengths={"coupler": -1.0, "nope": 1.0}, offsets={"jA": 0.1},
                           pivots={"A": (0.0, 0.0), "O4": (1.0, "a")}, local={"coupler": {"B": (1, 2)}})
    assert info.value.problems == (
        "lengths.coupler: expected a positive length (m), got -1.0",
        "lengths: expected one of the links 'ground', 'crank', 'coupler', 'rocker', got 'nope'",
        "local.coupler: expected one of the link's points after its first two ('P'), got 'B'",
        "offsets: 'fourbar' has no prismatic joint, got 'jA'",
        "pivots: expected one of the ground's points 'O2', 'O4', got 'A'",
        "pivots.O4: expected (x, y), two finite numbers, got (1.0, 'a')")
    with pytest.raises(ModelError, match="lengths: expected a mapping of link names to lengths"):
        fb.with_lengths([1.0])


def test_with_dimensions_keeps_the_input_and_declares_what_it_changed():
    """The ground's length moves its second pivot along the line from its first; an offset,
    a place and a pivot are declared and exact; the crank keeps its angle throughout."""
    sc = kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5)
    q = math.atan2(*sc.point("A").xy[::-1])
    m = sc.with_dimensions(offsets={"slide": 0.8}, lengths={"rod": 2.5})
    assert m.joint("slide").offset == 0.8 and m.point("B").y == pytest.approx(0.8, abs=1e-15)
    assert math.atan2(*m.point("A").xy[::-1]) == pytest.approx(q, abs=1e-15)
    assert math.dist(m.point("A").xy, m.point("B").xy) == pytest.approx(2.5, rel=1e-14)
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    moved = fb.with_dimensions(lengths={"ground": 3.5}, local={"coupler": {"P": (1.0, 0.5)}})
    assert moved.point("O4").xy == (3.5, 0.0) and moved.link("coupler").local == {"P": (1.0, 0.5)}
    A, B, P = (np.array(moved.point(n).xy) for n in "ABP")
    e = (B - A) / norm(B - A)
    assert (P - A) @ e == pytest.approx(1.0, abs=1e-14) and cross(e, P - A) == pytest.approx(0.5, abs=1e-14)
    assert norm(np.array(moved.point("O4").xy) - B) == pytest.approx(2.5, rel=1e-14)


def test_a_change_of_branch_warns_and_is_said_in_the_result():
    """The Watt six-bar with link5 5.51: at the crank's angle the second dyad closes only with
    the first in its other mode (found here by its own law of cosines)."""
    w = kl.mechanisms.watt6()
    case = next(c for c in cases() if c.name == "watt6")
    expected = case.expect(case.batch([{"link5": 5.51}]))
    assert expected["switched"][0] and not expected["refused"][0]
    with pytest.warns(UserWarning, match=r"another assembly mode of the dyad 'coupler' and 'rocker'"):
        m = w.with_lengths(link5=5.51)
    for name, xy in expected["points"].items():
        np.testing.assert_allclose(m.point(name).xy, xy[0], rtol=0, atol=1e-12)
    a = kl.kinematics.reassemble(w, lengths={"link5": 5.51})
    assert a.switched == ("the dyad 'coupler' and 'rocker' (A-B-O4)",)
