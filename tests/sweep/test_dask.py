"""The same study on a Dask cluster of two worker processes on loopback: the same table."""
import signal
import time
from contextlib import contextmanager

import pandas as pd
import pytest

import kinelab as kl
from kinelab.errors import ModelError

distributed = pytest.importorskip("distributed")

LINKS = ("ground", "crank", "coupler", "rocker")


@contextmanager
def deadline(seconds):
    """Fail instead of hanging: a cluster that does not answer is an error."""
    def fail(*_):
        raise TimeoutError(f"the Dask test took more than {seconds} s")
    old = signal.signal(signal.SIGALRM, fail)
    signal.alarm(seconds)
    try:
        yield
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


def _kinelab_path():
    import kinelab
    return kinelab.__file__


def test_dask_gives_the_local_table():
    t = kl.sweep.random(3000, seed=8, **{k: (0.3, 3.0) for k in LINKS})
    t.loc[5, "crank"] = -2.0
    t["coupler_point_along"], t["coupler_point_perpendicular"] = 0.5, 0.25
    metrics = ("assembles", "reachable", "grashof", "transmission_min", "transmission_max",
               "time_ratio", "swing", "descriptors")
    with deadline(240):
        local = kl.sweep.run("fourbar", t, metrics=metrics, chunk_size=400)
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                      host="127.0.0.1", dashboard_address=":0") as cluster, \
                distributed.Client(cluster) as client:
            # the workers run this same kinelab, not another installed copy
            assert set(client.run(_kinelab_path).values()) == {_kinelab_path()}
            seen = []
            remote = kl.sweep.run("fourbar", t, metrics=metrics, chunk_size=400, client=client,
                                  progress=lambda done, total: seen.append(done))
            by_address = kl.sweep.run("fourbar", t.head(50), metrics=("grashof",),
                                      client=cluster.scheduler_address)
    pd.testing.assert_frame_equal(local, remote)                      # identical, not close
    assert remote.attrs["problems"] == local.attrs["problems"] == {5: "crank: expected a length from 1e-09 m to 1e+09 m, got -2"}
    assert sorted(seen) == seen and seen[-1] == 3000 and len(seen) == 8          # chunks of 400
    assert by_address["grashof"].tolist() == local["grashof"].head(50).tolist()


def test_an_unreachable_scheduler_is_an_error_in_seconds():
    start = time.monotonic()
    with deadline(60), pytest.raises(ModelError, match=r"scheduler: cannot reach 'tcp://127.0.0.1:9' "
                                                       r"within 5 s .*check the address"):
        kl.sweep.run("fourbar", {k: [1.0] for k in LINKS}, client="tcp://127.0.0.1:9")
    assert time.monotonic() - start < 30
