"""The words of the figures: one table per language, one key per phrase, the notes' terms in
Portuguese ("ângulo da manivela", "polígono de velocidades", "centros instantâneos de
rotação", "torque na entrada", "ângulo de transmissão", "coeficiente de velocidade K").

Fields in braces are filled in by the figure: names come from the model or task file and are
never translated.  Numbers go through :func:`number`, which writes a decimal comma in
Portuguese; :func:`decimal_commas` does the same for the tick labels of a figure.  Tables
(CSV) keep the decimal point in every language.
"""
from __future__ import annotations

from kinelab.errors import ModelError, describe

__all__ = ["LANGUAGES", "WORDS", "KINDS_PT", "words", "kind_words", "number", "decimal_commas",
           "checked_language"]

LANGUAGES = ("en", "pt")

WORDS: dict[str, dict[str, str]] = {
    "en": {
        # sweeps: position, velocity and acceleration against the input
        "angle": "angle", "angular velocity": "angular velocity",
        "angular acceleration": "angular acceleration",
        "slide": "slide", "velocity": "velocity", "acceleration": "acceleration",
        "slide velocity": "slide velocity", "slide acceleration": "slide acceleration",
        "named angle": "{name} angle", "named angular velocity": "{name} angular velocity",
        "named angular acceleration": "{name} angular acceleration",
        "named slide": "{name}", "named velocity": "{name} velocity",
        "named acceleration": "{name} acceleration",
        "motion title": "{name}: position, velocity and acceleration",
        # the input on the x axis: the file's name of it (in Portuguese, with what it is)
        "input crank": "{name}", "input angle": "{name}", "input slide": "{name}",
        "sample": "sample",
        "singular": "singular (det J = 0)",
        "K label": "K = dS/dq", "L label": "L = dK/dq",
        "coefficients title": "{name}: velocity and acceleration coefficients",
        "path of": "path of {point}",
        "path title": "{name}: path of {point}",
        "transmission angle": "transmission angle",
        "transmission title": "{name}: transmission angle",
        # animations
        "velocities legend": "velocities: 1 {length} = {scale} {unit}",
        # dynamics
        "input torque": "input torque", "input force": "input force",
        "named torque": "{name}: input torque", "named force": "{name}: input force",
        "efforts title": "{name}: actuator efforts",
        "reaction": "|reaction|", "slide moment": "slide moment",
        "reactions title": "{name}: joint reactions",
        "shaking force": "shaking force on the ground",
        "shaking moment": "shaking moment about O",
        "time": "t",
        # graphical methods
        "lengths": "lengths", "at": "{name}, {where}",
        "velocity polygon": "velocity polygon and images",
        "acceleration polygon": "acceleration polygon and images",
        "velocities": "velocities", "accelerations": "accelerations",
        "normal": "normal", "tangential": "tangential", "coriolis": "Coriolis",
        "sliding": "sliding",
        "off the figure": "{label} (off the figure)",
        "circle diagram": ("circle diagram: primary (solid),\nby Kennedy's theorem "
                           "(dashed, in order)"),
        "centres title": "{name}: instant centres",
        "fixed centrode": "fixed centrode", "moving centrode": "moving centrode",
        "instant centre": "instant centre {label}",
        "centrodes title": "{name}: centrodes of {link}",
        "centrode leaves": "centrodes leave the drawing here (through infinity)",
        "data": "data", "smoothed": "smoothed ({window} samples a fit)",
        "error band": "error band", "estimate": "estimate",
        "derivatives title": "derivatives of a measured curve (noise ≈ {noise} {unit})",
        # synthesis
        "prescribed positions": "{n} prescribed positions",
        "prescribed positions and poles": "{n} prescribed positions and their poles",
        "coupler curve on the way": "coupler curve on the way",
        "four-bar through positions": "four-bar through {n} positions ({kind}, {state})",
        "centre points": "centre points (A0)", "circle points": "circle points (A1)",
        "prescribed P": "prescribed P",
        "burmester title": "centre-point and circle-point curves",
        "precision points": "precision points",
        "generated error": "generated y - f(x)",
        "structural error": "structural error (max {error})",
        "coupler curve branch": "coupler curve (this branch)", "targets": "targets",
        "path generator": "path generator through {n} points (rms error {error} {unit})",
        "limit position": "limit position {k}",
        "crank circle": "crank circle", "output travel": "output travel",
        "crank-rocker": ("crank-rocker: swing {swing} {angle}, time ratio {ratio},\nmin "
                         "transmission {transmission} {angle}"),
        "quick return stroke": "stroke {stroke} {length}", "quick return swing": "swing {swing} {angle}",
        "quick return": "{kind}: {travel}, time ratio {ratio}",
        "centre points of": "centre points of positions {which}",
        "five positions": "five positions, centre-point curves and Burmester points",
        # cams
        "svaj title": "SVAJ diagram", "cam angle": "cam angle", "cam profile": "profile",
        "pitch curve": "pitch curve", "base circle": "base circle", "undercut": "undercut",
        "cam title": "disk cam, {motion} {type} follower (turning counterclockwise)",
        "translating": "translating", "oscillating": "oscillating", "knife-edge": "knife-edge",
        "roller": "roller", "flat-faced": "flat-faced",
        "pressure angle": "pressure angle", "limit": "limit", "largest": "largest {value} {unit}",
        "radius of curvature": "radius of curvature", "roller radius": "roller radius",
        "contact force": "contact force", "contact moment": "contact moment",
        "jump": "jump (no contact)", "least": "least {value} {unit}",
        "follower dynamics": "follower dynamics at {rpm} rpm", "shaft torque": "shaft torque",
        "cam shaft torque": "cam shaft torque", "mean": "mean {value} N m",
    },
    "pt": {
        "angle": "ângulo", "angular velocity": "velocidade angular",
        "angular acceleration": "aceleração angular",
        "slide": "deslocamento", "velocity": "velocidade", "acceleration": "aceleração",
        "slide velocity": "velocidade de deslizamento",
        "slide acceleration": "aceleração de deslizamento",
        "named angle": "ângulo de {name}", "named angular velocity": "velocidade angular de {name}",
        "named angular acceleration": "aceleração angular de {name}",
        "named slide": "deslocamento de {name}", "named velocity": "velocidade de {name}",
        "named acceleration": "aceleração de {name}",
        "motion title": "{name}: posição, velocidade e aceleração",
        "input crank": "ângulo da manivela ({name})", "input angle": "ângulo de entrada ({name})",
        "input slide": "deslocamento de entrada ({name})",
        "sample": "amostra",
        "singular": "singular (det J = 0)",
        "K label": "coeficiente de velocidade K = dS/dq",
        "L label": "coeficiente de aceleração L = dK/dq",
        "coefficients title": "{name}: coeficientes de velocidade e de aceleração",
        "path of": "trajetória de {point}",
        "path title": "{name}: trajetória de {point}",
        "transmission angle": "ângulo de transmissão",
        "transmission title": "{name}: ângulo de transmissão",
        "velocities legend": "velocidades: 1 {length} = {scale} {unit}",
        "input torque": "torque na entrada", "input force": "força na entrada",
        "named torque": "{name}: torque na entrada", "named force": "{name}: força na entrada",
        "efforts title": "{name}: esforços dos atuadores",
        "reaction": "|reação|", "slide moment": "momento na guia",
        "reactions title": "{name}: reações nas juntas",
        "shaking force": "força de vibração na base",
        "shaking moment": "momento de vibração em O",
        "time": "t",
        "lengths": "comprimentos", "at": "{name}, {where}",
        "velocity polygon": "polígono de velocidades e imagens",
        "acceleration polygon": "polígono de acelerações e imagens",
        "velocities": "velocidades", "accelerations": "acelerações",
        "normal": "normal", "tangential": "tangencial", "coriolis": "Coriolis",
        "sliding": "deslizamento",
        "off the figure": "{label} (fora da figura)",
        "circle diagram": ("diagrama circular: primários (cheio),\npelo teorema de Kennedy "
                           "(tracejado, em ordem)"),
        "centres title": "{name}: centros instantâneos de rotação",
        "fixed centrode": "centroide fixa", "moving centrode": "centroide móvel",
        "instant centre": "centro instantâneo {label}",
        "centrodes title": "{name}: centroides de {link}",
        "centrode leaves": "as centroides saem do desenho aqui (pelo infinito)",
        "data": "dados", "smoothed": "suavizada ({window} amostras por ajuste)",
        "error band": "faixa de erro", "estimate": "estimativa",
        "derivatives title": "derivadas de uma curva medida (ruído ≈ {noise} {unit})",
        "prescribed positions": "{n} posições prescritas",
        "prescribed positions and poles": "{n} posições prescritas e seus polos",
        "coupler curve on the way": "curva do acoplador no percurso",
        "four-bar through positions": "quadrilátero por {n} posições ({kind}, {state})",
        "centre points": "pontos centrais (A0)", "circle points": "pontos circulares (A1)",
        "prescribed P": "P prescritos",
        "burmester title": "curvas de pontos centrais e de pontos circulares",
        "precision points": "pontos de precisão",
        "generated error": "y gerado - f(x)",
        "structural error": "erro estrutural (máx. {error})",
        "coupler curve branch": "curva do acoplador (este ramo)", "targets": "alvos",
        "path generator": "gerador de trajetória por {n} pontos (erro rms {error} {unit})",
        "limit position": "posição limite {k}",
        "crank circle": "círculo da manivela", "output travel": "curso da saída",
        "crank-rocker": ("manivela-balancim: oscilação {swing} {angle}, coeficiente de "
                         "velocidade K = {ratio},\nângulo de transmissão mín. {transmission} "
                         "{angle}"),
        "quick return stroke": "curso {stroke} {length}",
        "quick return swing": "oscilação {swing} {angle}",
        "quick return": "{kind}: {travel}, coeficiente de velocidade K = {ratio}",
        "centre points of": "pontos centrais das posições {which}",
        "five positions": "cinco posições, curvas de pontos centrais e pontos de Burmester",
        # cams
        "svaj title": "diagrama SVAJ", "cam angle": "ângulo do came", "cam profile": "perfil",
        "pitch curve": "curva primitiva", "base circle": "círculo de base",
        "undercut": "rebaixamento",
        "cam title": "came de disco, seguidor {type} {motion} (girando no sentido anti-horário)",
        "translating": "de translação", "oscillating": "oscilante", "knife-edge": "de faca",
        "roller": "de rolete", "flat-faced": "de face plana",
        "pressure angle": "ângulo de pressão", "limit": "limite", "largest": "maior {value} {unit}",
        "radius of curvature": "raio de curvatura", "roller radius": "raio do rolete",
        "contact force": "força de contato", "contact moment": "momento de contato",
        "jump": "salto (sem contato)", "least": "menor {value} {unit}",
        "follower dynamics": "dinâmica do seguidor a {rpm} rpm", "shaft torque": "torque no eixo",
        "cam shaft torque": "torque no eixo do came", "mean": "média {value} N m",
    },
}


# the words of a linkage's kind and state (kinelab.mechanisms.grashof, MotionSolution.state,
# QuickReturn.kind), which are English data, in Portuguese
KINDS_PT = {"crank-rocker": "manivela-balancim", "rocker-crank": "balancim-manivela",
            "double-crank": "dupla manivela", "double-rocker": "duplo balancim",
            "triple-rocker": "triplo balancim", "change-point": "ponto de mudança",
            "valid": "válido", "branch defect": "defeito de ramo",
            "circuit defect": "defeito de circuito", "order defect": "defeito de ordem",
            "transmission angle defect": "defeito de ângulo de transmissão",
            "offset slider-crank": "biela-manivela excêntrico",
            "slotted lever": "alavanca com corrediça", "whitworth": "Whitworth",
            "quick-return": "retorno rápido", "motion generation": "geração de movimento",
            "function generation": "geração de funções",
            "path generation": "geração de trajetória"}


def kind_words(text: str, lang: str) -> str:
    """A kind or a state (``"branch defect; circuit defect"``) in ``lang``."""
    if lang != "pt":
        return text
    return "; ".join(KINDS_PT.get(part, part) for part in text.split("; "))


def checked_language(lang: object) -> str:
    """``lang`` when it is one of LANGUAGES, else a one-line error naming ``lang``."""
    if not isinstance(lang, str) or lang not in LANGUAGES:
        raise ModelError(f"lang: expected 'en' or 'pt', got {describe(lang)}")
    return lang


def words(lang: str) -> dict[str, str]:
    """The figure words of ``lang`` ('en' or 'pt')."""
    return WORDS[checked_language(lang)]


def number(value: float, spec: str, lang: str) -> str:
    """``value`` formatted by ``spec`` (``".4g"``), with a decimal comma in Portuguese.

    Examples
    --------
    >>> number(1.0472, ".3g", "pt"), number(1.0472, ".3g", "en")
    ('1,05', '1.05')
    """
    text = format(value, spec)
    return text.replace(".", ",") if lang == "pt" else text


def decimal_commas(figure, lang: str) -> None:
    """In Portuguese, the tick labels (and offsets) of every axis of ``figure`` with a
    decimal comma; nothing in English.  Each axis keeps its own formatter, wrapped."""
    if lang != "pt":
        return
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            formatter = axis.get_major_formatter()
            if not isinstance(formatter, _CommaFormatter):
                axis.set_major_formatter(_comma_formatter(formatter))


def _comma_formatter(inner):
    from matplotlib.ticker import Formatter

    class CommaFormatter(_CommaFormatter, Formatter):
        pass
    return CommaFormatter(inner)


class _CommaFormatter:
    """A tick formatter writing ``inner``'s labels with a decimal comma."""

    def __init__(self, inner):
        self.inner = inner

    def set_axis(self, axis):
        self.axis = axis
        self.inner.set_axis(axis)

    def set_locs(self, locs):
        self.locs = locs
        self.inner.set_locs(locs)

    def __call__(self, x, pos=None):
        return self.inner(x, pos).replace(".", ",")

    def format_ticks(self, values):
        return [label.replace(".", ",") for label in self.inner.format_ticks(values)]

    def get_offset(self):
        return self.inner.get_offset().replace(".", ",")

    def format_data(self, value):
        return self.inner.format_data(value).replace(".", ",")

    def format_data_short(self, value):
        return self.inner.format_data_short(value).replace(".", ",")
