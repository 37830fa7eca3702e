"""Where the notes print a mechanism's equations differently from what they are.

The errata of the lecture notes (``docs/errata.md``, in the documentation site) lists every
slip found in them; a derivation marks the ones that concern the equations it writes, in
the section where it writes them, so that a student comparing it with the notes is told
which of the two to trust.  A mark belongs to the notes' worked mechanism it is about (the
four-bar, the slider-crank, the inverted slider-crank), recognised by its plan: four links,
one input, one dyad (RRR, RRP or RPR); or to every derivation (the names of the Jacobians,
the inertia term of the dynamics).
"""
from __future__ import annotations

from kinelab.model import Mechanism

__all__ = ["MARKS", "notes_mechanism", "marks"]

_FC = "Flores & Claro"
_M = "*Mecanismos*"

MARKS: dict[str, tuple[tuple[str, str, str, str | None, dict[str, str]], ...]] = {
    # mechanism -> ((section, entry, the notes' section, when, {lang: sentence}), ...)
    "any": (
        ("jacobian", "M-5", "§4.8", None, {
            "en": (f"{_M}, after eq. 51, calls $J_D$ and $J_I$ the Jacobians of the independent "
                   "and dependent coordinates, the other way round: $J_D = \\partial\\Phi/"
                   "\\partial q_D$, this $J$, is that of the dependent (secondary) ones, and "
                   "$J_I = \\partial\\Phi/\\partial q_I$, this $Q$, that of the independent "
                   "ones, as its §5.2.1 writes them."),
            "pt": (f"{_M}, após a eq. 51, chama $J_D$ e $J_I$ de jacobianos das coordenadas "
                   "independentes e dependentes, invertidos: $J_D = \\partial\\Phi/\\partial "
                   "q_D$, este $J$, é o das coordenadas dependentes (secundárias), e $J_I = "
                   "\\partial\\Phi/\\partial q_I$, este $Q$, o das independentes, como o seu "
                   "§5.2.1 os escreve.")}),
        ("dynamics", "M-8", "§5.3", None, {
            "en": (f"{_M}, eq. 65 (and the $f$ of §5.7), writes the first body's inertia "
                   "term as $I_k \\dot\\omega_1$; it is $I_1 \\dot\\omega_1$, each body with its "
                   "own moment of inertia, as below."),
            "pt": (f"{_M}, eq. 65 (e o $f$ do §5.7), escreve o termo de inércia do primeiro "
                   "corpo como $I_k \\dot\\omega_1$; é $I_1 \\dot\\omega_1$, cada corpo com o seu "
                   "momento de inércia, como abaixo.")}),
    ),
    "fourbar": (
        ("position", "FC-6", "§4.7.1", None, {
            "en": (f"{_FC} solve these equations with $\\theta_d = \\arcsin(r_2 \\sin\\theta_2 / "
                   "r_d)$ (eq. 4.118): the diagonal from A to $O_4$ is at $\\theta_d = "
                   "\\operatorname{{atan2}}(-r_2 \\sin\\theta_2, r_1 - r_2 \\cos\\theta_2)$, and with the "
                   "printed $\\theta_d$ eqs. 4.116–4.117 give the linkage's mirror image."),
            "pt": (f"{_FC} resolvem estas equações com $\\theta_d = \\arcsin(r_2 \\sin\\theta_2 / "
                   "r_d)$ (eq. 4.118): a diagonal de A a $O_4$ está a $\\theta_d = "
                   "\\operatorname{{atan2}}(-r_2 \\sin\\theta_2, r_1 - r_2 \\cos\\theta_2)$, e com o "
                   "$\\theta_d$ impresso as eqs. 4.116–4.117 dão a imagem espelhada do "
                   "mecanismo.")}),
        ("coefficients", "FC-5", "§4.7.1", None, {
            "en": (f"The rocker's $K$ above may look like {_FC}'s eq. 4.115, $\\omega_4 = "
                   "(r_2 \\omega_2 / r_4) \\sin(\\theta_2 - \\theta_3) / \\sin(\\theta_4 - "
                   "\\theta_3)$, but it is not: their $\\theta_4$ is the angle of $R_4$ from B to "
                   "$O_4$ (this rocker's angle $+ \\pi$), and with it the velocity loop gives "
                   "the same expression with a minus sign, which eq. 4.115 lacks."),
            "pt": (f"O $K$ do balancim acima pode parecer a eq. 4.115 de {_FC}, $\\omega_4 = "
                   "(r_2 \\omega_2 / r_4) \\sin(\\theta_2 - \\theta_3) / \\sin(\\theta_4 - "
                   "\\theta_3)$, mas não é: o $\\theta_4$ deles é o ângulo de $R_4$ de B a $O_4$ "
                   "(o ângulo deste balancim $+ \\pi$), e com ele a malha de velocidades dá a "
                   "mesma expressão com um sinal de menos, que falta na eq. 4.115.")}),
    ),
    "slider_crank": (
        ("position", "FC-3", "§4.5.3", None, {
            "en": (f"{_FC} print $\\theta_3 = \\arcsin(-r_2 \\sin\\theta_2 / r_3)$ (eq. 4.76); "
                   "the $y$ equation (4.64) gives $\\theta_3 = \\arcsin(r_2 \\sin\\theta_2 / "
                   "r_3)$, with their clockwise $\\theta_3$."),
            "pt": (f"{_FC} imprimem $\\theta_3 = \\arcsin(-r_2 \\sin\\theta_2 / r_3)$ (eq. "
                   "4.76); a equação em $y$ (4.64) dá $\\theta_3 = \\arcsin(r_2 \\sin\\theta_2 / "
                   "r_3)$, com o $\\theta_3$ deles medido no sentido horário.")}),
        ("position", "M-3", "§4.7", None, {
            "en": (f"{_M} solves them by Newton-Raphson (§4.7, Ex. 4.4); its eq. 45 divides by "
                   "$\\cos\\theta_3^{{(k+1)}}$ where $\\cos\\theta_3^{{(k)}}$ is meant (the Jacobian "
                   "at the current iterate), and its iteration table is off after row 0 "
                   "(errata M-4)."),
            "pt": (f"{_M} as resolve por Newton-Raphson (§4.7, Ex. 4.4); a sua eq. 45 divide "
                   "por $\\cos\\theta_3^{{(k+1)}}$ onde é $\\cos\\theta_3^{{(k)}}$ (o jacobiano na "
                   "iteração corrente), e a tabela de iterações erra a partir da linha 1 "
                   "(errata M-4).")}),
        ("jacobian", "M-7", "§4.8", None, {
            "en": (f"{_M}, Ex. 4.6, prints $J_I = -L_2 (s_2 + c_2 s_3 / c_3)$; it is $J_I = "
                   "-L_2 (-s_2 + c_2 s_3 / c_3)$, which vanishes where O, A and B are in line "
                   "($\\sin(\\theta_2 - \\theta_3) = 0$), the singular positions the text names."),
            "pt": (f"{_M}, Ex. 4.6, imprime $J_I = -L_2 (s_2 + c_2 s_3 / c_3)$; é $J_I = "
                   "-L_2 (-s_2 + c_2 s_3 / c_3)$, que se anula onde O, A e B estão alinhados "
                   "($\\sin(\\theta_2 - \\theta_3) = 0$), as posições singulares que o texto "
                   "cita.")}),
        ("coefficients", "FC-2", "§4.5.3", None, {
            "en": (f"{_FC}'s eq. 4.74, $\\omega_3 = -r_2 \\omega_2 \\cos\\theta_2 / (r_3 \\cos"
                   "\\theta_3)$, has a sign too many: Cramer's rule on their system (4.69) gives "
                   "$\\omega_3 = r_2 \\omega_2 \\cos\\theta_2 / (r_3 \\cos\\theta_3)$."),
            "pt": (f"A eq. 4.74 de {_FC}, $\\omega_3 = -r_2 \\omega_2 \\cos\\theta_2 / (r_3 "
                   "\\cos\\theta_3)$, tem um sinal a mais: a regra de Cramer no sistema (4.69) dá "
                   "$\\omega_3 = r_2 \\omega_2 \\cos\\theta_2 / (r_3 \\cos\\theta_3)$.")}),
        ("coefficients", "FC-4", "§4.5.4–4.5.5", None, {
            "en": (f"{_FC}'s eqs. 4.85 and 4.92 give the slider's speed $v_C$ with a minus sign "
                   "that their eqs. 4.84 and 4.89 do not have; $v_C$ is the slider's speed "
                   "towards the crank's pivot A (the sense of their figures), $-\\dot s$ where "
                   "$s$ grows away from it."),
            "pt": (f"As eqs. 4.85 e 4.92 de {_FC} dão a velocidade $v_C$ da corrediça com um "
                   "sinal de menos que as suas eqs. 4.84 e 4.89 não têm; $v_C$ é a velocidade "
                   "em direção ao pivô A da manivela (o sentido das suas figuras), $-\\dot s$ "
                   "onde $s$ cresce para longe dele.")}),
        ("coefficients", "FC-7", "§4.7.3", "offset", {
            "en": (f"For a slide line offset by $e$, {_FC}'s eq. 4.134 lacks the offset in "
                   "the numerator: the slider's velocity has $\\omega_2 r_2 \\cos\\theta_2 "
                   "(r_2 \\sin\\theta_2 + e)$ over $\\sqrt{{r_3^2 - (r_2 \\sin\\theta_2 + e)^2}}$, "
                   "not $\\omega_2 r_2^2 \\cos\\theta_2 \\sin\\theta_2$."),
            "pt": (f"Para uma linha de deslizamento desviada de $e$, a eq. 4.134 de {_FC} "
                   "perde o desvio no numerador: a velocidade da corrediça tem $\\omega_2 r_2 "
                   "\\cos\\theta_2 (r_2 \\sin\\theta_2 + e)$ sobre $\\sqrt{{r_3^2 - (r_2 \\sin"
                   "\\theta_2 + e)^2}}$, não $\\omega_2 r_2^2 \\cos\\theta_2 \\sin\\theta_2$.")}),
    ),
    "inverted_slider_crank": (
        ("position", "FC-8", "§4.7.4", None, {
            "en": (f"{_FC} solve these equations with $\\theta_3 = \\arctan((r_4 + \\beta"
                   "\\sqrt{{r_4^2 - a^2 + r_3^2}})/(a + r_3))$, $\\beta = \\pm 1$ (eq. 4.139): the "
                   "fraction is $\\tan(\\theta_3/2)$, so $\\theta_3$ is twice the arctangent, and "
                   "only one $\\beta$ closes the loop's $y$ projection."),
            "pt": (f"{_FC} resolvem estas equações com $\\theta_3 = \\arctan((r_4 + \\beta"
                   "\\sqrt{{r_4^2 - a^2 + r_3^2}})/(a + r_3))$, $\\beta = \\pm 1$ (eq. 4.139): a "
                   "fração é $\\tan(\\theta_3/2)$, logo $\\theta_3$ é o dobro do arco tangente, "
                   "e só um $\\beta$ fecha a projeção em $y$ da malha.")}),
    ),
}
"""The marks, by the notes' mechanism they concern (``"any"``: every derivation): the
section of the derivation they go in, the errata's entry, the notes' section it is in, when
it applies (always, or ``"offset"``: where a slide line is offset from its origin), and a
sentence in each language (LaTeX maths between dollars, braces doubled as in a format
string)."""

_DYADS = {"RRR": "fourbar", "RRP": "slider_crank", "RPR": "inverted_slider_crank"}
_KINDS = {"fourbar": "fourbar", "slider_crank": "slider_crank",
          "inverted_slider_crank": "inverted_slider_crank", "slotted_link": "inverted_slider_crank"}


def notes_mechanism(model: Mechanism) -> str | None:
    """Which of the notes' worked mechanisms ``model`` is: ``"fourbar"``, ``"slider_crank"``
    or ``"inverted_slider_crank"`` (Erthal's slotted link included), or None.

    A catalogue mechanism says so (``parameters["kind"]``); any other is recognised by its
    plan: four links, one input, one dyad of those kinds.
    """
    params = model.parameters if isinstance(model.parameters, dict) else {}
    kind = params.get("kind")
    if isinstance(kind, str) and kind in _KINDS:
        return _KINDS[kind]
    if len(model.links) != 4 or len(model.inputs) != 1:
        return None
    from kinelab.errors import KinelabError
    from kinelab.kinematics import plan
    try:
        steps = plan(model).steps
    except KinelabError:
        return None
    dyads = [s.kind for s in steps if s.kind not in ("driven", "placed", "locked")]
    return _DYADS.get(dyads[0]) if len(dyads) == 1 else None


def marks(d, section: str, lang: str) -> list[tuple[str, str]]:
    """The marks of ``section`` in derivation ``d`` (a :class:`Derivation`): (errata entry,
    sentence)."""
    kind = notes_mechanism(d.model)
    offset = any(meaning[0] == "offset" for meaning in d.equations.meaning.values())
    rows = MARKS["any"] + (MARKS[kind] if kind else ())
    return [(entry, words[lang]) for place, entry, _, when, words in rows
            if place == section and (when is None or (when == "offset" and offset))]
