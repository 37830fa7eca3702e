"""Catalogue: constructors for the standard mechanisms, with their names documented."""
from kinelab.mechanisms._catalogue import (SKETCHED, fivebar, fourbar, inverted_slider_crank,
                                           sketches, slider_crank, slotted_link, stephenson6,
                                           triad6, watt6, whitworth)
from kinelab.mechanisms._grashof import Grashof, grashof, grashof_kinds

__all__ = ["fourbar", "slider_crank", "inverted_slider_crank", "slotted_link", "whitworth",
           "fivebar", "watt6", "stephenson6", "triad6", "grashof", "grashof_kinds", "Grashof", "sketches", "SKETCHED"]
