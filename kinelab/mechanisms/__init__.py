"""Catalogue: constructors for the standard mechanisms, with their names documented."""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.mechanisms._catalogue": ("SKETCHED", "fivebar", "fourbar", "inverted_slider_crank",
                                      "sketches", "slider_crank", "slotted_link", "stephenson6",
                                      "triad6", "watt6", "whitworth"),
    "kinelab.mechanisms._grashof": ("Grashof", "grashof", "grashof_kinds"),
    "kinelab.mechanisms._spherical": ("spherical_fourbar",),
})

__all__ = ["fourbar", "slider_crank", "inverted_slider_crank", "slotted_link", "whitworth",
           "fivebar", "watt6", "stephenson6", "triad6", "grashof", "grashof_kinds", "Grashof", "sketches", "SKETCHED",
           "spherical_fourbar"]
