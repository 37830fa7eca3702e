"""The memory budget: large requests are refused before anything is allocated, with the
estimate, the budget and how to change it; work that needs little memory stays small."""
import numpy as np
import pytest
from click.testing import CliRunner

import kinelab as kl
from kinelab import _memory
from kinelab.cli import main
from kinelab.errors import MemoryBudgetError, ModelError
from kinelab.model import Link, Mechanism, Point


@pytest.fixture
def budget():
    old = kl.memory_budget()
    yield
    kl.memory_budget(old)


def test_a_billion_samples_are_refused_with_the_estimate(budget):
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5)
    q = np.broadcast_to(0.5, (10**9,))             # no memory behind it
    # 6 stored coordinates x (value, K, L, two rates) x 8 bytes, 3 copies of the inputs and
    # a status: 1e9 x (240 + 24 + 41) bytes = 284 GiB
    with pytest.raises(MemoryBudgetError, match=r"the results of 1,000,000,000 samples \(6 "
                       r"coordinates each, with K, L and rates\) would take about 284 GiB, more "
                       r"than the memory budget of 2 GiB; .* KINELAB_MEMORY_BUDGET"):
        kl.analyze(fb, q)


def test_the_budget_can_be_raised_and_lowered(budget):
    assert kl.memory_budget("1M") == 2 * 2**30
    with pytest.raises(MemoryBudgetError, match="more than the memory budget of 1 MiB"):
        kl.analyze(kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5), np.linspace(0, 1, 20_000))
    assert kl.memory_budget(3 * 2**30) == 2**20
    assert kl.memory_budget() == 3 * 2**30


@pytest.mark.parametrize("text, expected", [("8G", 8 * 2**30), ("512M", 512 * 2**20), ("1.5g", int(1.5 * 2**30)),
                                            ("2000000000", 2_000_000_000), ("64KiB", 64 * 2**10)])
def test_sizes(text, expected):
    assert _memory.parse_size(text, "x") == expected


@pytest.mark.parametrize("text", ["", "lots", "-1G", "0", "nanG", "infM"])
def test_bad_sizes(text):
    with pytest.raises(ModelError, match="x: expected a size such as 8G, 512M or a number of bytes"):
        _memory.parse_size(text, "x")


def test_the_environment_sets_the_default(monkeypatch, budget):
    monkeypatch.setenv("KINELAB_MEMORY_BUDGET", "3G")
    assert _memory._budget_from_environment() == 3 * 2**30
    monkeypatch.setenv("KINELAB_MEMORY_BUDGET", "three")
    with pytest.raises(ModelError, match="KINELAB_MEMORY_BUDGET: expected a size"):
        _memory._budget_from_environment()


def test_a_huge_grid_of_inputs_is_refused_before_it_is_built():
    mf = kl.io.ModelFile.read("examples/fivebar.toml")
    grid = kl.io.ModelFile(mechanism=mf.mechanism, units=mf.units, samples=(1_000_000, 1_000_000),
                           sweep="grid")
    with pytest.raises(MemoryBudgetError, match=r"the inputs of 1,000,000,000,000 samples \(a grid "
                                                r"of 1,000,000 x 1,000,000\)"):
        grid.sample_inputs()


def test_limits_need_no_memory_for_unused_points(budget):
    """As many points as a model may have (MAX_POINTS) on the coupler: finding where it
    assembles writes no coordinates (the whole table would be 1441 x 4,000 x 3 doubles,
    138 MB)."""
    fb = kl.mechanisms.fourbar(1.0, 2.0, 1.0, 1.5)          # non-Grashof: limits to find
    extra = tuple(Point(f"P{i}", 0.5 + 1e-5 * i, 1.0) for i in range(kl.model.MAX_POINTS - 4))
    links = tuple(Link("coupler", ("A", "B") + tuple(p.name for p in extra)) if link.name == "coupler"
                  else link for link in fb.links)
    m = Mechanism("many points", fb.points + extra, links, fb.joints, fb.inputs)
    kl.memory_budget("64M")
    (lo, hi), = kl.kinematics.reachable_ranges(m)
    assert hi == pytest.approx(np.arccos(-0.3125), abs=1e-9) and lo == pytest.approx(-hi, abs=1e-9)


def test_the_command_line_option(tmp_path, budget):
    result = CliRunner().invoke(main, ["--memory-budget", "1M", "analyze", "examples/crank_rocker.toml",
                                       "--samples", "100000", "--out", str(tmp_path / "out")])
    assert result.exit_code == 2
    assert result.stderr.count("\n") == 1 and "more than the memory budget of 1 MiB" in result.stderr
    assert not (tmp_path / "out").exists()


def test_check_of_a_large_model_needs_little_memory(tmp_path, budget):
    """A coupler carrying as many points as a model may have (MAX_POINTS): reading, planning
    and checking its sweep stay within a 16 MiB budget (analysing the sweep would need about
    70 MB)."""
    from tests.io.bad_cases import BASE

    n = kl.model.MAX_POINTS - 4
    extra = "".join(f"X{i} = [{100 + i * 1e-3}, 150]\n" for i in range(n))
    names = ", ".join(f'"X{i}"' for i in range(n))
    text = (BASE.replace("O4 = [300, 0]", "O4 = [300, 0]\n" + extra)
            .replace('points = ["A", "B"]', f'points = ["A", "B", {names}]'))
    path = tmp_path / "big.toml"
    path.write_text(text)
    result = CliRunner().invoke(main, ["--memory-budget", "16M", "check", str(path)])
    assert result.exit_code == 0, result.output
    assert "sweep: 361 samples assemble, none singular" in result.stdout
