"""Canonical labelling of small graphs, by colour refinement and individualisation.

Two graphs are isomorphic exactly when their canonical forms are equal.  The graph is a
symmetric matrix of entries (0 for no edge, or any comparable value: an edge
multiplicity, a tuple of labels); the diagonal holds loops.  The method is the one of
nauty, without its pruning by automorphisms, which the small graphs of kinematic chains
(a dozen vertices) do not need:

1. refine: colour each vertex by its colour and the multiset of (entry, colour) of its
   neighbours, until no colour class splits (an equitable partition); colours are
   numbered by sorting these signatures, so the numbering does not depend on how the
   vertices were labelled;
2. if some class has several vertices, try each of them in turn as a class of its own
   (individualise), refine, and go on;
3. every branch ends with all vertices told apart, i.e. an ordering; the canonical form
   is the smallest matrix, written in that ordering, over all branches.
"""
from __future__ import annotations

from collections.abc import Hashable, Sequence

__all__ = ["canonical_form", "orbits"]


def _refine(colors: list, adj: list[list[tuple[int, Hashable]]]) -> list[int]:
    while True:
        sig = [(colors[v], tuple(sorted((e, colors[w]) for w, e in adj[v])))
               for v in range(len(colors))]
        ranks = {s: k for k, s in enumerate(sorted(set(sig)))}
        new = [ranks[s] for s in sig]
        if len(ranks) == len(set(colors)):
            return new
        colors = new


def canonical_form(matrix: Sequence[Sequence], colors: Sequence | None = None,
                   absent=0) -> tuple[tuple, tuple[int, ...]]:
    """Canonical form of a graph given by a symmetric matrix of comparable entries.

    Parameters
    ----------
    matrix : square sequence of sequences
        ``matrix[i][j]``: the edge between vertices i and j (``absent`` for none); the
        diagonal holds what sits on a vertex (its loops).
    colors : sequence, optional
        A colour per vertex that isomorphisms must keep (e.g. the ground link).
    absent : optional
        The entry meaning "no edge".

    Returns
    -------
    form : tuple of tuples
        The vertex colours and loops, then the matrix, with rows and columns in canonical
        order; equal for isomorphic graphs.
    order : tuple of int
        ``order[k]`` is the vertex placed k-th.

    Examples
    --------
    A path 0-1-2 labelled two ways has one form:

    >>> from kinelab.structure._canon import canonical_form
    >>> a = [[0, 1, 0], [1, 0, 1], [0, 1, 0]]
    >>> b = [[0, 0, 1], [0, 0, 1], [1, 1, 0]]
    >>> canonical_form(a)[0] == canonical_form(b)[0]
    True
    """
    n = len(matrix)
    adj = [[(w, matrix[v][w]) for w in range(n) if w != v and matrix[v][w] != absent]
           for v in range(n)]
    start = [(c, matrix[v][v]) for v, c in enumerate(colors or [0] * n)]
    ranks = {s: k for k, s in enumerate(sorted(set(start)))}
    best: list = [None, None]

    def search(cols: list[int]) -> None:
        cols = _refine(cols, adj)
        if len(set(cols)) == n:
            order = sorted(range(n), key=cols.__getitem__)
            form = (tuple(start[v] for v in order),) + tuple(
                tuple(matrix[order[i]][order[j]] for j in range(n)) for i in range(n))
            if best[0] is None or form < best[0]:
                best[0], best[1] = form, tuple(order)
            return
        sizes: dict[int, int] = {}
        for c in cols:
            sizes[c] = sizes.get(c, 0) + 1
        target = min(c for c, k in sizes.items() if k > 1)
        for v in (v for v in range(n) if cols[v] == target):
            search([2 * c + (c == target and u != v) for u, c in enumerate(cols)])

    if n == 0:
        return (), ()
    search([ranks[s] for s in start])
    return best[0], best[1]


def orbits(matrix: Sequence[Sequence], absent=0) -> list[list[int]]:
    """Classes of vertices that some automorphism of the graph maps onto one another.

    Vertices u and v are in one orbit exactly when the graph with u marked and the graph
    with v marked are isomorphic.

    Examples
    --------
    >>> from kinelab.structure._canon import orbits
    >>> orbits([[0, 1, 0], [1, 0, 1], [0, 1, 0]])      # a path: the ends, the middle
    [[0, 2], [1]]
    """
    n = len(matrix)
    by_form: dict[tuple, list[int]] = {}
    for v in range(n):
        form = canonical_form(matrix, [int(u == v) for u in range(n)], absent)[0]
        by_form.setdefault(form, []).append(v)
    return sorted(by_form.values())
