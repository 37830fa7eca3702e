"""The gallery's entries: their titles and histories (``index.toml``) and their model files
(``models/<name>.toml``)."""
from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import TYPE_CHECKING

from kinelab.errors import ModelError, shown, suggest

if TYPE_CHECKING:
    from kinelab.io import ModelFile

__all__ = ["Entry", "entries", "entry", "load", "names"]

HERE = Path(__file__).parent
INDEX = HERE / "index.toml"
MODELS = HERE / "models"


@dataclass(frozen=True)
class Entry:
    """One mechanism of the gallery.

    Attributes
    ----------
    name : str
        Its name in the gallery, also its model file's stem and the ``name`` in that file.
    title : str
        What the mechanism is called, e.g. ``"Watt's linkage"``.
    history : str
        One or two sentences: who devised it, when, and what for.
    path : pathlib.Path
        Its model file, shipped in the package; read it with :func:`load` or
        :meth:`kinelab.io.ModelFile.read`, copy it to change it.
    """

    name: str
    title: str
    history: str
    path: Path


@cache
def _index() -> dict[str, Entry]:
    with INDEX.open("rb") as f:
        table = tomllib.load(f)
    return {name: Entry(name, item["title"], item["history"], MODELS / f"{name}.toml")
            for name, item in table.items()}


def names() -> tuple[str, ...]:
    """The names of the gallery's entries, in the gallery's order (by kind of mechanism:
    straight-line linkages first).

    Examples
    --------
    >>> "watt_linkage" in kl.gallery.names()
    True
    """
    return tuple(_index())


def entries() -> tuple[Entry, ...]:
    """Every entry of the gallery, in the order of :func:`names`."""
    return tuple(_index().values())


def entry(name: str) -> Entry:
    """The entry called ``name``: its title, history and model file.

    Raises
    ------
    ModelError
        When the gallery has no entry of that name; the message suggests a close name.

    Examples
    --------
    >>> kl.gallery.entry("peaucellier_lipkin").path.name
    'peaucellier_lipkin.toml'
    >>> kl.gallery.entry("hokeen")
    Traceback (most recent call last):
    ...
    kinelab.errors.ModelError: gallery: no entry 'hokeen' (did you mean 'hoeken'?); kinelab.gallery.names() lists the entries
    """
    found = _index().get(name) if isinstance(name, str) else None
    if found is None:
        raise ModelError(f"gallery: {unknown(name)}; kinelab.gallery.names() lists the entries")
    return found


def unknown(name: object) -> str:
    """``no entry 'x' (did you mean 'y'?)``: what an unknown name is told."""
    hint = suggest(name, _index()) if isinstance(name, str) else ""
    return f"no entry {shown(name)}{hint}"


def load(name: str) -> ModelFile:
    """The model file of the entry ``name``, read as :meth:`kinelab.io.ModelFile.read` reads
    it (``load(name).mechanism`` is the mechanism, ``load(name).analyze()`` sweeps its
    inputs over the ranges the file gives).

    Examples
    --------
    >>> mf = kl.gallery.load("crank_rocker")
    >>> [link.name for link in mf.mechanism.links]
    ['ground', 'crank', 'coupler', 'rocker']
    """
    from kinelab.io import ModelFile      # lazy: listing the gallery needs no model reading
    return ModelFile.read(entry(name).path)
