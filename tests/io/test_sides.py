"""A link's sides in model files: read in the file's length unit, written back as given,
round trips through TOML, JSON and the plain data the web page sends."""
import json
import math
from pathlib import Path

import pytest

import kinelab as kl
from kinelab.io import ModelFile
from kinelab.io._text import Written, in_si

ROOT = Path(__file__).resolve().parents[2]
JANSEN = ROOT / "examples" / "jansen.toml"


def test_sides_are_lengths_in_the_files_unit_converted_from_their_digits():
    top = kl.load(JANSEN).link("top")
    # each the float nearest the digits written times the unit's factor, as for the length
    cm = kl.model.LENGTH_UNITS["cm"]
    assert top.length == in_si(Written("41.5"), cm)
    assert top.sides == {"E": {"B": in_si(Written("40.1"), cm), "C": in_si(Written("55.8"), cm),
                               "side": "left"}}
    assert top.sides["E"]["B"] == pytest.approx(0.401, rel=1e-15)


def test_sides_are_written_as_given_one_point_to_a_line():
    mf = ModelFile.read(JANSEN)
    text = mf.to_toml()
    assert '[links.sides]\nE = {B = 40.1, C = 55.8, side = "left"}\n' in text
    assert '[links.sides]\nG = {D = 49.0, F = 65.7, side = "left"}\n' in text
    assert ModelFile.from_toml(text) == mf
    assert ModelFile.from_toml(text).to_toml() == text
    in_mm = kl.io.to_toml(mf.mechanism, units={"length": "mm", "angle": "deg"})
    assert 'E = {B = 401.0, C = 558.0, side = "left"}' in in_mm
    assert kl.io.from_toml(in_mm) == mf.mechanism


@pytest.mark.parametrize("length", ["m", "cm", "mm", "in"])
def test_sides_round_trip_exactly_in_every_unit(length, tmp_path):
    m = kl.load(JANSEN)
    for suffix in (".toml", ".json"):
        path = kl.io.save(m, tmp_path / f"jansen{suffix}", units={"length": length, "angle": "deg"})
        again = kl.load(path)
        assert again == m
        assert again.link("leg").sides == m.link("leg").sides


def test_the_web_pages_json_form_round_trips_sides():
    """As the page sends a model: the JSON form through plain JSON numbers, and the
    mechanism's own plain data."""
    mf = ModelFile.read(JANSEN)
    data = json.loads(json.dumps(mf.to_dict()))
    assert data["links"][4]["sides"] == {"E": {"B": 40.1, "C": 55.8, "side": "left"}}
    assert ModelFile.from_dict(data) == mf
    m = mf.mechanism
    assert kl.model.Mechanism.from_dict(json.loads(json.dumps(m.to_dict()))) == m


def test_a_coupler_point_by_sides_reads_as_the_python_link():
    text = (ROOT / "examples" / "crank_rocker.toml").read_text().replace(
        'local = { P = [150, 100] }', 'sides = { P = { A = 200, B = 150, side = "right" } }')
    coupler = kl.io.from_toml(text).link("coupler")
    assert coupler == kl.model.Link("coupler", ("A", "B", "P"), length=0.3,
                                    sides={"P": {"B": 0.15, "A": 0.2, "side": "right"}})
    # a flat triangle (100 + 200 = 300 mm) needs no side, and is written without one
    flat = kl.io.from_toml(text.replace('A = 200, B = 150, side = "right"', "A = 100, B = 200"))
    assert flat.link("coupler").sides == {"P": {"A": 0.1, "B": 0.2}}
    P, A, B = (flat.point(n).xy for n in "PAB")
    assert math.dist(P, A) == pytest.approx(0.1, rel=1e-12) and math.dist(P, B) == pytest.approx(0.2, rel=1e-12)
    assert "P = {A = 100.0, B = 200.0}" in kl.io.to_toml(flat, units={"length": "mm", "angle": "deg"})
