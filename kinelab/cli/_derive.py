"""``kinelab derive``: the derivation of a model in the notes' notation, as a document.

It reads the model file and calls :func:`kinelab.derive.derive`; the document is the
derivation's own (:meth:`~kinelab.derive.Derivation.to_markdown`, ``to_latex``), and a PDF
is that LaTeX compiled by the TeX engine installed, if any.
"""
from __future__ import annotations

import click

from kinelab._deadline import within
from kinelab._files import atomic_write, output
from kinelab.cli._main import (errors_from, output_path, parse_inputs, read_model, said_written,
                               stem)
from kinelab.derive import LANGUAGES, TIME_LIMIT, derive
from kinelab.derive._derivation import time_limit_message
from kinelab.derive._document import write_pdf
from kinelab.derive._notation import NOTATIONS

__all__ = ["derive_command"]


@click.command("derive")
@click.argument("model", type=click.Path(exists=True, dir_okay=False))
@click.option("--at", "at", default=None, metavar="VALUE",
              help="Input(s) of the last section's numbers, in the file's units or with a unit "
                   "(30, 30deg, 0.5rad, 12mm; 30,60 for two inputs); default the sketch's.")
@click.option("--lang", type=click.Choice(LANGUAGES), default="en", show_default=True,
              help="Language of the document: English or Portuguese.")
@click.option("--format", "fmt", type=click.Choice(("md", "tex", "pdf")), default="md",
              show_default=True,
              help="Markdown with LaTeX maths, a standalone LaTeX file, or a PDF (needs a TeX "
                   "engine: lualatex, xelatex, pdflatex or tectonic).")
@click.option("--notation", default="notes", show_default=True, metavar="notes|names|NAME=SYMBOL,...",
              help="The symbols: 'notes', the notes' letters (a catalogue mechanism's, and the "
                   "model file's [notation] table); 'names', the model's own names "
                   "(theta_lever, s_slot, L_crank); or symbols to write instead of the names, "
                   "theta_lever=A,s_slot=B, over the notes' ones.")
@click.option("--out", "-o", default=".", metavar="DIR", show_default=True,
              help="Directory (or file) to write <name>_derivation.<format> to.")
@click.option("--time-limit", type=click.FloatRange(0, min_open=True), default=TIME_LIMIT,
              show_default=True, metavar="SECONDS",
              help="The most the derivation and its document may take; past it the command "
                   "stops and says so.")
def derive_command(model, at, lang, fmt, notation, out, time_limit):
    """Write the derivation of MODEL in the notes' notation: position equations (one vector
    loop per independent circuit), their time derivative, J, Q, det J and the singular
    configurations, K and L, and for a model with masses the Gibbs-Appell / Kane terms,
    after Erthal, "Mecanismos com 1 GL: análise geral de velocidade e aceleração" and the
    course notes "Mecanismos".  The last section gives the numbers at one input beside
    kinelab's analysis (SI units)."""
    mf = read_model(model)
    symbols = notation_option(notation)
    q = None
    if at is not None:
        q = parse_inputs(at, mf)

    def document():
        d = derive(mf.mechanism, lang, notation=symbols, time_limit=None)
        return d.to_markdown(at=q, time_limit=None) if fmt == "md" else d.to_latex(
            at=q, time_limit=None)
    with errors_from(mf):
        text = within(time_limit, document,
                      message=time_limit_message(mf.mechanism, None, time_limit, "it"))
    path = output_path(out, f"{stem(model)}_derivation", fmt)
    said_written([output(path, lambda p: write_pdf(text, p) if fmt == "pdf" else
                         atomic_write(p, lambda f: f.write(text)))])


def notation_option(text: str):
    """``--notation``: "notes", "names", or ``NAME=SYMBOL,...`` as a mapping."""
    text = text.strip()
    if text in NOTATIONS:
        return text
    pairs = [p.partition("=") for p in text.split(",") if p.strip()]
    bad = [a + b + c for a, b, c in pairs if not b or not a.strip() or not c.strip()]
    if bad or not pairs:
        raise click.BadParameter(f"expected notes, names or NAME=SYMBOL,... (theta_lever=A,"
                                 f"s_slot=B), got {text!r}", param_hint="'--notation'")
    return {a.strip(): c.strip() for a, _, c in pairs}
