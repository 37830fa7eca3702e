"""A derivation marks where the lecture notes print its equations otherwise (errata entries),
in the section that writes them, in the document's language; and what a mark says holds for
the mechanism derived."""
import re
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.derive import derive
from kinelab.derive._errata import MARKS, marks, notes_mechanism

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"


def _load(name):
    return kl.load(EXAMPLES / f"{name}.toml")


def _sections(text: str) -> dict[str, list[str]]:
    """The errata entries marked under each second-level heading of a Markdown derivation."""
    out, heading = {}, None
    for line in text.splitlines():
        if line.startswith("## "):
            heading = line[3:]
            out[heading] = []
        elif heading is not None:
            out[heading] += re.findall(r"\(errata, ([A-Z]+-\d+)\)", line)
    return out


@pytest.mark.parametrize("name, kind", [
    ("crank_rocker", "fourbar"), ("engine", "slider_crank"),
    ("offset_slider_crank", "slider_crank"), ("inverted_slider_crank", "inverted_slider_crank"),
    ("slotted_link", "inverted_slider_crank"), ("whitworth", None), ("stephenson6", None),
    ("fivebar", None), ("jansen", None)])
def test_the_notes_mechanism_is_recognised_by_its_plan(name, kind):
    assert notes_mechanism(_load(name)) == kind


@pytest.mark.parametrize("build, kind", [
    (lambda: kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5), "fourbar"),
    (lambda: kl.mechanisms.slider_crank(crank=1.0, rod=3.0), "slider_crank"),
    (lambda: kl.mechanisms.inverted_slider_crank(ground=2.0, crank=1.0), "inverted_slider_crank")])
def test_a_catalogue_mechanism_is_recognised(build, kind):
    assert notes_mechanism(build()) == kind


def test_the_four_bar_is_marked_where_flores_and_claro_print_it_otherwise():
    text = derive(_load("crank_rocker")).to_markdown()
    marked = _sections(text)
    assert marked["Position equations"] == ["FC-6"]
    assert marked["The Jacobian and the singular configurations"] == ["M-5"]
    assert marked["Velocity coefficients"] == ["FC-5"]
    assert "eq. 4.115" in text and "minus sign" in text


def test_an_offset_slide_line_is_marked_and_an_in_line_one_is_not():
    inline = _sections(derive(_load("engine")).to_markdown())
    offset = _sections(derive(_load("offset_slider_crank")).to_markdown())
    assert inline["Velocity coefficients"] == ["FC-2", "FC-4"]
    assert offset["Velocity coefficients"] == ["FC-2", "FC-4", "FC-7"]
    assert inline["Position equations"] == ["FC-3", "M-3"]
    assert inline["The Jacobian and the singular configurations"] == ["M-5", "M-7"]
    assert inline["Dynamics: Gibbs-Appell and Kane"] == ["M-8"]      # the engine has masses


def test_a_mechanism_the_notes_do_not_work_gets_only_the_general_marks():
    marked = _sections(derive(_load("stephenson6")).to_markdown())
    assert sum(marked.values(), []) == ["M-5"]


def test_the_marks_speak_the_documents_language():
    pt = derive(_load("crank_rocker"), lang="pt").to_markdown()
    assert pt.count("*As notas imprimem-no de outro modo* (errata, ") == 3
    assert "falta na eq. 4.115" in pt
    tex = derive(_load("slotted_link")).to_latex()
    assert r"\emph{Where the notes print it otherwise} (errata, FC-8)" in tex
    assert r"\sqrt{r_4^2 - a^2 + r_3^2}" in tex          # maths kept, braces single


@pytest.mark.parametrize("page", ["errata.md", "errata.pt.md"])
def test_every_mark_is_an_entry_of_the_errata(page):
    text = (ROOT / "docs" / page).read_text(encoding="utf-8")
    entries = set(re.findall(r"^### ([A-Z]+-\d+)\.", text, re.M))
    marked = {row[1] for rows in MARKS.values() for row in rows}
    assert marked <= entries
    for rows in MARKS.values():
        for section, entry, where, when, words in rows:
            assert set(words) == {"en", "pt"}
            assert where in text.split(f"### {entry}.")[1].split("\n")[0]   # the entry's title


def test_what_the_four_bar_mark_says_holds_for_the_derived_rocker():
    """FC-5: the derived K of the rocker is -(r2/r4) sin(q - t3) / sin(t4' - t3) with the
    notes' t4' = rocker angle + pi, and not eq. 4.115's expression without the minus."""
    m = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    d = derive(m, dynamics=False)
    q = np.radians([20.0, 60.0, 150.0, 290.0])
    v = d.evaluate(q)
    t3, t4 = v.S[:, 0], v.S[:, 1] + np.pi
    right = -(1.0 / 2.5) * np.sin(q - t3) / np.sin(t4 - t3)
    k_rocker = v.K[:, 1, 0]
    np.testing.assert_allclose(k_rocker, right, rtol=1e-12)
    np.testing.assert_allclose(k_rocker, v.K_engine[:, 1, 0], rtol=1e-12)
    assert np.all(np.abs(k_rocker + right) > 1e-3)             # the printed form is another number


def test_what_the_offset_mark_says_holds_for_the_derived_slider():
    """FC-7: with the slide line e below the crank's pivot, the slider's velocity is
    -w r2 sin t - w r2 cos t (r2 sin t + e) / sqrt(r3^2 - (r2 sin t + e)^2)."""
    e, r2, r3, w = 0.5, 1.0, 3.0, 7.0
    m = kl.mechanisms.slider_crank(crank=r2, rod=r3, offset=-e)
    d = derive(m, dynamics=False)
    assert "FC-7" in [entry for entry, _ in marks(d, "coefficients", "en")]
    t = np.radians([10.0, 50.0, 130.0])
    v = d.evaluate(t)
    slide = [i for i, s in enumerate(d.S) if d.equations.unknowns[s][0] == "slide"][0]
    root = np.sqrt(r3 ** 2 - (r2 * np.sin(t) + e) ** 2)
    right = -w * r2 * np.sin(t) - w * r2 * np.cos(t) * (r2 * np.sin(t) + e) / root
    np.testing.assert_allclose(w * v.K[:, slide, 0], right, rtol=1e-12)
