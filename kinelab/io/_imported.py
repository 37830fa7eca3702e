"""What a model built from another tool's drawing says about itself, in that drawing's terms.

An importer (a Pyslvs expression, a linkage2d file) builds a kinelab model on the user's
behalf: its points, links and joints are kinelab's names for what the drawing has, and its
sketch is the drawing.  The model's own messages ("the sketch puts the dyad ... (P1-P2-P3)",
"point 'P4'") would speak of things the user never wrote; these functions reword them:
``sketch`` becomes the drawing, and a Pyslvs model's names its expression's joint numbers.
"""
from __future__ import annotations

import re

from kinelab.errors import ModelError
from kinelab.model import Mechanism

__all__ = ["in_drawing_terms", "in_expression_terms", "planned"]

_DRAWING = [
    (re.compile(r"\bat the sketch\b"), "as drawn"),
    (re.compile(r"\bmove a point of the sketch\b"), "move a joint of the drawing"),
    (re.compile(r"\bthe sketch's\b"), "the drawing's"),
    (re.compile(r"\b[Tt]he sketch\b"), "the drawing"),
    (re.compile(r"\ba singular sketch\b"), "a singular drawing"),
    (re.compile(r"\bsketch\b"), "drawing"),
]
# a Pyslvs model's names (kinelab.io.from_pyslvs): point P{i} is joint i of the expression,
# the pin there jP{i} (jP{i}_{link} when it pins several links), its slider sP{i}, a slider
# block P{i}_block, and a second point of a slotted link P{i}_on_{link}
_EXPRESSION = [
    (re.compile(r"\(((?:P\d+-)+P\d+)"), lambda m: "(joints " + m.group(1).replace("P", "")),
    (re.compile(r"'P(\d+)_block'"), r"the slider block at joint \1"),
    (re.compile(r"'P(\d+)_on_([^']+)'"), r"the point of link '\2' on its slot at joint \1"),
    (re.compile(r"'jP(\d+)(?:_[^']+)?'"), r"the pin at joint \1"),
    (re.compile(r"'sP(\d+)'"), r"the slider at joint \1"),
    (re.compile(r"points 'P(\d+)' and 'P(\d+)'"), r"joints \1 and \2"),
    (re.compile(r"\bpoint 'P(\d+)'"), r"joint \1"),
    (re.compile(r"'P(\d+)'"), r"joint \1"),
    (re.compile(r"\bits first two points\b"), "its first two joints"),
]


def in_drawing_terms(problem: str) -> str:
    """A model's problem said of the drawing it was imported from."""
    for pattern, words in _DRAWING:
        problem = pattern.sub(words, problem)
    return problem


def in_expression_terms(problem: str) -> str:
    """A Pyslvs model's problem said of its expression: joint numbers for kinelab's names."""
    problem = re.sub(r"^mechanism '[^']*': ", "", problem)
    for pattern, words in _EXPRESSION:
        problem = pattern.sub(words, problem)
    return in_drawing_terms(problem)


def planned(m: Mechanism, source: str, pyslvs: bool) -> Mechanism:
    """An imported model, planned as ``kinelab check`` would; what the engine refuses is said
    in the drawing's terms (and a Pyslvs model's in its joint numbers), the engine's own
    error kept as the cause.  ``source`` names the file."""
    from kinelab import kinematics
    from kinelab.structure import mobility

    try:
        kinematics.plan(m)
    except ModelError as exc:
        reword = in_expression_terms if pyslvs else in_drawing_terms
        problems = [reword(p) for p in exc.problems]
        mob = mobility(m)
        if mob.exact != len(m.inputs) == mob.kutzbach_gruebler:
            # the count is right and the drawing is not: a special (singular) position, such
            # as links drawn in line, where the joints allow another number of motions
            problems = [f"the linkage is drawn in a singular position: as drawn, its joints "
                        f"allow {mob.exact} motion(s) where its {len(m.inputs)} input(s) and "
                        "Kutzbach-Gruebler's count expect "
                        f"{mob.kutzbach_gruebler} (links drawn in line, say); draw it in a "
                        "general position, with no links in line"]
        raise ModelError(problems, source=source) from exc
    return m
