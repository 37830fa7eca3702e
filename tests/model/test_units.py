"""Units: the tables, the names of compound units and the factors, checked by hand."""
import math

import numpy as np
import pytest

import kinelab as kl
from kinelab.errors import ModelError
from kinelab.model import ANGLE_UNITS, LENGTH_UNITS, Units

DEG = math.pi / 180


def test_tables_are_exact_and_reexported_from_io():
    assert LENGTH_UNITS == {"m": 1.0, "cm": 0.01, "mm": 0.001, "in": 0.0254}
    assert ANGLE_UNITS == {"rad": 1.0, "deg": DEG}
    assert kl.io.Units is Units and kl.io.LENGTH_UNITS is LENGTH_UNITS
    assert kl.io.ANGLE_UNITS is ANGLE_UNITS


@pytest.mark.parametrize("si, mm_deg, factor", [
    # factor: file units per SI unit, worked by hand
    ("m", "mm", 1000.0),
    ("rad", "deg", 180 / math.pi),
    ("m/s", "mm/s", 1000.0),
    ("rad/s^2", "deg/s^2", 180 / math.pi),
    ("rad/rad", "deg/deg", 1.0),
    ("m/rad", "mm/deg", 1000.0 * DEG),
    ("rad/m", "deg/mm", (180 / math.pi) / 1000.0),
    ("m/rad^2", "mm/deg^2", 1000.0 * DEG ** 2),
    ("m/(rad*rad)", "mm/deg^2", 1000.0 * DEG ** 2),
    ("m/(rad*m)", "mm/(deg*mm)", DEG),
    ("rad/(m*m)", "deg/mm^2", (180 / math.pi) / 1e6),
    ("s", "s", 1.0),
])
def test_compound_units_by_hand(si, mm_deg, factor):
    u = Units("mm", "deg")
    assert u.unit(si) == mm_deg
    assert u.convert(2.5, si) == pytest.approx(2.5 * factor, rel=1e-15)
    assert Units().unit(si) == si.replace("(rad*rad)", "rad^2").replace("(m*m)", "m^2")
    assert Units().convert(2.5, si) == 2.5


def test_inches_and_arrays():
    u = Units("in", "rad")
    v = np.array([0.0254, 0.0508])
    np.testing.assert_array_equal(u.convert(v, "m"), [1.0, 2.0])
    assert u.unit("m/s^2") == "in/s^2"
    assert u.convert(v, "m").shape == (2,)


def test_resolve_keywords():
    assert Units.resolve() == Units("m", "rad")
    assert Units.resolve(degrees=True) == Units("m", "deg")
    assert Units.resolve({"length": "cm"}) == Units("cm", "rad")
    assert Units.resolve(Units("mm", "deg")) == Units("mm", "deg")
    assert Units.resolve({"angle": "deg"}, degrees=True) == Units("m", "deg")


@pytest.mark.parametrize("units, degrees, message", [
    ({"length": "km"}, False,
     r"^units\.length: expected one of 'm', 'cm', 'mm', 'in', got 'km' \(did you mean 'm'\?\)$"),
    ({"angle": "grad"}, False, r"^units\.angle: expected one of 'rad', 'deg', got 'grad'"),
    ({"lenght": "mm"}, False,
     r"^units: expected the keys 'length' and 'angle', got 'lenght' \(did you mean 'length'\?\)$"),
    ("mm", False, r"^units: expected a mapping such as \{'length': 'mm', 'angle': 'deg'\} or a "
                  r"kinelab Units, got 'mm'$"),
    ({"angle": "rad"}, True, r"^units\.angle: degrees=True asks for 'deg', got 'rad'; drop one"),
])
def test_bad_units_name_the_field_and_the_choices(units, degrees, message):
    with pytest.raises(ModelError, match=message):
        Units.resolve(units, degrees=degrees)


def test_an_unknown_si_spelling_is_a_programming_error():
    with pytest.raises(ValueError, match="not an SI unit kinelab converts: 'N\\*m'"):
        Units().unit("N*m")
