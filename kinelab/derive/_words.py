"""The words of a derivation's document: one table per language, one key per sentence.

Text is Markdown-flavoured (``*emphasis*``, inline maths in ``$...$``); the LaTeX writer
turns the emphasis into ``\\emph``.  Fields in braces are filled in by the document: names
come already quoted for the output format, maths already in LaTeX.
"""
from __future__ import annotations

__all__ = ["WORDS"]

_ERTHAL = "Erthal, *Mecanismos com 1 GL: análise geral de velocidade e aceleração*"
_NOTES = "the course notes *Mecanismos*"
_DAS_NOTAS = "das notas de aula *Mecanismos*"

WORDS: dict[str, dict[str, str]] = {
    "en": {
        "title": "{name}: the velocity and acceleration equations",
        "intro": (f"The general method of {_ERTHAL}, carried out for this model by kinelab: "
                  "position equations $\\Phi(q, S) = 0$, their time derivative, the Jacobian "
                  "$J$ and the vector $Q$, the singular configurations ($\\det J = 0$), the "
                  "velocity coefficients $K$ and the acceleration coefficients $L$."),
        "symbols": "Symbols",
        "symbols_intro": ("Lengths in m, angles in rad, CCW from the $x$ axis.  The values are "
                          "the model's."),
        "col_symbol": "symbol", "col_meaning": "meaning", "col_value": "value",
        "inputs_head": "Primary coordinates (inputs) $q$",
        "unknowns_head": "Secondary coordinates (unknowns) $S$",
        "parameters_head": "Constants",
        "input_angle": "angle of {b} from {a} (input {name})",
        "input_angle_ground": "angle of {b} (input {name})",
        "input_slide": "slide of {joint} (input {name})",
        "unknown_angle": "angle of {link} (from {p} towards {r})",
        "unknown_angle_one": "angle of {link}",
        "unknown_slide": "slide of {joint}: distance of {point} from {origin} along the axis",
        "length": "length of {link} ({a} to {b})",
        "distance": "distance from {a} to {b} on {link}",
        "direction": "angle of {a}{b} from the direction of {root}",
        "direction_ground": "angle of {a}{b} from the $x$ axis",
        "link_offset": "angle of {link} from the direction of {root}",
        "link_offset_ground": "angle of {link} from the $x$ axis",
        "axis": "angle of the axis of {joint} from the direction of {root}",
        "axis_ground": "angle of the axis of {joint} from the $x$ axis",
        "offset": "distance of the line of {joint} from {origin}, to the left of its axis",
        "x": "$x$ of the fixed point {point}",
        "y": "$y$ of the fixed point {point}",
        "position": "Position equations",
        "notes_differ": "*Where the notes print it otherwise* (errata, {entry}):",
        "loops_count": ("The link graph has {links} links and {joints} joints, so "
                        "{loops} independent loops ({joints} $-$ {links} $+$ 1).  Each loop "
                        "is a closed vector polygon; its projections on $x$ and $y$ are two "
                        "position equations."),
        "loops_count_one": ("The link graph has {links} links and {joints} joints, so one "
                            "independent loop ({joints} $-$ {links} $+$ 1), a closed vector "
                            "polygon; its projections on $x$ and $y$ are two position "
                            "equations."),
        "loop": "Loop {k}, going round {path}:",
        "no_loops": ("The model has no closed loop: every coordinate follows from the inputs "
                     "directly, and $S$ is empty."),
        "redundant": ("Equations {rows} follow from the others (a redundant constraint, as in "
                      "a parallelogram's extra link); they are left out of $\\Phi$."),
        "redundant_one": ("Equation {rows} follows from the others (a redundant constraint, as "
                          "in a parallelogram's extra link); it is left out of $\\Phi$."),
        "velocity": "Velocity equations",
        "velocity_intro": "Differentiating the position equations with respect to time:",
        "matrix_form": "In matrix form, $J \\dot S + Q \\dot q = 0$, with",
        "matrix_names": ("$J = \\partial\\Phi/\\partial S$ (the Jacobian matrix), "
                         "$\\dot S$ the vector of secondary velocities, "
                         "$Q = \\partial\\Phi/\\partial q$ and $\\dot q$ the vector of primary "
                         "velocities."),
        "jacobian": "The Jacobian and the singular configurations",
        "det": "Its determinant:",
        "det_large": ("$\\det J$ is too large to read here ({ops} operations); its value at "
                      "the chosen input is in the last section."),
        "singular_intro": "$\\det J = 0$, and the velocities are undefined, where",
        "sing_slide": "{factor}: the point {point} reaches {origin}, the origin of the slide {joint}{pivot};",
        "sing_pivot": " (the pivot of {link})",
        "sing_in_line": "{factor}: {a} and {b} are in line (a toggle: a dead centre of the chain);",
        "reach": "Toggles and dead centres over the input range",
        "reach_intro": ("Over the model's input range, {span}, the two kinds of singular "
                        "position the notes tell apart (found by `kinelab.kinematics`)."),
        "reach_intro_many": ("Over the box of the model's input ranges, {span}, $\\det J = 0$ "
                             "is one equation in the {count} inputs: its solutions are curves "
                             "in the plane of the inputs (surfaces, for three). "
                             "`kinelab.kinematics.toggles` finds points on them on a grid of "
                             "${grid}$ samples, each bisected along its grid line: *limit "
                             "positions*, where the loops stop closing, and *change points*, "
                             "where $\\det J$ changes sign; and any sample of the grid where it "
                             "is zero. For a mechanism driven at its actuated joints these are "
                             "its parallel singularities (Gosselin and Angeles' second type: "
                             "the output can move with the inputs locked)."),
        "toggle_reached_many": "{factor} is reached at {count} of the points found, e.g. {where};",
        "toggle_not_reached_box": "{factor} is not reached in this box;",
        "toggle_none_box": "$\\det J = 0$ is not reached in this box.",
        "many limit position": "a limit position (the loops stop closing)",
        "many change point": "a change point ($\\det J$ changes sign)",
        "many touch": "an isolated point on the grid",
        "dead_many": "*Dead centres* ($K = 0$) are found for mechanisms of one input.",
        "reach_failed": "Toggles and dead centres could not be found: {why}",
        "toggle_intro": ("*Toggles* (dead centres of the chain, $\\det J = 0$: the chain "
                         "locks, or may change branch), for each condition above:"),
        "toggle_reached": "{factor} is reached at {where};",
        "toggle_not_reached": "{factor} is not reached over this range;",
        "toggle_none": "$\\det J = 0$ is not reached over this range.",
        "limit position": "a limit position (the input cannot go on)",
        "change point": "a change point (the input goes on; the branch may change)",
        "dead_intro": ("*Dead centres* ($K = 0$: the coordinate stops and turns back; not a "
                       "singular configuration, $\\det J \\neq 0$ there), apart from the "
                       "toggles:"),
        "dead_at": "{symbol} turns back at {where};",
        "dead_where": "{q}, where {value}",
        "dead_none": "{symbol} does not turn back over this range;",
        "sing_perpendicular": "{factor}: {a} and {b} are perpendicular;",
        "sing_angle": "{factor}: {link} is at {values} from the $x$ axis;",
        "sing_other": "{factor}.",
        "sing_none": "$\\det J$ depends on no coordinate: the model has no singular configuration.",
        "coefficients": "Velocity coefficients",
        "K_intro": ("Solving for the secondary velocities, $\\dot S = -J^{{-1}} Q \\dot q = "
                    "K \\dot q$, with $K = dS/dq$:"),
        "K_large": ("$K$ is too large to read here ({ops} operations); it is "
                    "$K = -J^{{-1}} Q$ with the $J$ and $Q$ above, and its value at the "
                    "chosen input is in the last section."),
        "acceleration": "Acceleration equations",
        "acceleration_intro": ("Differentiating the velocity equations with respect to time and "
                               "grouping the terms, in matrix form:"),
        "acceleration_rows": ("Differentiating the velocity equations with respect to time and "
                              "grouping the terms, one row of $J \\ddot S$ at a time:"),
        "zeros_left_out": "The entries not written are 0.",
        "acceleration_large": ("The differentiated velocity equations are too large to read "
                               "here ({ops} operations)."),
        "L_intro": ("With $\\dot S = K \\dot q$ the secondary accelerations are "
                    "$\\ddot S = K \\ddot q + L \\dot q^2$, where $L = dK/dq$, the total "
                    "derivative $\\partial K/\\partial q + (\\partial K/\\partial S) K$.  "
                    "Written with the velocity coefficients, as the notes write it:"),
        "L_intro_many": ("With $\\dot S = K \\dot q$ the secondary accelerations are "
                         "$\\ddot S = K \\ddot q + \\dot q^T L \\dot q$, where $L_{{ab}} = "
                         "\\partial K_{{a}}/\\partial q_{{b}} + (\\partial K_{{a}}/\\partial S) "
                         "K_{{b}}$.  Written with the velocity coefficients, as the notes write it:"),
        "L_in_K_large": ("$L$ written with the velocity coefficients is too large to read here "
                         "({ops} operations); it solves $J L = -(dJ/dq\\, K + dQ/dq)$."),
        "L_explicit": "And with $K$ substituted:",
        "L_large": ("With $K$ substituted, $L$ is too large to read here ({ops} operations); "
                    "its value at the chosen input is in the last section."),
        "dynamics": "Dynamics: Gibbs-Appell and Kane",
        "dynamics_intro": (f"The equations of motion in the form of {_NOTES} (§5), "
                           "$C^T D f = 0$, with the generalised coordinates $x = (q, S)$, the "
                           "generalised speeds $u = \\dot x$ and the bodies ($N = {bodies}$):"),
        "bodies_head": "Bodies",
        "body_link": "{link}: mass {m}, moment of inertia {I} about {point}",
        "body_point": "point mass {m} at {point} (on {link})",
        "body_loaded": "{link}: no mass; loads act on it (reference point {point})",
        "C_intro": "$C = [1;\\ K]$, the speeds of all coordinates in terms of the inputs':",
        "D_intro": ("$D$ holds the partial velocities $\\partial v_G/\\partial u_i$ and "
                    "$\\partial \\omega/\\partial u_i$ of each body, one row per generalised speed:"),
        "f_intro": ("$f$ holds, for each body, the applied force minus $m a_G$ and the applied "
                    "moment about its point minus $I \\alpha$:"),
        "matrix_large": "{what} is too large to show here ({ops} operations).",
        "loads_head": "Loads: {items}.",
        "load_force": "{symbol} = {law}",
        "gravity": "gravity {g} along {direction}",
        "tau_intro": ("The actuators act on the input coordinates themselves, so their efforts "
                      "$\\tau$ are the generalised forces of $q$: $C^T D f + \\tau = 0$.  With "
                      "$\\dot S = K \\dot q$ and the accelerations through $L$:"),
        "tau_large": "The equations of motion are too large to read here ({ops} operations).",
        "numbers": "Numbers at {at}",
        "numbers_intro": ("The secondary coordinates $S$ and the right-hand column come from "
                          "`kinelab.analyze`; the derivation's expressions are evaluated with "
                          "those $S$.  SI units (m, rad)."),
        "or": "or",
        "col_derived": "derivation", "col_engine": "kinelab.analyze", "col_difference": "difference",
        "residual": "Loop closure $\\Phi(q, S)$ at the engine's $S$: largest {r}.",
        "J_value": "$J$ and $Q$:",
        "det_value": ("$\\det J$ = {det}; the engine's group-by-group determinant is {engine} "
                      "(the same zeros, scaled group by group)."),
        "singular_here": "This configuration is singular: K and L are undefined here.",
        "efforts_head": "Actuator efforts at $\\dot q$ = {qd}, $\\ddot q$ = {qdd}",
        "efforts_note": ("The right-hand column is `kinelab.dynamics.inverse`, the engine's "
                         "Kane terms from its K and L."),
    },
    "pt": {
        "title": "{name}: as equações de velocidade e de aceleração",
        "intro": (f"O método geral de {_ERTHAL}, aplicado a este modelo pelo kinelab: "
                  "equações de posição $\\Phi(q, S) = 0$, sua derivada no tempo, a matriz "
                  "jacobiana $J$ e o vetor $Q$, as configurações singulares ($\\det J = 0$), "
                  "os coeficientes de velocidade $K$ e os coeficientes de aceleração $L$."),
        "symbols": "Símbolos",
        "symbols_intro": ("Comprimentos em m, ângulos em rad, no sentido anti-horário a partir "
                          "do eixo $x$.  Os valores são os do modelo."),
        "col_symbol": "símbolo", "col_meaning": "significado", "col_value": "valor",
        "inputs_head": "Coordenadas primárias (entradas) $q$",
        "unknowns_head": "Coordenadas secundárias (incógnitas) $S$",
        "parameters_head": "Constantes",
        "input_angle": "ângulo de {b} em relação a {a} (entrada {name})",
        "input_angle_ground": "ângulo de {b} (entrada {name})",
        "input_slide": "deslocamento de {joint} (entrada {name})",
        "unknown_angle": "ângulo de {link} (de {p} para {r})",
        "unknown_angle_one": "ângulo de {link}",
        "unknown_slide": "deslocamento de {joint}: distância de {point} a {origin} ao longo do eixo",
        "length": "comprimento de {link} ({a} a {b})",
        "distance": "distância de {a} a {b} em {link}",
        "direction": "ângulo de {a}{b} em relação à direção de {root}",
        "direction_ground": "ângulo de {a}{b} em relação ao eixo $x$",
        "link_offset": "ângulo de {link} em relação à direção de {root}",
        "link_offset_ground": "ângulo de {link} em relação ao eixo $x$",
        "axis": "ângulo do eixo de {joint} em relação à direção de {root}",
        "axis_ground": "ângulo do eixo de {joint} em relação ao eixo $x$",
        "offset": "distância da reta de {joint} a {origin}, à esquerda do eixo",
        "x": "$x$ do ponto fixo {point}",
        "y": "$y$ do ponto fixo {point}",
        "position": "Equações de posição",
        "notes_differ": "*As notas imprimem-no de outro modo* (errata, {entry}):",
        "loops_count": ("O grafo das peças tem {links} peças e {joints} juntas, logo "
                        "{loops} malhas independentes ({joints} $-$ {links} $+$ 1).  Cada "
                        "malha é um polígono vetorial fechado; suas projeções em $x$ e $y$ são "
                        "duas equações de posição."),
        "loops_count_one": ("O grafo das peças tem {links} peças e {joints} juntas, logo uma "
                            "malha independente ({joints} $-$ {links} $+$ 1), um polígono "
                            "vetorial fechado; suas projeções em $x$ e $y$ são duas equações "
                            "de posição."),
        "loop": "Malha {k}, percorrida por {path}:",
        "no_loops": ("O modelo não tem malha fechada: toda coordenada decorre diretamente das "
                     "entradas, e $S$ é vazio."),
        "redundant": ("As equações {rows} decorrem das outras (um vínculo redundante, como a "
                      "peça extra de um paralelogramo); ficam fora de $\\Phi$."),
        "redundant_one": ("A equação {rows} decorre das outras (um vínculo redundante, como a "
                          "peça extra de um paralelogramo); fica fora de $\\Phi$."),
        "velocity": "Equações de velocidade",
        "velocity_intro": "Obtidas através das derivadas das equações de posição em relação ao tempo:",
        "matrix_form": "Na forma matricial, $J \\dot S + Q \\dot q = 0$, com",
        "matrix_names": ("$J = \\partial\\Phi/\\partial S$ (a matriz jacobiana), $\\dot S$ o "
                         "vetor das velocidades secundárias, $Q = \\partial\\Phi/\\partial q$ e "
                         "$\\dot q$ o vetor das velocidades primárias."),
        "jacobian": "A matriz jacobiana e as singularidades",
        "det": "Seu determinante:",
        "det_large": ("$\\det J$ é grande demais para ler aqui ({ops} operações); seu valor na "
                      "entrada escolhida está na última seção."),
        "singular_intro": "$\\det J = 0$, e as velocidades ficam indefinidas, quando",
        "sing_slide": "{factor}: o ponto {point} chega a {origin}, a origem do deslocamento {joint}{pivot};",
        "sing_pivot": " (o pivô de {link})",
        "sing_in_line": "{factor}: {a} e {b} ficam alinhados (posição de travamento, ou de alinhamento);",
        "reach": "Posições de travamento e pontos mortos na faixa de entrada",
        "reach_intro": ("Na faixa de entrada do modelo, {span}, os dois tipos de posição "
                        "singular que as notas distinguem (calculados por `kinelab.kinematics`)."),
        "reach_intro_many": ("Na caixa das faixas de entrada do modelo, {span}, "
                             "$\\det J = 0$ é uma equação nas {count} entradas: suas soluções "
                             "são curvas no plano das entradas (superfícies, para três). "
                             "`kinelab.kinematics.toggles` encontra pontos nelas numa grade "
                             "de ${grid}$ amostras, cada um refinado por bisseção ao longo da "
                             "sua linha: *posições limite*, onde as malhas deixam de fechar, e "
                             "*pontos de mudança de ramo*, onde $\\det J$ muda de sinal; e "
                             "qualquer amostra da grade onde ele se anula. Num mecanismo "
                             "acionado pelas suas juntas atuadas, são as suas singularidades "
                             "paralelas (do segundo tipo de Gosselin e Angeles: a saída pode se "
                             "mover com as entradas travadas)."),
        "toggle_reached_many": ("{factor} é atingida em {count} dos pontos encontrados, p. ex. "
                                "{where};"),
        "toggle_not_reached_box": "{factor} não é atingida nesta caixa;",
        "toggle_none_box": "$\\det J = 0$ não é atingido nesta caixa.",
        "many limit position": "posição limite (as malhas deixam de fechar)",
        "many change point": "ponto de mudança de ramo ($\\det J$ muda de sinal)",
        "many touch": "um ponto isolado na grade",
        "dead_many": ("*Pontos mortos* ($K = 0$) são calculados para mecanismos de uma "
                      "entrada."),
        "reach_failed": "Não foi possível calcular as posições de travamento e os pontos mortos: {why}",
        "toggle_intro": ("*Posições de travamento* (ou de alinhamento; $\\det J = 0$: a "
                         "cadeia trava, ou pode mudar de ramo), para cada condição acima:"),
        "toggle_reached": "{factor} é atingida em {where};",
        "toggle_not_reached": "{factor} não é atingida nesta faixa;",
        "toggle_none": "$\\det J = 0$ não é atingido nesta faixa.",
        "limit position": "posição limite (a entrada não pode avançar)",
        "change point": "ponto de mudança de ramo (a entrada avança; o ramo pode mudar)",
        "dead_intro": ("*Pontos mortos* ($K = 0$: a coordenada para e inverte o sentido; não "
                       "é configuração singular, $\\det J \\neq 0$ ali), à parte das posições "
                       "de travamento:"),
        "dead_at": "{symbol} inverte o sentido em {where};",
        "dead_where": "{q}, com {value}",
        "dead_none": "{symbol} não inverte o sentido nesta faixa;",
        "sing_perpendicular": "{factor}: {a} e {b} ficam perpendiculares;",
        "sing_angle": "{factor}: {link} fica a {values} do eixo $x$;",
        "sing_other": "{factor}.",
        "sing_none": "$\\det J$ não depende de nenhuma coordenada: o modelo não tem configuração singular.",
        "coefficients": "Coeficientes de velocidade",
        "K_intro": ("Isolando as velocidades secundárias, $\\dot S = -J^{{-1}} Q \\dot q = "
                    "K \\dot q$, com $K = dS/dq$:"),
        "K_large": ("$K$ é grande demais para ler aqui ({ops} operações); é "
                    "$K = -J^{{-1}} Q$ com os $J$ e $Q$ acima, e seu valor na entrada "
                    "escolhida está na última seção."),
        "acceleration": "Equações das acelerações",
        "acceleration_intro": ("Derivando as equações de velocidade em relação ao tempo e "
                               "agrupando as parcelas, na forma matricial:"),
        "acceleration_rows": ("Derivando as equações de velocidade em relação ao tempo e "
                              "agrupando as parcelas, uma linha de $J \\ddot S$ por vez:"),
        "zeros_left_out": "As entradas não escritas são nulas.",
        "acceleration_large": ("As equações de velocidade derivadas são grandes demais para ler "
                               "aqui ({ops} operações)."),
        "L_intro": ("Substituindo $\\dot S = K \\dot q$, as acelerações secundárias são "
                    "$\\ddot S = K \\ddot q + L \\dot q^2$, com $L = dK/dq$, a derivada total "
                    "$\\partial K/\\partial q + (\\partial K/\\partial S) K$.  Escrito com os "
                    "coeficientes de velocidade, como nas notas:"),
        "L_intro_many": ("Substituindo $\\dot S = K \\dot q$, as acelerações secundárias são "
                         "$\\ddot S = K \\ddot q + \\dot q^T L \\dot q$, com $L_{{ab}} = "
                         "\\partial K_{{a}}/\\partial q_{{b}} + (\\partial K_{{a}}/\\partial S) "
                         "K_{{b}}$.  Escrito com os coeficientes de velocidade, como nas notas:"),
        "L_in_K_large": ("$L$ escrito com os coeficientes de velocidade é grande demais para ler "
                         "aqui ({ops} operações); é a solução de $J L = -(dJ/dq\\, K + dQ/dq)$."),
        "L_explicit": "E com $K$ substituído:",
        "L_large": ("Com $K$ substituído, $L$ é grande demais para ler aqui ({ops} operações); "
                    "seu valor na entrada escolhida está na última seção."),
        "dynamics": "Dinâmica: Gibbs-Appell e Kane",
        "dynamics_intro": (f"As equações dinâmicas na forma {_DAS_NOTAS} (§5), $C^T D f = 0$, "
                           "com as coordenadas generalizadas $x = (q, S)$, as velocidades "
                           "generalizadas $u = \\dot x$ e os corpos ($N = {bodies}$):"),
        "bodies_head": "Corpos",
        "body_link": "{link}: massa {m}, momento de inércia {I} em relação a {point}",
        "body_point": "massa concentrada {m} em {point} (sobre {link})",
        "body_loaded": "{link}: sem massa; há cargas sobre ele (ponto de referência {point})",
        "C_intro": "$C = [1;\\ K]$, as velocidades de todas as coordenadas em função das entradas:",
        "D_intro": ("$D$ contém as velocidades parciais $\\partial v_G/\\partial u_i$ e "
                    "$\\partial \\omega/\\partial u_i$ de cada corpo, uma linha por velocidade "
                    "generalizada:"),
        "f_intro": ("$f$ contém, para cada corpo, a força ativa menos $m a_G$ e o momento ativo "
                    "em relação ao seu ponto menos $I \\alpha$:"),
        "matrix_large": "{what} é grande demais para mostrar aqui ({ops} operações).",
        "loads_head": "Cargas: {items}.",
        "load_force": "{symbol} = {law}",
        "gravity": "gravidade {g} na direção {direction}",
        "tau_intro": ("Os atuadores agem sobre as próprias coordenadas de entrada, e seus esforços "
                      "$\\tau$ são as forças generalizadas de $q$: $C^T D f + \\tau = 0$.  Com "
                      "$\\dot S = K \\dot q$ e as acelerações por meio de $L$:"),
        "tau_large": "As equações dinâmicas são grandes demais para ler aqui ({ops} operações).",
        "numbers": "Valores em {at}",
        "numbers_intro": ("As coordenadas secundárias $S$ e a coluna da direita vêm de "
                          "`kinelab.analyze`; as expressões da dedução são avaliadas com esses "
                          "$S$.  Unidades SI (m, rad)."),
        "or": "ou",
        "col_derived": "dedução", "col_engine": "kinelab.analyze", "col_difference": "diferença",
        "residual": "Fechamento das malhas $\\Phi(q, S)$ com o $S$ do kinelab: no máximo {r}.",
        "J_value": "$J$ e $Q$:",
        "det_value": ("$\\det J$ = {det}; o determinante do kinelab, grupo a grupo, é {engine} "
                      "(os mesmos zeros, com outra escala em cada grupo)."),
        "singular_here": "Esta configuração é singular: K e L não estão definidos aqui.",
        "efforts_head": "Esforços dos atuadores com $\\dot q$ = {qd}, $\\ddot q$ = {qdd}",
        "efforts_note": ("A coluna da direita é `kinelab.dynamics.inverse`, os termos de Kane do "
                         "kinelab a partir de seus K e L."),
    },
}
