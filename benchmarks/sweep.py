"""Sweep benchmark: four-bar designs per second, locally and on Dask, beside two references.

    .venv/bin/python benchmarks/sweep.py [DESIGNS]        (or: make bench; default 10**6)

1. ``kl.sweep.run`` over DESIGNS four-bars x 72 crank angles with the Grashof class and the
   transmission-angle range, in this process, beside a plain-numpy reference written here
   (the law of cosines over the same (designs x angles) array and Grashof's inequality) in
   the same run;
2. the same study with all the standard metrics (time ratio and swing too);
3. a Python loop over ``kl.analyze`` (one engine call per design), on a sample of designs;
4. the same study on a Dask LocalCluster of 1 and then 2 worker processes (one thread
   each) on loopback, with the results checked equal to the local ones.

Wall time, best and median of three runs; CPU time of this process beside it (the machine
is shared).  Numbers, not a test: it never fails on speed.
"""
from __future__ import annotations

import statistics
import sys
import time

import numpy as np

import kinelab as kl

LINKS = ("ground", "crank", "coupler", "rocker")
SAMPLES = 72
REPEATS = 3


def designs(n: int):
    return kl.sweep.random(n, seed=0, **{k: (0.3, 3.0) for k in LINKS})


def timed(f, repeats=REPEATS):
    """(result, best wall, median wall, median CPU of this process), seconds."""
    walls, cpus, result = [], [], None
    for _ in range(repeats):
        w, c = time.perf_counter(), time.process_time()
        result = f()
        walls.append(time.perf_counter() - w)
        cpus.append(time.process_time() - c)
    return result, min(walls), statistics.median(walls), statistics.median(cpus)


def numpy_reference(t) -> dict:
    """Assembly and the transmission-angle range by the law of cosines, Grashof by the
    inequality: the least a vectorised four-bar sweep has to compute, in chunks of 10**4."""
    out = {"assembles": [], "grashof": [], "transmission_min": [], "transmission_max": []}
    q = np.linspace(0, 2 * np.pi, SAMPLES, endpoint=False)
    cos_q = np.cos(q)
    a = t[list(LINKS)].to_numpy()
    for lo in range(0, len(a), 10_000):
        g, c, b, r = (a[lo:lo + 10_000, i:i + 1] for i in range(4))
        cos_mu = (b * b + r * r - g * g - c * c + 2 * g * c * cos_q) / (2 * b * r)
        ok = (np.abs(cos_mu) <= 1).all(axis=1)
        mu = np.arccos(np.clip(cos_mu, -1, 1))
        acute = np.minimum(mu, np.pi - mu)
        s, l_ = a[lo:lo + 10_000].min(1), a[lo:lo + 10_000].max(1)
        grashof = s + l_ <= a[lo:lo + 10_000].sum(1) - s - l_
        out["assembles"].append(ok)
        out["grashof"].append(grashof)
        out["transmission_min"].append(np.where(ok, acute.min(1), np.nan))
        out["transmission_max"].append(np.where(ok, acute.max(1), np.nan))
    return {k: np.concatenate(v) for k, v in out.items()}


def line(label, n, best, median, cpu, ref=None):
    ratio = f"  x{median / ref:6.2f} of the reference" if ref else ""
    print(f"  {label:44s} {best:8.2f} s best {median:8.2f} s median {cpu:8.2f} s CPU "
          f"{n / median:12,.0f} designs/s{ratio}")


def main(n: int) -> None:
    t = designs(n)
    quick = ("assembles", "grashof", "transmission_min", "transmission_max")
    print(f"{n:,} four-bar designs x {SAMPLES} crank angles (random lengths 0.3 to 3 m)")
    ref, rb, rm, rc = timed(lambda: numpy_reference(t))
    line("plain numpy reference (law of cosines)", n, rb, rm, rc)
    df, b, m, c = timed(lambda: kl.sweep.run("fourbar", t, metrics=quick, progress=False))
    line("kl.sweep.run: grashof + transmission range", n, b, m, c, rm)
    same = (np.array_equal(df["assembles"].to_numpy(), ref["assembles"])
            and np.allclose(df["transmission_min"], ref["transmission_min"], atol=1e-12, equal_nan=True)
            and np.array_equal(df["grashof"].isin(["triple-rocker"]).to_numpy(), ~ref["grashof"]))
    print(f"  (sweep and reference agree: {same})")
    _, b, m, c = timed(lambda: kl.sweep.run("fourbar", t, progress=False))
    line("kl.sweep.run: + time ratio and swing", n, b, m, c, rm)

    few = min(n, 2000)
    q = np.linspace(0, 2 * np.pi, SAMPLES, endpoint=False)
    rows = t.head(few)[list(LINKS)].to_numpy()

    def loop():
        for row in rows:
            try:
                sol = kl.analyze(kl.mechanisms.fourbar(*row), q, unreachable="mask")
            except kl.errors.ModelError:
                continue
            kl.kinematics.transmission_angle(sol)
    _, b, m, c = timed(loop, repeats=1)
    line(f"Python loop over kl.analyze ({few:,} designs)", few, b, m, c)

    try:
        from distributed import Client, LocalCluster
    except ImportError:
        print("  (dask.distributed is not installed: no Dask numbers)")
        return
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          host="127.0.0.1", dashboard_address=":0") as cluster, Client(cluster) as client:
            kl.sweep.run("fourbar", t.head(1000), metrics=quick, client=client)   # warm the workers
            remote, b, m, c = timed(lambda: kl.sweep.run("fourbar", t, metrics=quick, client=client,
                                                         progress=False))
            line(f"on Dask, {workers} worker process{'es' if workers > 1 else ''}", n, b, m, c, rm)
            print(f"  (same table as the local run: {remote.equals(df)})")


if __name__ == "__main__":
    main(int(float(sys.argv[1])) if len(sys.argv) > 1 else 10 ** 6)
