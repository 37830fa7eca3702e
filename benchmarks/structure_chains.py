"""Time the enumeration of planar kinematic chains and their inversions (prints numbers).

The twelve-link chains of mobility 1 (5 loops) are beyond what ``planar_chains`` lists; they
are enumerated here without that limit, as a check of the published count.
"""
import time

from kinelab.structure._chains import _enumerate

# expected: the published counts (Tsai, Mechanism Design: Enumeration of Kinematic Structures)
for links, dof, expected in [(8, 1, 16), (10, 1, 230), (9, 2, 40), (11, 2, 839), (12, 1, 6856)]:
    _enumerate.cache_clear()
    t = time.perf_counter()
    chains = _enumerate(links, dof)
    t_chains = time.perf_counter() - t
    t = time.perf_counter()
    mechanisms = sum(len(c.inversions()) for c in chains)
    t_inv = time.perf_counter() - t
    check = "  (expected %d)" % expected
    print(f"{links:2d} links, F = {dof}: {len(chains):5d} chains in {t_chains:6.2f} s{check}; "
          f"{mechanisms:6d} inversions in {t_inv:6.2f} s")
