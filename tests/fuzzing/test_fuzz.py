"""Hostile model files, task files, CSV tables and atlases, generated from valid ones (see
``grammar.py``): each ends in success or in one bounded line per problem naming the file,
with exit status 2, quickly; hostile requests to the web app end in 2xx or a one-line JSON
4xx, and hostile names in files written in --out only, under safe names.  A modest number
of cases here; ``benchmarks/fuzz_model_files.py`` runs 10^5 and more."""
import random
import time

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from kinelab import _compiled
from tests.fuzzing import grammar


@pytest.fixture(scope="module", autouse=True)
def _kernel_ready():
    """Every entry point of the compiled kernel loaded (or compiled, on a cold cache) before
    the first case: the suite runs in "compiled" mode, where the first call of an entry point
    compiles it in the calling thread, and the cases' time limits are for the work, not for
    numba (a server in the default mode never compiles in a request; see ``_compiled``)."""
    _compiled.wait()


@settings(max_examples=150, suppress_health_check=[HealthCheck.too_slow,
                                                   HealthCheck.function_scoped_fixture])
@given(rng=st.randoms(use_true_random=False))
def test_a_hostile_file_ends_in_one_line_or_success(rng, tmp_path_factory):
    c = grammar.case(rng)
    start = time.perf_counter()
    outcome, detail = grammar.run(c, tmp_path_factory.mktemp("case"))
    elapsed = time.perf_counter() - start
    assert outcome in grammar.FINE, (outcome, detail, c.command, c.suffix, c.text[:500])
    assert elapsed < 60.0, (elapsed, c.command)           # generous: a check takes well under 1 s


@settings(max_examples=60, suppress_health_check=[HealthCheck.too_slow,
                                                  HealthCheck.function_scoped_fixture])
@given(rng=st.randoms(use_true_random=False))
def test_a_hostile_table_task_or_atlas_ends_in_one_line_naming_it_or_success(rng, tmp_path_factory):
    c = grammar.any_case(rng)
    outcome, detail = grammar.run(c, tmp_path_factory.mktemp("case"))
    assert outcome in grammar.FINE, (outcome, detail, c.family, c.command, c.text[:500])


@settings(max_examples=40, suppress_health_check=[HealthCheck.too_slow])
@given(rng=st.randoms(use_true_random=False))
def test_a_hostile_request_gets_json_2xx_or_4xx_in_one_line(rng):
    c = grammar.web_case(rng)
    outcome, detail = grammar.run_web(c, seconds=30.0)
    assert outcome in grammar.FINE, (outcome, detail, c.command, c.text[:500])


@settings(max_examples=6, suppress_health_check=[HealthCheck.too_slow,
                                                 HealthCheck.function_scoped_fixture])
@given(rng=st.randoms(use_true_random=False))
def test_hostile_names_are_written_in_out_under_safe_names(rng, tmp_path_factory):
    c = grammar.names_case(rng)
    outcome, detail = grammar.run_names(c, tmp_path_factory.mktemp("case"))
    assert outcome in grammar.FINE, (outcome, detail, c.command, c.stem, c.text[:500])


# cases the fuzzing found (benchmarks/fuzz_model_files.py, 100,000 cases): a huge pivot
# abscissa in a synthesis task (three seeds), a dynamics run with no finite effort, and a
# gravity component too large for a float
@pytest.mark.parametrize("seed", [129989, 141339, 153981, 139037, 149413])
def test_cases_that_once_escaped(seed, tmp_path):
    outcome, detail = grammar.run(grammar.case(random.Random(seed)), tmp_path)
    assert outcome in grammar.FINE, (outcome, detail)


# requests and names the fuzzing found (benchmarks/fuzz_model_files.py --files web,names),
# each with the families it was drawn from: a model of 10,000 problems answered with all of
# them in "problems", past the 20 lines of its message; a column and a model named with two
# $ (mathtext) in differentiate's and plot's figures
@pytest.mark.parametrize("families, seed", [(("web",), 439), (("names",), 3), (("names",), 20)])
def test_requests_and_names_that_once_escaped(families, seed, tmp_path):
    outcome, detail = grammar.run(grammar.any_case(random.Random(seed), families), tmp_path)
    assert outcome in grammar.FINE, (outcome, detail)
