"""Structure: mobility, connectivity, number and type synthesis (topology only)."""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.structure._chains": ("Inversion", "KinematicChain", "chain_of", "count_chains",
                                  "planar_chains"),
    "kinelab.structure._connectivity": ("Chain", "Connectivity", "LieMobility", "connectivity",
                                        "lie_mobility"),
    "kinelab.structure._count": ("LAMBDAS", "PairClass", "joint_catalogue", "kutzbach_gruebler",
                                 "pair_counts", "pair_freedoms", "space_dimension"),
    "kinelab.structure._groups": ("DisplacementGroup", "displacement_group", "generated_group"),
    "kinelab.structure._mobility": ("Mobility", "mobility"),
    "kinelab.structure._types": ("Architecture", "ChainType", "Motion", "TypeSynthesis",
                                 "active_chains", "alternative_method", "chain_types",
                                 "number_synthesis", "passive_chain", "type_synthesis"),
})

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
