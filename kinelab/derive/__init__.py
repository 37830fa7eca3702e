"""The derivation in the notes' notation (sympy): loop equations, J, Q, det J, K, L.

What a student of Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*
is asked to obtain by hand, obtained for any planar model kinelab analyses:

- :func:`derive` -- the position equations (one vector loop per independent circuit),
  J = dPhi/dS, Q = dPhi/dq, det J and its singular configurations, K = -J^-1 Q and
  L = dK/dq, and for a model with masses the Gibbs-Appell / Kane terms C, D, f
  (*Mecanismos*, §5), as a :class:`Derivation` of sympy objects;
- :meth:`Derivation.to_markdown`, :meth:`Derivation.to_latex` -- the document, in English
  or Portuguese, in the notes' order, with the numbers at one input beside the engine's;
- :func:`loop_equations` -- the position equations alone.
"""
from kinelab.derive._derivation import (LANGUAGES, MAX_UNKNOWNS, TIME_LIMIT, Derivation,
                                        DerivationValues, Singularity, derive)
from kinelab.derive._dynamics import Body, KaneDerivation
from kinelab.derive._loops import Loop, LoopEquations, loop_equations
from kinelab.derive._simplify import READABLE_OPS, SIMPLIFY_OPS, SIMPLIFY_SECONDS

__all__ = ["derive", "Derivation", "DerivationValues", "Singularity", "KaneDerivation", "Body",
           "loop_equations", "LoopEquations", "Loop", "LANGUAGES", "SIMPLIFY_OPS",
           "SIMPLIFY_SECONDS", "READABLE_OPS", "MAX_UNKNOWNS", "TIME_LIMIT"]
