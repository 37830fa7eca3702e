"""Sweeps of every family: design-samples per second of processor time, beside references.

    .venv/bin/python benchmarks/families.py [DESIGNS]        (default 20,000)

For each family (the catalogue's kinds with one input, and Stephenson, Watt and triad
six-bars whose designs move their points), DESIGNS designs x 72 input angles, and the
two-input five-bar's designs on 72 pairs of crank angles:

1. ``kl.kinematics.analyze_designs``: the full analysis (positions, velocities,
   accelerations) of every design at every sample in one call;
2. ``kl.sweep.run`` with the family's standard metrics (for the six-bars: the transmission
   angle's range and the time ratio of the output);
3. a Python loop over ``kl.analyze`` (one engine call per design, as sweeps of these
   families ran before), on 200 designs;

beside, in the same run, the plain-numpy closed form of the four-bar (the law of cosines
over the same designs x samples: assembly and transmission angle), the least a sweep has to
compute.  Processor time of this process (the machine is shared), best of three; the load
average is printed.  Numbers, not a test: it never fails on speed.
"""
from __future__ import annotations

import dataclasses
import os
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

import kinelab as kl

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = 72
REPEATS = 3
Q = np.linspace(0.0, 2 * np.pi, SAMPLES, endpoint=False)


def cpu(f, repeats=REPEATS):
    """(result, best processor time in s)."""
    best, result = np.inf, None
    for _ in range(repeats):
        c = time.process_time()
        result = f()
        best = min(best, time.process_time() - c)
    return result, best


def catalogue(kind: str, n: int, rng) -> tuple[kl.sweep.Family, pd.DataFrame]:
    u = lambda lo, hi: rng.uniform(lo, hi, n)          # noqa: E731
    columns = {"fourbar": dict(ground=u(2, 3), crank=u(0.5, 1), coupler=u(2, 3), rocker=u(2, 3)),
               "slider_crank": dict(crank=u(0.5, 1.5), rod=u(2, 4), offset=u(-0.3, 0.3)),
               "inverted_slider_crank": dict(ground=u(1.5, 3), crank=u(0.5, 1.2), offset=u(-0.2, 0.2)),
               "slotted_link": dict(crank=u(0.5, 1.5), distance=u(1.6, 3)),
               "whitworth": dict(crank=u(1, 2), distance=u(0.1, 0.9), lever=u(0.5, 2),
                                 rod=u(2.5, 4), ram_height=u(-0.3, 0.3))}[kind]
    return kl.sweep.family(kind), pd.DataFrame(columns)


def moved(mechanism, n: int, rng, spread: float, **roles):
    """A model's family with its points moved at random (normal, ``spread`` of its size)."""
    size = np.ptp([p.xy[:2] for p in mechanism.points], axis=0).max()
    columns = {f"{p.name}.{c}": getattr(p, c) + rng.normal(0.0, spread * size, n)
               for p in mechanism.points if p.name != "O2" for c in "xy"}
    return kl.sweep.family(mechanism, **roles), pd.DataFrame(columns)


def points_of(fam, designs: pd.DataFrame) -> tuple[kl.Mechanism, np.ndarray, dict]:
    """The arguments of analyze_designs for a family's designs (their sketches)."""
    from kinelab.sweep._family import _SketchedDesigns
    prepared = _SketchedDesigns(fam, {c: designs[c].to_numpy() for c in designs}, [""] * len(designs))
    good = np.array([not p for p in prepared.problems])
    return (prepared.template, prepared.points[good],
            {k: a[good] for k, a in prepared.axes.items()} or None)


def numpy_fourbar(n: int, rng) -> float:
    """Processor time of the four-bar's law of cosines over n designs x SAMPLES."""
    g, c, b, r = (rng.uniform(lo, hi, (n, 1)) for lo, hi in ((2, 3), (0.5, 1), (2, 3), (2, 3)))
    cos_q = np.cos(Q)

    def run():
        cos_mu = (b * b + r * r - g * g - c * c + 2 * g * c * cos_q) / (2 * b * r)
        mu = np.arccos(np.clip(cos_mu, -1, 1))
        return (np.abs(cos_mu) <= 1).all(axis=1), np.minimum(mu, np.pi - mu).min(axis=1)
    return cpu(run)[1]


def main(n: int) -> None:
    rng = np.random.default_rng(0)
    print(f"{n:,} designs x {SAMPLES} samples per family; load average "
          f"{', '.join(f'{x:.1f}' for x in os.getloadavg())}")
    ref = numpy_fourbar(n, rng)
    print(f"  {'plain-numpy four-bar (law of cosines)':40s} {n * SAMPLES / ref:14,.0f} design-samples/s")
    families = [(k,) + catalogue(k, n, rng) for k in
                ("slider_crank", "inverted_slider_crank", "slotted_link", "whitworth", "fourbar")]
    s6 = kl.load(ROOT / "examples" / "stephenson6.toml")
    families.append(("Stephenson six-bar",) + moved(s6, n, rng, 0.002, output="output",
                                                   transmission=("link5", "output")))
    watt = dataclasses.replace(kl.mechanisms.watt6(), parameters={})      # its points as columns
    families.append(("Watt six-bar",) + moved(watt, n, rng, 0.002, output="output",
                                             transmission=("link5", "output")))
    triad = dataclasses.replace(kl.mechanisms.triad6(), parameters={})
    families.append(("triad six-bar (Newton)",) + moved(triad, n, rng, 0.002, output="link5"))
    print(f"  {'family':28s} {'analyze_designs':>16s} {'sweep.run':>16s} {'loop of analyze':>16s}"
          "   (design-samples/s of processor time; x: of the plain-numpy four-bar)")
    for label, fam, designs in families:
        mech, points, axes = points_of(fam, designs)
        kl.kinematics.analyze_designs(mech, points[:10], Q, 1.0, axes=None if axes is None else
                                      {k: a[:10] for k, a in axes.items()})   # loaded once
        _, full = cpu(lambda: kl.kinematics.analyze_designs(mech, points, Q, 1.0, axes=axes))
        _, swept = cpu(lambda: kl.sweep.run(fam, designs, samples=SAMPLES, progress=False))
        few = designs.head(200)
        built = [fam.build(row) for row in few.to_dict("records")]
        _, looped = cpu(lambda: [kl.analyze(m, Q, 1.0, unreachable="mask", at_singular="flag")
                                 for m in built], repeats=1)
        rate = [len(points) * SAMPLES / full, n * SAMPLES / swept, len(few) * SAMPLES / looped]
        print(f"  {label:28s} " + " ".join(f"{r:10,.0f} x{r * ref / (n * SAMPLES):4.2f}"
                                           for r in rate))
    # the five-bar has two inputs: no sweep of one input's turn, the analysis of its designs
    # on a circle of both cranks' angles about the sketch
    five = kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.5, coupler2=1.5, crank2=1.0)
    sketch = np.array([p.xy[:2] for p in five.points])
    points = sketch + rng.normal(0.0, 0.002, (n,) + sketch.shape)
    q = kl.kinematics.plan(five).q_sketch + 0.3 * np.stack([np.cos(Q), np.sin(Q)], -1)
    kl.kinematics.analyze_designs(five, points[:10], q, 1.0)
    _, full = cpu(lambda: kl.kinematics.analyze_designs(five, points, q, 1.0))
    built = [dataclasses.replace(five, points=tuple(dataclasses.replace(p, x=x, y=y) for p, (x, y)
                                                    in zip(five.points, d))) for d in points[:200]]
    _, looped = cpu(lambda: [kl.analyze(m, q, 1.0, unreachable="mask", at_singular="flag")
                             for m in built], repeats=1)
    rate = [n * SAMPLES / full, 200 * SAMPLES / looped]
    print(f"  {'fivebar (two inputs)':28s} {rate[0]:10,.0f} x{rate[0] * ref / (n * SAMPLES):4.2f} "
          f"{'':16s} {rate[1]:10,.0f} x{rate[1] * ref / (n * SAMPLES):4.2f}")


if __name__ == "__main__":
    main(int(float(sys.argv[1])) if len(sys.argv) > 1 else 20_000)
