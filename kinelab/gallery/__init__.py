"""A gallery of classic mechanisms, each a model file shipped in the package.

Watt's and Chebyshev's straight-line linkages and Watt's beam engine, the exact inversors of Peaucellier-Lipkin and
Hart, Jansen's and Klann's legs, quick returns, Grashof's classes of the four-bar,
slider-cranks, presses, six-bars and more, and five spatial linkages (Sarrus's, Bennett's, the
Cardan joint and shaft, the 6-SPS platform), whose files describe them for ``kinelab check``
and whose motion :mod:`kinelab.spatial` analyses: :func:`names` lists them, :func:`entry` gives one's title, a note of its
history and the path of its model file, and :func:`load` reads that file as
:meth:`kinelab.io.ModelFile.read` does.  ``kinelab gallery`` lists them on the command line
and writes a copy of one's model file to work on.

Examples
--------
>>> import kinelab as kl
>>> kl.gallery.entry("hoeken").title
"Hoeken's linkage"
>>> mf = kl.gallery.load("hoeken")
>>> mf.analyze().position("P").shape
(361, 2)
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.gallery._gallery": ("Entry", "entries", "entry", "load", "names"),
})

__all__ = ["names", "entries", "entry", "load", "Entry"]
