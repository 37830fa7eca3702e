"""Time of one edit of a dimension, re-assembled (``Mechanism.with_dimensions`` through
``kinelab.kinematics.reassemble``): per catalogue mechanism, the median time of edits that
assemble (continuation, and the search over branches where the path stops) and of edits
that are refused (with the gap, the inputs that reach and the nearest length in the
message), over seeded random edits of one length by up to three times either way.

Prints one line per mechanism, in ms.
"""
import statistics
import sys
import time

import numpy as np

import kinelab as kl


def main(edits: int = 200) -> None:
    rng = np.random.default_rng(1)
    catalogue = {
        "fourbar": kl.mechanisms.fourbar(3.0, 1.0, 3.0, 2.5, coupler_point=(1.5, 1.0)),
        "slider_crank": kl.mechanisms.slider_crank(1.0, 3.0, offset=0.5),
        "inverted_slider_crank": kl.mechanisms.inverted_slider_crank(2.0, 1.0),
        "slotted_link": kl.mechanisms.slotted_link(1.0, 2.0),
        "whitworth": kl.mechanisms.whitworth(1.0, 0.5, 3.0, 2.5),
        "fivebar": kl.mechanisms.fivebar(3.0, 1.0, 2.0, 2.0, 1.5),
        "watt6": kl.mechanisms.watt6(),
        "stephenson6": kl.mechanisms.stephenson6(),
        "triad6": kl.mechanisms.triad6(),
    }
    print(f"{'mechanism':24s} {'assembled':>10s} {'ms':>7s} {'refused':>8s} {'ms':>7s}")
    for name, m in catalogue.items():
        links = [link for link in m.links if not link.ground and len(link.points) >= 2]
        times = {"assembled": [], "refused": []}
        for _ in range(edits):
            link = links[rng.integers(len(links))]
            a, b = (np.array(m.point(p).xy) for p in link.points[:2])
            length = float(np.hypot(*(b - a))) * float(np.exp(rng.uniform(-1.1, 1.1)))
            t0 = time.perf_counter()
            try:
                kl.kinematics.reassemble(m, lengths={link.name: length})
                kind = "assembled"
            except kl.errors.AssemblyError:
                kind = "refused"
            times[kind].append(1e3 * (time.perf_counter() - t0))
        row = [f"{name:24s}"]
        for kind in ("assembled", "refused"):
            t = times[kind]
            row.append(f"{len(t):>10d} {statistics.median(t) if t else float('nan'):>7.2f}")
        print(" ".join(row))


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 200)
