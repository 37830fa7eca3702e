"""The certificate of a kinematic analysis: it passes on every example model and catalogue
mechanism, it fails (naming the quantity and the route) when a number is wrong, it is the
same in mm as in m, and its samples follow the stated rule."""
import dataclasses
import re
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.io import ModelFile
from kinelab.verify import NEAR_SAMPLES, checked_samples
from tests.derive.cases import CATALOGUE

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted(p.name for p in (ROOT / "examples").glob("*.toml"))


def example_sweep(name: str, samples: int = 121) -> kl.KinematicSolution:
    mf = ModelFile.read(ROOT / "examples" / name)
    q, qd, qdd = mf.sample_inputs(samples)
    return kl.analyze(mf.mechanism, q, qd, qdd, at_singular="flag", verify=True)


def catalogue_sweep(name: str, samples: int = 121) -> kl.KinematicSolution:
    m = CATALOGUE[name]()
    if len(m.inputs) == 1:
        lo, hi = kl.kinematics.reachable_ranges(m)[0]
        q = np.linspace(lo, hi, samples)
        return kl.analyze(m, q, 3.0, 2.0, at_singular="flag", verify=True)
    q0 = kl.kinematics.plan(m).q_sketch
    t = np.linspace(0, 2 * np.pi, samples)
    q = q0 + 0.2 * np.column_stack([np.sin(t), np.cos(t)])
    return kl.analyze(m, q, np.array([1.0, -2.0]), 0.5, verify=True)


@pytest.mark.parametrize("name", EXAMPLES)
def test_every_example_is_verified(name):
    cert = example_sweep(name).certificate
    assert cert.passed, str(cert)
    # every kinematic quantity is there, each computed by at least two routes besides the
    # reported one (the closed form or the Newton engine)
    assert {"angle", "position", "K", "L", "velocity", "acceleration"} <= set(cert)
    # gear and cam joints are in neither the Newton engine nor the derivation: loop closure and
    # finite differences are their second routes, and the certificate says so
    text = (ROOT / "examples" / name).read_text()
    geared = 'type = "G"' in text or 'type = "C"' in text
    for name_, (routes, largest) in cert.items():
        assert len(routes) >= (2 if geared else 3), (name_, routes)
        assert 0.0 <= largest <= 1e-6
    assert "finite differences" in cert["K"][0]
    if geared:
        joints = "cam joints" if 'type = "C"' in text else "gear joints"
        assert any(joints in note for note in cert.notes)
    else:
        assert "symbolic derivation" in cert["L"][0]


@pytest.mark.parametrize("name", sorted(CATALOGUE))
def test_every_catalogue_mechanism_is_verified(name):
    cert = catalogue_sweep(name).certificate
    assert cert.passed, str(cert)
    assert cert.verdict().startswith(f"verified: {len(cert)} quantities, largest disagreement ")


def test_the_mapping_contract():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    sol = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, 37), qd=10.0, verify=True)
    routes, largest = sol.certificate["K"]
    assert routes == ("closed form", "Newton engine", "symbolic derivation", "finite differences")
    assert isinstance(largest, float) and largest < 1e-8
    assert dict(sol.certificate)["position"][0][:2] == ("closed form", "loop closure")
    # the plain call is the kinematics' own, with no certificate
    assert kl.analyze(fb, q=0.5).certificate is None
    assert kl.kinematics.analyze(fb, q=0.5).certificate is None


def corrupted(sol, item: str, column: int, by: float):
    """``sol`` with one stored column of one item changed at one sample."""
    jets = sol.stored_jets.copy()
    slot = int(sol.plan.item_slot[item])
    jets[len(jets) // 3, slot, column] += by
    return dataclasses.replace(sol, stored_jets=jets, certificate=None)


def test_a_wrong_K_fails_and_is_named():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    sol = kl.analyze(fb, q=np.linspace(0.1, 6.0, 60), qd=2.0)
    bad = corrupted(sol, sol.plan.link_item["rocker"], 1, 1e-6)        # K of the rocker
    cert = kl.verify.certify(bad)
    assert not cert.passed
    verdict = cert.verdict()
    assert verdict.startswith("NOT verified: K by Newton engine (")
    # every independent route sees it; the positions are untouched
    assert {c.route for c in cert.quantity("K").failures} == {
        "Newton engine", "symbolic derivation", "finite differences"}
    assert cert.quantity("position").passed and cert.quantity("angle").passed
    assert re.search(r"K by finite differences \(\S+ > bound \S+\)", verdict)


def test_a_point_off_its_link_fails_loop_closure():
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.2)
    sol = kl.analyze(sc, q=np.linspace(0.0, 6.0, 50), qd=1.0)
    bad = corrupted(sol, sol.plan.point_item["B"], 0, 1e-7 * sol.plan.scale)
    cert = kl.verify.certify(bad)
    closure = [c for c in cert.quantity("position").comparisons if c.route == "loop closure"][0]
    assert not closure.passed and closure.disagreement == pytest.approx(1e-7, rel=1e-3)


def test_a_wrong_route_fails(monkeypatch):
    """A route that is wrong makes the certificate fail: the check can fail."""
    from kinelab.verify import _symbolic
    real = _symbolic.SymbolicRoute.evaluate

    def off(self, q, S):
        out = real(self, q, S)
        out["L"] = out["L"] * (1 + 1e-6)
        return out
    monkeypatch.setattr(_symbolic.SymbolicRoute, "evaluate", off)
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    cert = kl.analyze(fb, q=np.linspace(0.1, 6.0, 40), qd=2.0, verify=True).certificate
    assert [(q.name, c.route) for q in cert.quantities for c in q.failures] == [
        ("L", "symbolic derivation"), ("acceleration", "symbolic derivation")]


def test_the_same_in_millimetres():
    """Disagreements are relative to the mechanism's size and 1 rad: the same model in mm
    and in m gives the same certificate, to rounding."""
    m = kl.load(ROOT / "examples" / "crank_rocker.toml")           # SI
    mm = kl.mechanisms.fourbar(ground=300.0, crank=100.0, coupler=300.0, rocker=250.0,
                               coupler_point=(150.0, 100.0))
    si = kl.mechanisms.fourbar(ground=0.3, crank=0.1, coupler=0.3, rocker=0.25,
                               coupler_point=(0.15, 0.1))
    q = np.linspace(0.0, 2 * np.pi, 91)
    a = kl.analyze(si, q, 10.0, verify=True).certificate
    b = kl.analyze(mm, q, 10.0, verify=True).certificate
    assert list(a) == list(b) and a.passed and b.passed
    for name in a:
        assert a[name][0] == b[name][0]
        for x, y in zip(a.quantity(name).comparisons, b.quantity(name).comparisons):
            assert x.bound == y.bound and x.samples == y.samples
            # both at rounding level; neither grows by the factor 1000 of the unit
            assert max(x.disagreement, y.disagreement) <= 100 * max(
                min(x.disagreement, y.disagreement), 1e-12)
    assert m.name == "crank-rocker"


def test_singular_samples_are_left_out_and_said():
    rocker = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    lo, hi = kl.kinematics.reachable_ranges(rocker)[0]
    sol = kl.analyze(rocker, np.linspace(lo, hi, 181), 2.0, at_singular="flag", verify=True)
    assert sol.singular[[0, -1]].all()            # both limit positions are in the sweep
    cert = sol.certificate
    assert cert.passed, str(cert)
    assert any("2 sample(s) flagged singular" in n for n in cert.notes)
    # the bounds near a limit position are wider (conditioning), and say why
    fd = [c for c in cert.quantity("L").comparisons if c.route == "finite differences"][0]
    assert fd.samples == 179 and "Richardson" in fd.reason


def test_change_points_switched_are_checked_without_the_newton_engine():
    par = kl.mechanisms.fourbar(ground=100, crank=60, coupler=100, rocker=60)
    q = np.radians(np.arange(-90, 450, 2.0))
    sol = kl.analyze(par, q, 1.0, at_singular="flag", at_change_point="switch", verify=True)
    cert = sol.certificate
    assert cert.passed, str(cert)
    assert "Newton engine" not in cert["K"][0]
    assert any("switched there" in n for n in cert.notes)


def test_the_samples_checked_follow_the_rule():
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    lo, hi = kl.kinematics.reachable_ranges(fb)[0]
    sol = kl.analyze(fb, np.linspace(lo, hi, 200_001), at_singular="flag")
    idx = checked_samples(sol)
    assert np.array_equal(idx, checked_samples(sol))                  # deterministic
    assert np.all(np.diff(idx) > 0)                                    # in the sweep's order
    near = np.flatnonzero(sol.assembled & (sol.singularity < kl.verify.NEAR_SINGULAR))
    spread = np.linspace(0, 200_000, 200_001 // kl.verify.STRIDE).round().astype(int)
    assert set(spread) <= set(idx) | {0, 200_000}                      # the ends are singular
    assert len(set(near) & set(idx)) == min(len(near), NEAR_SAMPLES)
    # every sample of a small sweep, assembled ones only
    small = kl.analyze(fb, np.linspace(lo - 0.1, hi, 1000), unreachable="mask", at_singular="flag")
    assert np.array_equal(checked_samples(small), np.flatnonzero(small.assembled))


def test_verify_must_be_a_flag():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    with pytest.raises(kl.errors.ModelError, match="verify: expected True or False, got 'yes'"):
        kl.analyze(fb, 0.5, verify="yes")
    with pytest.raises(kl.errors.ModelError, match="expected a result to certify"):
        kl.verify.certify(fb)


@pytest.mark.parametrize("limit, why", [
    ("MAX_UNKNOWNS", "2 unknown coordinates; the derivation is written for at most 1"),
    ("MAX_SECOND_DERIVATIVES", "second derivatives to take in symbols (at most 10")])
def test_the_symbolic_route_is_skipped_when_too_large_and_says_why(monkeypatch, limit, why):
    import kinelab.derive
    from kinelab.verify import _symbolic
    monkeypatch.setattr(kinelab.derive if limit == "MAX_UNKNOWNS" else _symbolic, limit,
                        1 if limit == "MAX_UNKNOWNS" else 10)
    sc = kl.mechanisms.slider_crank(crank=1.0, rod=3.0)        # a new plan: nothing cached
    cert = kl.analyze(sc, q=np.linspace(0.0, 6.0, 30), qd=1.0, verify=True).certificate
    assert cert.passed, str(cert)
    assert all("symbolic derivation" not in cert[q][0] for q in cert)
    assert any(n.startswith("the symbolic derivation: skipped, ") and why in n for n in cert.notes)
