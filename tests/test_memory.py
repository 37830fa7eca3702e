"""Reuse of result memory: only memory nothing references is handed out again."""
import numpy as np
import pytest

import kinelab as kl
from kinelab import _memory
from kinelab.errors import ModelError

MiB = 1 << 20


def address(a: np.ndarray) -> int:
    return a.__array_interface__["data"][0]


def test_dropped_block_is_reused_and_a_live_view_keeps_its_block():
    pool = _memory._Pool(64 * MiB)
    a = pool.empty((MiB // 8 + 5, 2))
    where = address(a)
    del a
    b = pool.empty((MiB // 8 + 5, 2))
    assert address(b) == where                         # dropped: its memory comes back
    view = b[::3, 1]                                   # a view keeps the block in use
    del b
    c = pool.empty((MiB // 8 + 5, 2))
    assert address(c) != where
    assert not np.shares_memory(view, c)


def test_a_smaller_request_takes_the_smallest_free_block_that_fits():
    pool = _memory._Pool(64 * MiB)
    big, small = pool.empty((4 * MiB,), np.uint8), pool.empty((2 * MiB,), np.uint8)
    where_small = address(small)
    del big, small
    assert address(pool.empty((MiB + 1,), np.uint8)) == where_small


def test_limit_bounds_what_is_held_and_zero_turns_reuse_off():
    pool = _memory._Pool(5 * MiB)
    kept = [pool.empty((2 * MiB,), np.uint8) for _ in range(3)]   # the third is not held
    assert pool.held() == 4 * MiB
    del kept
    pool.set_limit(0)
    assert pool.held() == 0
    a = pool.empty((2 * MiB,), np.uint8)
    assert pool.held() == 0 and a.shape == (2 * MiB,)


def test_small_arrays_are_plain_numpy():
    pool = _memory._Pool(64 * MiB)
    a = pool.empty((10, 3))
    assert a.base is None and pool.held() == 0


def test_analysis_never_writes_over_a_result_still_in_use():
    fb = kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0))
    n = 100_000                                        # results well over the pooling size
    first = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, n), qd=10.0)
    rocker = first.angle("rocker")
    kept = rocker.copy()
    del first
    second = kl.analyze(fb, q=np.linspace(1.0, 3.0, n), qd=-4.0, qdd=2.0)
    np.testing.assert_array_equal(rocker, kept)
    assert not np.shares_memory(rocker, second.stored_jets)
    # and memory that was let go gives the same numbers as fresh memory
    del rocker
    third = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, n), qd=10.0)
    old = kl.reuse_result_memory(0)
    try:
        fresh = kl.analyze(fb, q=np.linspace(0.0, 2 * np.pi, n), qd=10.0)
    finally:
        kl.reuse_result_memory(old)
    np.testing.assert_array_equal(third.stored_jets, fresh.stored_jets)
    np.testing.assert_array_equal(third.stored_rates, fresh.stored_rates)
    np.testing.assert_array_equal(third.det_J, fresh.det_J)


@pytest.mark.parametrize("bad", [-1, 1.5, "1G", True, None])
def test_limit_must_be_a_whole_number_of_bytes(bad):
    with pytest.raises(ModelError, match="max_bytes"):
        kl.reuse_result_memory(bad)


def test_analyses_in_several_threads_keep_their_own_results():
    from concurrent.futures import ThreadPoolExecutor
    mechanisms = [kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
                  kl.mechanisms.stephenson6(), kl.mechanisms.slider_crank(1.0, 3.0, offset=0.2)]
    q = np.linspace(0.0, 2 * np.pi, 60_000)
    expected = [kl.analyze(m, q=q, qd=2.0).stored_jets.copy() for m in mechanisms]

    def work(k):
        held = []
        for _ in range(6):
            held.append(kl.analyze(mechanisms[k % 3], q=q, qd=2.0))
            if len(held) > 2:
                held.pop(0)                                   # drop some, keep some
        return k, [s.stored_jets for s in held]

    with ThreadPoolExecutor(4) as pool:
        for k, results in pool.map(work, range(8)):
            for jets in results:
                np.testing.assert_array_equal(jets, expected[k % 3])
