"""The symbols a derivation writes: the notes' letters, or the model's own names.

A model is written with its own names (``theta_coupler``, ``L_crank``, ``s_slot``); the
catalogue's mechanisms, whose constructors follow the notes, take the letters the notes use
for them, and a model file's ``[notation]`` table (kept in ``parameters["notation"]``) names
the symbols to write instead of its own (``theta_lever = "A"``).  Keys are either what a
symbol stands for, ``("angle", "lever")`` (see :func:`kinelab.derive.loop_equations`), or the
name kinelab would give it, ``"theta_lever"``; the second wins.
"""
from __future__ import annotations

from collections.abc import Mapping

from kinelab.errors import ModelError, check_choice, describe
from kinelab.model import Mechanism

__all__ = ["notation_of", "NOTES_LETTERS", "NOTATIONS"]

NOTATIONS = ("notes", "names")

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


def notation_of(model: Mechanism, notation="notes") -> dict:
    """The symbol names a derivation of ``model`` writes, by key.

    ``notation`` is ``"notes"`` (the notes' letters of a catalogue mechanism, then the
    model's ``[notation]`` table over them), ``"names"`` (the model's own names, nothing
    renamed), or a mapping of keys to symbols to write over the notes' ones.
    """
    if isinstance(notation, str):
        check_choice("notation", notation, NOTATIONS)
        if notation == "names":
            return {}
    elif not isinstance(notation, Mapping):
        raise ModelError(f"notation: expected 'notes', 'names' or a mapping of symbols to the "
                         f"symbols to write, such as {{'theta_lever': 'A'}}, got "
                         f"{describe(notation)}")
    params = model.parameters if isinstance(model.parameters, Mapping) else {}
    kind = params.get("kind")
    out: dict = dict(NOTES_LETTERS.get(kind, {})) if isinstance(kind, str) else {}
    table = params.get("notation")
    if isinstance(table, Mapping):
        out.update(table)
    if isinstance(notation, Mapping):
        out.update(notation)
    return out
