"""Structure: mobility, connectivity, number and type synthesis (topology only)."""
from kinelab.structure._chains import (Inversion, KinematicChain, chain_of, count_chains,
                                       planar_chains)
from kinelab.structure._connectivity import (Chain, Connectivity, LieMobility, connectivity,
                                             lie_mobility)
from kinelab.structure._count import (LAMBDAS, PairClass, joint_catalogue, kutzbach_gruebler,
                                      pair_counts, pair_freedoms, space_dimension)
from kinelab.structure._groups import DisplacementGroup, displacement_group, generated_group
from kinelab.structure._mobility import Mobility, mobility
from kinelab.structure._types import (Architecture, ChainType, Motion, TypeSynthesis,
                                      active_chains, alternative_method, chain_types,
                                      number_synthesis, passive_chain, type_synthesis)

__all__ = [
    # counting (*Mecanismos*, §2.1)
    "LAMBDAS", "PairClass", "joint_catalogue", "kutzbach_gruebler", "pair_counts",
    "pair_freedoms", "space_dimension",
    # exact mobility
    "Mobility", "mobility",
    # Lie groups and connectivity (§1.3, §2.2)
    "DisplacementGroup", "displacement_group", "generated_group",
    "Chain", "Connectivity", "LieMobility", "connectivity", "lie_mobility",
    # structural synthesis of planar chains
    "Inversion", "KinematicChain", "chain_of", "count_chains", "planar_chains",
    # type synthesis (§3)
    "Architecture", "ChainType", "Motion", "TypeSynthesis", "active_chains",
    "alternative_method", "chain_types", "number_synthesis", "passive_chain",
    "type_synthesis",
]
