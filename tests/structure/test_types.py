"""Type synthesis (*Mecanismos*, §3), its exercises, and the mobility of what it proposes."""
from fractions import Fraction

import pytest
from hypothesis import given, settings, strategies as st

from kinelab.errors import ModelError
from kinelab.structure import (active_chains, alternative_method, chain_types,
                               mobility, number_synthesis, passive_chain,
                               type_synthesis)

from .models import parallel


def test_example_3_1_table_and_architectures():
    # 9 + 5 nP1 = 6 Ne (Eq. 4): Ne = 7/3, 19/6, 4 for nP1 = 1, 2, 3
    s = number_synthesis(3, "spatial")
    assert s.table == ((1, Fraction(7, 3)), (2, Fraction(19, 6)), (3, Fraction(4)))
    assert all(9 + 5 * n == 6 * ne for n, ne in s.table)
    assert len(s.names) == 8 and set(s.names) == {a + b + c for a in "RP" for b in "RP" for c in "RP"}
    # the serial chains have the mobility they were made for
    assert all(mobility(parallel([n], "spatial")).exact == 3 for n in s.names)


def test_planar_open_chain_of_three_prismatic_pairs_is_left_out():
    # in the plane three P pairs give only two independent translations
    assert "PPP" not in number_synthesis(3, "planar").names
    assert len(number_synthesis(3, "planar").names) == 7


def test_example_3_2_gough_stewart():
    s = active_chains(6, "spatial")
    assert s.total_connectivity == 36 and s.connectivities == ((6, 6, 6, 6, 6, 6),)
    assert "6-UPS" in s.names and "6-SPS" not in s.names   # S-P-S: 7 freedoms, one idle
    assert mobility(parallel(["UPS"] * 6, "spatial")).exact == 6


def test_example_3_3_tricept():
    s = passive_chain("Rx Ry Tr", "spatial")
    assert s.total_connectivity == (6 + 1) * 3 and s.connectivities == ((6, 6, 6, 3),)
    assert "3-UPS+UP" in s.names
    assert all(a.actuators == 3 and a.chains[-1].actuated is None for a in s.architectures())
    assert mobility(parallel(["UPS"] * 3 + ["UP"], "spatial")).exact == 3


def test_example_3_4_alternative():
    s = alternative_method("Tx Ty", "planar")
    assert s.total_connectivity == (3 + 1) * 2 - 3 and s.names[0] == "RRR+PP"
    rrr_pp = s.architectures()[0]
    assert [c.actuated for c in rrr_pp.chains] == [0, 0]   # the pairs nearest the base
    assert mobility(parallel(["RRR", "PP"], "planar")).exact == 2


@given(st.sampled_from(["planar", "spherical", "spatial"]), st.integers(1, 6))
def test_connectivity_equations(space, m):
    lam = 6 if space == "spatial" else 3
    if m > lam:
        with pytest.raises(ModelError, match=f"mobility: expected a whole number from 1 to {lam}"):
            active_chains(m, space)
        return
    s = active_chains(m, space)
    assert s.total_connectivity == (lam + 1) * m - lam              # Eq. (5)
    for cs in s.connectivities:
        assert sum(cs) == s.total_connectivity and len(cs) == m
        assert all(m <= c <= lam for c in cs)                        # Eq. (6)
    for arch in s.architectures(limit=20):
        assert arch.total_connectivity == s.total_connectivity and arch.actuators == m


@settings(max_examples=15)
@given(st.integers(0, 10_000))
def test_proposed_architectures_have_the_mobility(k):
    # in general position every candidate of active-chain enumeration moves with M = 3
    s = active_chains(3, "spatial")
    arch = s.architectures(limit=k % s.count() + 1)[-1]
    model = parallel([c.name for c in arch.chains], "spatial", seed=k)
    assert mobility(model).exact == 3


def test_chain_types_connectivity_and_motion():
    assert [c.name for c in chain_types(2, "planar")] == ["RR", "RP", "PR", "PP"]
    assert [c.name for c in chain_types(2, "planar", motion="Tx Ty")] == ["PP"]
    assert {c.name for c in chain_types(3, "spatial", motion="Rz Tz Tr", max_joints=3)} == {
        "RPP", "PRP", "PPR", "CP", "PC"}
    six = chain_types(6, "spatial")
    assert all(c.connectivity == 6 and c.actuated is not None for c in six)
    assert "SS" not in {c.name for c in chain_types(6, "spatial", active=False)}  # idle spin
    assert [c.name for c in chain_types(3, "spherical")] == ["RRR"]


# -- Exercises 3.1 to 3.7 of the notes ---------------------------------------------------
def test_exercise_3_1_spherical_wrist():
    assert number_synthesis(3, "spherical", motion="Rx Ry Rz").names == ("RRR",)
    assert active_chains(3, "spherical").names == ("3-RRR",)
    assert mobility(parallel(["RRR"] * 3, "spherical")).exact == 3


def test_exercise_3_2_tz_rx_ry():
    assert number_synthesis(3, "spatial", motion="Tz Rx Ry").names == ("RRP", "RPR", "PRR")
    s = active_chains(3, "spatial")
    assert s.connectivities == ((6, 6, 3), (6, 5, 4), (5, 5, 5))
    assert "3-RPS" in s.names
    assert mobility(parallel(["RPS"] * 3, "spatial")).exact == 3


def test_exercise_3_3_tx_tz_rx_ry():
    assert len(number_synthesis(4, "spatial", motion="Tx Tz Rx Ry").names) == 6
    s = active_chains(4, "spatial")
    assert s.connectivities == ((6, 6, 6, 4), (6, 6, 5, 5))
    assert "3-UPS+PPU" in s.names and "PPU" in {c.name for c in chain_types(4, "spatial", motion="Tx Tz Rx Ry")}
    assert mobility(parallel(["UPS"] * 3 + ["PPU"], "spatial")).exact == 4


def test_exercise_3_4_spherical_two_rotations():
    s = passive_chain("Rx Ry", "spherical")
    assert s.names == ("2-RRR+RR",) and s.total_connectivity == 8
    assert mobility(parallel(["RRR", "RRR", "RR"], "spherical")).exact == 2


def test_exercise_3_5_cylindrical_workspace():
    s = passive_chain("Rz Tz Tr", "spatial")
    assert "3-UPS+RPP" in s.names and s.total_connectivity == 21
    assert mobility(parallel(["UPS"] * 3 + ["RPP"], "spatial")).exact == 3


def test_exercise_3_6_planar_translations_otherwise():
    others = [n for n in alternative_method("Tx Ty", "planar").names if n != "RRR+PP"]
    assert others == ["RRP+PP", "RPR+PP", "RPP+PP", "PRR+PP", "PRP+PP", "PPR+PP"]
    assert mobility(parallel(["RPR", "PP"], "planar")).exact == 2


def test_exercise_3_7_cylindrical_by_the_alternative_method():
    s = alternative_method("Rz Tz Tr", "spatial")
    assert "2-UPS+RPP" in s.names and s.total_connectivity == 7 * 3 - 6
    arch = next(a for a in s.architectures() if a.name == "2-UPS+RPP")
    assert [c.actuated for c in arch.chains] == [1, 1, 0]   # P of each UPS, the base R
    assert mobility(parallel(["UPS", "UPS", "RPP"], "spatial")).exact == 3


# -- bad input ------------------------------------------------------------------------------
@pytest.mark.parametrize("call, message", [
    (lambda: active_chains(0, "spatial"), r"mobility: expected a whole number from 1 to 6, got 0"),
    (lambda: active_chains(-2, "planar"), r"mobility: expected a whole number from 1 to 3, got -2"),
    (lambda: number_synthesis(4, "planar"), r"in a space of lambda = 3 an end link has at most 3"),
    (lambda: active_chains(2, 3), r"space: expected one of 'planar', 'spherical', 'spatial', got 3"),
    (lambda: passive_chain("Tx Tz", "spherical"), r"a spherical link has at most 3 rotations and 0"),
    (lambda: passive_chain("Rx Rz", "planar"), r"a planar link has at most 1 rotations and 2"),
    (lambda: passive_chain("Tx Qy", "planar"), r"motion: expected translations and rotations"),
    (lambda: passive_chain("Tx Tx", "planar"), r"names a displacement twice"),
    (lambda: chain_types(3, "spatial", joints=("R", "cam")), r"a spatial chain type is made of"),
    (lambda: type_synthesis("planar", 2, method="passive"), r"the passive method needs the wanted motion"),
    (lambda: type_synthesis("planar", 3, method="passive", motion="Tx Ty"), r"mobility: 3 does not match"),
    (lambda: type_synthesis("planar", 2, method="best"), r"method: expected one of 'open', 'active'"),
])
def test_bad_input(call, message):
    with pytest.raises(ModelError, match=message):
        call()
