"""The notes' letters for the catalogue's mechanisms.

A model file or a model built in Python is written with its own names (``theta_coupler``,
``L_crank``, ``s_slot``); the catalogue's mechanisms, whose constructors follow the notes,
take the letters the notes use for them.  Keys name what a symbol stands for (see
:func:`kinelab.derive.loop_equations`).
"""
from __future__ import annotations

from kinelab.model import Mechanism

__all__ = ["notation_of", "NOTES_LETTERS"]

NOTES_LETTERS: dict[str, dict[tuple, str]] = {
    # Erthal, Mecanismos com 1 GL: B cos A - R cos q - C = 0, B sin A - R sin q = 0
    "slotted_link": {("input", 0): "q", ("angle", "lever"): "A", ("slide", "slot"): "B",
                     ("length", "crank"): "R", ("x", "O2"): "C"},
    # links numbered as in the notes: 1 ground, 2 crank, 3 coupler or rod, 4 rocker
    "fourbar": {("input", 0): "q", ("length", "crank"): "L_2", ("length", "coupler"): "L_3",
                ("length", "rocker"): "L_4", ("x", "O4"): "L_1", ("angle", "coupler"): "theta_3",
                ("angle", "rocker"): "theta_4"},
    "slider_crank": {("input", 0): "q", ("length", "crank"): "L_2", ("length", "rod"): "L_3",
                     ("angle", "rod"): "theta_3", ("slide", "slide"): "s", ("offset", "slide"): "e"},
    "inverted_slider_crank": {("input", 0): "q", ("length", "crank"): "L_2", ("x", "O4"): "L_1",
                              ("angle", "rocker"): "theta_4", ("slide", "slide"): "s",
                              ("offset", "slide"): "e"},
    "fivebar": {("input", 0): "q_1", ("input", 1): "q_2", ("length", "crank1"): "L_2",
                ("length", "coupler1"): "L_3", ("length", "coupler2"): "L_4",
                ("length", "crank2"): "L_5", ("x", "O4"): "L_1", ("angle", "coupler1"): "theta_3",
                ("angle", "coupler2"): "theta_4"},
}


def notation_of(model: Mechanism) -> dict[tuple, str]:
    """The symbol names of a catalogue mechanism (empty for any other model)."""
    kind = model.parameters.get("kind") if isinstance(model.parameters, dict) else None
    return dict(NOTES_LETTERS.get(kind, {})) if isinstance(kind, str) else {}
