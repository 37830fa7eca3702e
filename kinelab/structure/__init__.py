"""Structure: mobility, connectivity, number and type synthesis (topology only)."""
from kinelab.structure._count import (LAMBDAS, PairClass, joint_catalogue, kutzbach_gruebler,
                                      pair_counts, pair_freedoms, space_dimension)
from kinelab.structure._mobility import Mobility, mobility

__all__ = [
    "LAMBDAS", "PairClass", "joint_catalogue", "kutzbach_gruebler", "pair_counts",
    "pair_freedoms", "space_dimension",
    "Mobility", "mobility",
]
