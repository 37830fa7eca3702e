"""Arguments of the structure room: each bad one is a ModelError naming it, on one line."""
import pytest

from kinelab.errors import ModelError
from kinelab.structure import (chain_of, connectivity, count_chains, generated_group,
                               lie_mobility, mobility, pair_counts, planar_chains)

from .models import disk_cam_flat_follower, fourbar, parallelogram_fivebar, rssr


# the textbook values (Kutzbach-Gruebler and the rank agree on them, see test_mobility.py)
# at the default tolerance and at both ends of the range a caller may choose
@pytest.mark.parametrize("rtol", [None, 1e-13, 1e-12, 1e-9, 1e-6, 1e-3])
@pytest.mark.parametrize("build, exact", [
    (fourbar, 1), (parallelogram_fivebar, 1), (rssr, 1), (disk_cam_flat_follower, 1)])
def test_mobility_at_legal_tolerances(build, exact, rtol):
    m = mobility(build()) if rtol is None else mobility(build(), rtol=rtol)
    assert m.exact == exact


@pytest.mark.parametrize("rtol, shown", [
    (float("nan"), "nan"), (float("inf"), "inf"), (1.0, "1.0"), (10, "10"), (-1, "-1"),
    (0, "0"), (0.5, "0.5"), (1e-16, "1e-16"), ("a", "'a'"), (None, "None"), (True, "true"),
    (10**400, "a whole number of 401 digits")])
def test_mobility_refuses_a_tolerance_out_of_range(rtol, shown):
    with pytest.raises(ModelError, match=r"^rtol: expected a relative tolerance from 1e-13 to "
                       r"0\.001 \(default 1e-09\), got " + shown.replace(".", r"\.")) as info:
        mobility(fourbar(), rtol=rtol)
    assert "\n" not in str(info.value)


def test_generated_group_checks_its_tolerance_too():
    with pytest.raises(ModelError, match="rtol: expected a relative tolerance"):
        generated_group([[0, 1, 0, 0, 0, 0]], rtol=float("nan"))


@pytest.mark.parametrize("call", [
    lambda: chain_of(None), lambda: pair_counts(None), lambda: mobility(None),
    lambda: connectivity(None, "a", "b"), lambda: lie_mobility(None, "a"),
    lambda: pair_counts("fourbar.toml")])
def test_model_must_be_a_mechanism(call):
    with pytest.raises(ModelError, match=r"^model: expected a kinelab\.model\.Mechanism, got "):
        call()


@pytest.mark.parametrize("seed, shown", [("a", "'a'"), (-1, "-1"), (1.5, "1.5"), (True, "true")])
def test_sketch_seed_is_a_whole_number(seed, shown):
    with pytest.raises(ModelError, match=f"^seed: expected a whole number >= 0, got {shown}"):
        planar_chains(6)[0].to_mechanism(seed=seed)


def test_sketch_ground_is_a_link_index():
    with pytest.raises(ModelError, match="^ground: expected a link of the chain, 0 to 5, got true"):
        planar_chains(6)[0].to_mechanism(ground=True)


@pytest.mark.parametrize("links, dof, message", [
    (10**400, 1, "links: a whole number of 401 digits is beyond what is enumerated"),
    (10**400, 2, "links: a whole number of 401 digits is beyond what is enumerated"),
    (13, 10**400, "mobility: a whole number of 401 digits is beyond what is enumerated"),
    (10, 10**16, "mobility: 10000000000000000 is beyond what is enumerated"),
])
def test_huge_counts_are_described_not_printed(links, dof, message):
    with pytest.raises(ModelError, match=message) as info:
        count_chains(links, dof)
    assert len(str(info.value)) < 300
