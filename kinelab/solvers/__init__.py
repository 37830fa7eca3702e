"""Generic numerical kernels: the solvers the notes teach, batched."""
from kinelab.solvers._bisect import bisect

__all__ = ["bisect"]
