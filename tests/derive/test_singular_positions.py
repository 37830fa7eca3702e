"""The derivation's section on toggles (det J = 0 reached or not over the input range) and
dead centres (K = 0), in both languages, against closed forms (derived in
tests/kinematics/test_dead_centres.py)."""
import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pytest

import kinelab as kl
from kinelab.derive import derive
from kinelab.derive._words import WORDS

ROOT = Path(__file__).resolve().parents[2]


def section(text: str, lang: str) -> str:
    head = "### " + WORDS[lang]["reach"]
    assert text.count(head) == 1
    return text.split(head)[1].split("\n## ")[0]


def q_values(text: str) -> list[float]:
    return [float(v) for v in re.findall(r"\$q = (-?[\d.e+-]+)\$", text)]


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_engine_rod_never_perpendicular_and_its_slider_dead_centres(lang):
    """Crank 50 mm < rod 180 mm: det J = L_rod cos(theta_rod) = 0 is not reached; the slide
    turns back at q = 0 (0.23 m) and pi (0.13 m), the rod at pi/2 and 3 pi/2."""
    text = derive(kl.load(ROOT / "examples" / "engine.toml"), lang).to_markdown(lang=lang)
    part = section(text, lang)
    words = WORDS[lang]
    not_reached = words["toggle_not_reached"].split("{factor}")[1]
    assert re.search(r"\\cos \{\\theta_\{\\text\{rod\}\}\} = 0\$" + re.escape(not_reached), part)
    slide = next(s for s in part.splitlines() if s.startswith("- $s_{\\text{slide}}$"))
    assert q_values(slide) == pytest.approx([0.0, math.pi], abs=1e-9)
    assert re.findall(r"s_\{\\text\{slide\}\} = ([\d.]+)\$ m", slide) == ["0.23", "0.13"]
    rod = next(s for s in part.splitlines() if s.startswith("- $\\theta_{\\text{rod}}$"))
    assert q_values(rod) == pytest.approx([math.pi / 2, 3 * math.pi / 2], abs=1e-9)


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_triple_rocker_toggle_reached_at_its_limit_positions(lang):
    fb = kl.mechanisms.fourbar(ground=1.0, crank=2.0, coupler=1.0, rocker=1.5)
    part = section(derive(fb, lang).to_markdown(lang=lang), lang)
    item = next(s for s in part.splitlines() if s.startswith("- $\\sin"))
    limit = math.acos(-0.3125)            # |A O4| = coupler + rocker = 2.5
    assert q_values(item) == pytest.approx([-limit, limit], abs=1e-9)
    assert item.count(WORDS[lang]["limit position"]) == 2


def test_change_point_linkage_toggle_is_a_change_point():
    """a + b = c + d (ground 3, crank 1, coupler 2, rocker 2): all four links in line at
    q = pi, where the crank goes on."""
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=2.0, rocker=2.0)
    part = section(derive(fb).to_markdown(), "en")
    item = next(s for s in part.splitlines() if s.startswith("- $\\sin"))
    assert WORDS["en"]["change point"] in item
    assert [v % (2 * math.pi) for v in q_values(item)] == pytest.approx([math.pi], abs=1e-9)


def test_portuguese_calls_the_toggle_posicao_de_travamento_and_the_dead_centre_ponto_morto():
    fb = kl.mechanisms.fourbar(ground=3.0, crank=1.0, coupler=3.0, rocker=2.5)
    text = derive(fb, "pt").to_markdown(lang="pt")
    in_line = next(s for s in text.splitlines() if "ficam alinhados" in s)
    assert "posição de travamento" in in_line and "ponto morto" not in in_line
    part = section(text, "pt")
    assert "*Posições de travamento*" in part and "*Pontos mortos*" in part
    assert "não é atingida nesta faixa" in part          # a crank-rocker never locks
    assert part.count("inverte o sentido em") == 2       # the coupler and the rocker
    english = derive(fb, "en").to_markdown(lang="en")
    assert "(a toggle: a dead centre of the chain)" in english


def pairs_of(text: str) -> list[tuple[float, float]]:
    """The (q1, q2) of each point a toggle line of several inputs shows."""
    return [(float(a), float(b)) for a, b in
            re.findall(r"\$q_\{1\} = (-?[\d.e+-]+)\$ \([^)]*\), \$q_\{2\} = (-?[\d.e+-]+)\$", text)]


@pytest.mark.parametrize("lang", ["en", "pt"])
def test_two_inputs_toggles_over_the_box_of_their_ranges(lang):
    """The symmetric five-bar (ground, cranks 100 mm, couplers 120 mm): its couplers fall
    in line (sin(theta_coupler1 - theta_coupler2) = 0) where the loops stop closing,
    |AB| = 240 mm; the points shown are on that curve."""
    five = kl.load(ROOT / "tests" / "cli" / "fivebar_reach.toml")
    part = section(derive(five, lang).to_markdown(lang=lang), lang)
    words = WORDS[lang]
    assert words["reach_intro_many"].split("{span}")[0] in part
    assert "$61 \\times 61$" in part
    item = next(s for s in part.splitlines() if s.startswith("- $\\sin"))
    count = re.search(r"(\d+)", item.split("= 0$")[1])
    assert int(count[1]) > 100
    assert words["many limit position"] in item
    shown = pairs_of(item)
    assert len(shown) == 3
    for q1, q2 in shown:
        d = math.hypot(0.1 + 0.1 * math.cos(q2) - 0.1 * math.cos(q1),
                       0.1 * math.sin(q2) - 0.1 * math.sin(q1))
        assert d == pytest.approx(0.24, abs=1e-9)
    assert words["dead_many"] in part


def test_two_inputs_isolated_toggles_and_a_box_without_any():
    """The example five-bar: det J = 0 only at isolated samples of its grid (|AB| = 300 mm at
    (180, 0) deg, A = B at (300, 240) and (420, 120) deg, ...); near its sketch, nowhere."""
    five = kl.load(ROOT / "examples" / "fivebar.toml")
    part = section(derive(five).to_markdown(), "en")
    item = next(s for s in part.splitlines() if s.startswith("- $\\sin"))
    assert "is reached at 4 of the points found" in item
    assert item.count(WORDS["en"]["many touch"]) == 3
    assert pairs_of(item)[0] == pytest.approx((math.pi, 0.0), abs=1e-9)
    near = kl.mechanisms.fivebar(ground=1.0, crank1=1.0, coupler1=1.2, coupler2=1.2,
                                 crank2=1.0, q0=(np.pi / 2, np.pi / 2))
    ranged = dataclasses.replace(near, inputs=tuple(
        dataclasses.replace(i, range=(1.2, 2.0)) for i in near.inputs))
    for lang in ("en", "pt"):
        part = section(derive(ranged, lang).to_markdown(lang=lang), lang)
        not_reached = WORDS[lang]["toggle_not_reached_box"].split("{factor}")[1]
        assert re.search(r"^- \$\\sin.* = 0\$" + re.escape(not_reached) + "$", part, re.M)
