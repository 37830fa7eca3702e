"""The words of the summaries the drawing commands print: one table per language, one key
per sentence, the notes' terms in Portuguese (the figures' own words are in
``kinelab.plot._words``).  Numbers go through :func:`number`, with a decimal comma in
Portuguese; the tables the commands write (CSV) keep the decimal point."""
from __future__ import annotations

import math

__all__ = ["SAID", "number", "formatted"]

SAID: dict[str, dict[str, str]] = {
    "en": {
        # dynamics
        "undefined": "{name}: no effort defined (every sample singular or unassembled)",
        "effort": "{name}: peak |effort| {peak} {unit}, rms {rms} {unit}",
        "shaking": "shaking force: peak {force} N; shaking moment: peak {moment} N m",
        "singular": "{count} singular sample(s): forces undefined there (NaN)",
        # polygons
        "velocity polygon": "{name}: velocity polygon [{unit}], from the pole O_V",
        "acceleration polygon": "acceleration polygon [{unit}], from the pole O_A",
        "under": "{point}' is the point of {guide} under {point}",
        # centres
        "centres": "{name}: instant centres [{unit}]; links {numbers}",
        "links": "links", "found": "found", "joint": "joint {joint}",
        "velocities": "velocities", "at infinity": "at infinity", "direction": "direction",
        # differentiate
        "derivatives": ("{data}: {n} samples of {y} against {x}; noise about {noise} {unit}; "
                        "local fits of degree 5 over {window} samples ({how}); median error "
                        "band on the velocity {band} {rate}"),
        "window given": "as --window says",
        "window chosen": "{share} of the {gcv} generalised cross-validation chose",
        # synth
        "solved": "{name}: {what}, {n} linkage(s)",
        "swing": "swing", "stroke": "stroke", "time ratio": "time ratio",
        "min transmission": "min transmission", "pivot angle": "pivot angle",
        "rms error": "rms error", "max structural error": "max structural error",
        "unbounded": "unbounded (the linkage does not close everywhere)",
        "limit": "{limit} {unit} limit",
        "not measured": "min transmission not measured ({limit} not met)",
        "meets": "min transmission {mu} {unit} (meets the {limit})",
        "below": "min transmission {mu} {unit} (below the {limit})",
        "wrote files": "wrote {n} file(s) to {path}",
        # cam
        "cam head": "{name}: disk cam, {motion} {type} follower, base circle {radius} {length}",
        "translating": "translating", "oscillating": "oscillating", "knife-edge": "knife-edge",
        "roller": "roller", "flat-faced": "flat-faced",
        "smallest for pressure": " (the smallest for a pressure angle of {limit} {angle})",
        "smallest for curvature": (" (the smallest with a radius of curvature of at least "
                                   "{limit} {length})"),
        "largest pressure": "  largest pressure angle {phi} {angle} at {at} {angle}",
        "smallest radius": ("  smallest radius of curvature {r} {length} (profile, convex) at "
                            "{at} {angle}"),
        "face width": ("  face width {width} {length} (contact from {lo} to {hi} {length}; add a "
                       "clearance)"),
        "undercut": "  undercut: {answer}", "yes": "yes", "no": "no",
        "continuity": "  continuity: {jump}",
        "jump at": "{quantity} jumps by {jump} at {angle} deg, between segments {left} and {right}",
        "infinite jerk": " (the fundamental law of cam design: an infinite jerk)",
        "continuous": "  continuity: S, V and A continuous at every joint",
        "force": "force", "moment": "moment",
        "at any speed": "at any speed",
        "not every lower": "at this speed, but not at every lower one (contact is lost {where})",
        "at rest": "at rest", "from rpm": "from {rpm} rpm",
        "up to": "up to {rpm} rpm ({speed} {angle}/s)",
        "contact kept": ("  dynamics: contact kept: least contact {force} {least} {unit} at {at} "
                         "{angle}; jump-free {upto}"),
        "jump": ("  dynamics: jump: contact {force} below zero from {at} {angle} at this speed "
                 "({rpm} rpm); preload of at least {need} {unit} needed{margin}"),
        "for a margin": " (for a margin of {margin} {unit})",
        "shaft torque": "  cam shaft torque: peak {peak} N m at {at} {angle}, mean {mean} N m",
    },
    "pt": {
        "undefined": "{name}: esforço indefinido (todas as amostras singulares ou não montadas)",
        "effort": "{name}: |esforço| máximo {peak} {unit}, rms {rms} {unit}",
        "shaking": ("força de vibração: máxima {force} N; momento de vibração: máximo "
                    "{moment} N m"),
        "singular": "{count} amostra(s) singular(es): forças indefinidas nelas (NaN)",
        "velocity polygon": "{name}: polígono de velocidades [{unit}], a partir do polo O_V",
        "acceleration polygon": "polígono de acelerações [{unit}], a partir do polo O_A",
        "under": "{point}' é o ponto de {guide} sob {point}",
        "centres": "{name}: centros instantâneos de rotação [{unit}]; membros {numbers}",
        "links": "membros", "found": "obtido", "joint": "junta {joint}",
        "velocities": "velocidades", "at infinity": "no infinito", "direction": "direção",
        "derivatives": ("{data}: {n} amostras de {y} em função de {x}; ruído cerca de {noise} "
                        "{unit}; ajustes locais de grau 5 sobre {window} amostras ({how}); "
                        "faixa de erro mediana da velocidade {band} {rate}"),
        "window given": "como diz --window",
        "window chosen": ("{share} das {gcv} que a validação cruzada generalizada "
                          "escolheu"),
        "solved": "{name}: {what}, {n} mecanismo(s)",
        "swing": "oscilação", "stroke": "curso", "time ratio": "coeficiente de velocidade K",
        "min transmission": "ângulo de transmissão mín.", "pivot angle": "ângulo do pivô",
        "rms error": "erro rms", "max structural error": "erro estrutural máx.",
        "unbounded": "ilimitado (o mecanismo não fecha em toda parte)",
        "limit": "limite de {limit} {unit}",
        "not measured": "ângulo de transmissão mín. não medido ({limit} não atendido)",
        "meets": "ângulo de transmissão mín. {mu} {unit} (atende ao {limit})",
        "below": "ângulo de transmissão mín. {mu} {unit} (abaixo do {limit})",
        "wrote files": "escreveu {n} arquivo(s) em {path}",
        "cam head": ("{name}: came de disco, seguidor {type} {motion}, círculo de base {radius} "
                     "{length}"),
        "translating": "de translação", "oscillating": "oscilante", "knife-edge": "de faca",
        "roller": "de rolete", "flat-faced": "de face plana",
        "smallest for pressure": " (o menor para um ângulo de pressão de {limit} {angle})",
        "smallest for curvature": (" (o menor com raio de curvatura de pelo menos {limit} "
                                   "{length})"),
        "largest pressure": "  maior ângulo de pressão {phi} {angle} em {at} {angle}",
        "smallest radius": ("  menor raio de curvatura {r} {length} (perfil, convexo) em {at} "
                            "{angle}"),
        "face width": ("  largura da face {width} {length} (contato de {lo} a {hi} {length}; "
                       "acrescente uma folga)"),
        "undercut": "  rebaixamento: {answer}", "yes": "sim", "no": "não",
        "continuity": "  continuidade: {jump}",
        "jump at": ("{quantity} salta {jump} em {angle} graus, entre os segmentos {left} e "
                    "{right}"),
        "infinite jerk": " (a lei fundamental do projeto de cames: um jerk infinito)",
        "continuous": "  continuidade: S, V e A contínuos em todas as junções",
        "force": "força", "moment": "momento",
        "at any speed": "a qualquer velocidade",
        "not every lower": ("a esta velocidade, mas não a todas as menores (o contato se perde "
                            "{where})"),
        "at rest": "em repouso", "from rpm": "a partir de {rpm} rpm",
        "up to": "até {rpm} rpm ({speed} {angle}/s)",
        "contact kept": ("  dinâmica: contato mantido: menor {force} de contato {least} {unit} "
                         "em {at} {angle}; sem salto {upto}"),
        "jump": ("  dinâmica: salto: {force} de contato abaixo de zero a partir de {at} {angle} "
                 "a esta velocidade ({rpm} rpm); pré-carga de pelo menos {need} {unit} "
                 "necessária{margin}"),
        "for a margin": " (para uma margem de {margin} {unit})",
        "shaft torque": ("  torque no eixo do came: máximo {peak} N m em {at} {angle}, médio "
                         "{mean} N m"),
    },
}


def formatted(v: float, spec: str, lang: str = "en") -> str:
    """``v`` formatted by ``spec`` (``".4f"``), with a decimal comma in Portuguese."""
    text = format(v, spec)
    return text.replace(".", ",") if lang == "pt" else text


def number(v: float, digits: int = 6, lang: str = "en") -> str:
    """A printed number to ``digits`` significant figures ('-' when not finite, '0' for
    zero), with a decimal comma in Portuguese.

    Examples
    --------
    >>> number(1.25, lang="pt"), number(1.25)
    ('1,25', '1.25')
    """
    text = "-" if not math.isfinite(v) else f"{v:.{digits}g}" if v != 0 else "0"
    return text.replace(".", ",") if lang == "pt" else text
