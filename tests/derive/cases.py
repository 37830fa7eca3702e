"""The models the derivation is checked on: every catalogue mechanism, every example model
and a few built here for the inputs the catalogue does not use (a relative angle, a slide,
a redundant link).  Derivations are cached: each is made once per test session."""
from functools import lru_cache
from pathlib import Path

import numpy as np

import kinelab as kl
from kinelab.derive import derive
from kinelab.model import Input, Mechanism

ROOT = Path(__file__).resolve().parents[2]
# the examples the derivation writes: not those with gear (G) or cam (C) joints, which it
# does not take, and says so (tests/kinematics/test_gears.py, test_cam_joint.py)
EXAMPLES = sorted(p.name for p in (ROOT / "examples").glob("*.toml")
                  if 'type = "G"' not in p.read_text() and 'type = "C"' not in p.read_text())


def _driven_at(m: Mechanism, **input_kw) -> Mechanism:
    return Mechanism(m.name, m.points, m.links, m.joints, (Input(**input_kw),))


CATALOGUE = {
    "fourbar": lambda: kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5,
                                             coupler_point=(1.0, 0.5)),
    "fourbar_crossed": lambda: kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0,
                                                     rocker=2.5, branch="crossed"),
    "slider_crank": lambda: kl.mechanisms.slider_crank(crank=1.0, rod=3.0, offset=0.2),
    "inverted_slider_crank": lambda: kl.mechanisms.inverted_slider_crank(ground=2.0, crank=1.0,
                                                                         offset=0.3),
    "slotted_link": lambda: kl.mechanisms.slotted_link(crank=1.0, distance=2.0),
    "whitworth": lambda: kl.mechanisms.whitworth(crank=1.0, distance=0.5, lever=1.0, rod=2.0,
                                                 ram_height=0.2),
    "fivebar": lambda: kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.5, coupler2=1.5,
                                             crank2=1.0),
    "watt6": kl.mechanisms.watt6,
    "stephenson6": kl.mechanisms.stephenson6,
    "triad6": kl.mechanisms.triad6,
}

BUILT = {
    # the four-bar driven at the crank pin: the coupler's angle relative to the crank's
    "fourbar_relative_input": lambda: _driven_at(CATALOGUE["fourbar"](), joint="jA"),
    # the angle between two moving links, given as a pair of links
    "fourbar_links_input": lambda: _driven_at(CATALOGUE["fourbar"](), links=("rocker", "coupler")),
    # the slider-crank driven by its slide (a compressor read backwards)
    "slider_driven": lambda: _driven_at(CATALOGUE["slider_crank"](), joint="slide"),
    # a parallelogram with an extra link: one loop equation is redundant
    "double_parallelogram": lambda: kl.load(ROOT / "tests" / "kinematics" / "double_parallelogram.toml"),
}


def model(name: str) -> Mechanism:
    if name in CATALOGUE:
        return CATALOGUE[name]()
    if name in BUILT:
        return BUILT[name]()
    return kl.load(ROOT / "examples" / name)


@lru_cache(maxsize=None)
def derivation(name: str, lang: str = "en"):
    return derive(model(name), lang)


def configurations(d, count: int, seed: int = 0) -> np.ndarray:
    """``count`` random inputs (count, M) where the model assembles, away from singular
    configurations: around the sketch, within the input range the model gives."""
    rng = np.random.default_rng(seed)
    m = d.model
    sketch = np.array([d.equations.sketch[s] for s in d.q])
    out = []
    for _ in range(200):
        q = sketch + rng.uniform(-0.6, 0.6, len(sketch))
        st = kl.kinematics.assembly_status(m, q if len(q) > 1 else q[0])
        if st.assembled[0] and st.singularity[0] > 0.05:
            out.append(q)
        if len(out) == count:
            return np.array(out)
    raise AssertionError(f"{m.name}: fewer than {count} assembled configurations near the sketch")


def four_slider_dyads() -> dict:
    """A crank driving four slider dyads (RRP) whose slide lines lie at odd angles, as a
    model file's JSON form: eight unknowns, the most a derivation takes, and expressions
    that stay large (its derivation takes tens of seconds)."""
    angles = (17.0, 71.0, 133.0, 251.0)
    points = {"O": [0.0, 0.0], "A": [0.0, 0.1]}
    links = [{"name": "crank", "points": ["O", "A"]}]
    joints = [{"name": "jO", "type": "R", "links": ["ground", "crank"], "point": "O"}]
    for i, angle in enumerate(angles):
        a = np.radians(angle)
        g = 0.2 * np.array([np.cos(a + 1), np.sin(a + 1)])
        d = np.array([np.cos(a), np.sin(a)])
        # B on the slide line through G, 0.5 from A
        b, c = (np.array([0.0, 0.1]) - g) @ d, (np.array([0.0, 0.1]) - g) @ (np.array([0.0, 0.1]) - g) - 0.25
        points[f"G{i}"] = g.tolist()
        points[f"B{i}"] = (g + (b + np.sqrt(b * b - c)) * d).tolist()
        links += [{"name": f"rod{i}", "points": ["A", f"B{i}"]},
                  {"name": f"slider{i}", "points": [f"B{i}"]}]
        joints += [{"name": f"jA{i}", "type": "R", "links": ["crank", f"rod{i}"], "point": "A"},
                   {"name": f"jB{i}", "type": "R", "links": [f"rod{i}", f"slider{i}"],
                    "point": f"B{i}"},
                   {"name": f"s{i}", "type": "P", "links": ["ground", f"slider{i}"],
                    "point": f"B{i}", "axis": angle, "origin": f"G{i}"}]
    ground = {"name": "ground", "points": ["O"] + [f"G{i}" for i in range(len(angles))],
              "ground": True}
    return {"schema": 1, "name": "four sliders", "units": {"length": "m", "angle": "deg"},
            "points": points, "links": [ground] + links, "joints": joints,
            "inputs": [{"joint": "jO", "range": [0, 360], "speed": 60}]}
