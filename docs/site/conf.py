"""Sphinx configuration of kinelab's documentation site, shared by its two languages.

Each language has its own source directory (``docs/site/en``, ``docs/site/pt``) and this
one configuration; the language is chosen on the command line::

    sphinx-build -W --keep-going -c docs/site -D language=pt docs/site/pt docs/_build/html/pt

(``make docs`` builds both).  Figures are drawn at build time by running kinelab
(matplotlib's plot directive), so an example that stops working stops the build.
"""
import os
import re

from docutils import nodes

# the pure-numpy engine: the same numbers as the compiled kernel, without waiting for it
os.environ.setdefault("KINELAB_KERNEL", "numpy")
os.environ.setdefault("MPLBACKEND", "Agg")

project = "kinelab"
author = "kinelab"
copyright = "kinelab"
language = "en"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "matplotlib.sphinxext.plot_directive",
]

source_suffix = {".md": "markdown"}
exclude_patterns = ["_build"]
root_doc = "index"

# MyST: the guides link to each other's sections by their titles ("#files-kinelab-reads")
myst_heading_anchors = 4
# a type named in a docstring ("q", "N", "Mechanism") may be an attribute of several classes:
# Sphinx links the first and says so; that is no broken link
suppress_warnings = ["ref.python"]

# API reference from the numpydoc docstrings
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "show-inheritance": False}
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_ivar = True

# figures: run at build time, small, no source links (the code is on the page)
plot_include_source = True
plot_html_show_source_link = False
plot_html_show_formats = False
plot_formats = [("png", 80)]
plot_rcparams = {"figure.figsize": (6.0, 3.6), "font.size": 9}
plot_pre_code = "import numpy as np\nimport matplotlib.pyplot as plt\nimport kinelab as kl\n"

html_theme = "alabaster"
html_static_path = []
html_copy_source = False
html_show_sourcelink = False

TITLES = {"en": "kinelab: analysis and synthesis of mechanisms",
          "pt": "kinelab: análise e síntese de mecanismos"}


def _language_titles(app, config):
    config.html_title = TITLES.get(config.language, TITLES["en"])
    config.html_short_title = "kinelab"


_LITERAL = re.compile(r"(``.*?``)")


def _absolute_bars(app, what, name, obj, options, lines):
    """The docstrings write absolute values as |x| in plain text, which reST reads as a
    substitution: escape those bars, outside literals and doctests."""
    in_doctest = False
    for i, line in enumerate(lines):
        text = line.lstrip()
        if text.startswith(">>>"):
            in_doctest = True
        elif not text:
            in_doctest = False
        if in_doctest or "|" not in line:
            continue
        lines[i] = "".join(part if part.startswith("``") else part.replace("|", r"\|")
                           for part in _LITERAL.split(line))


def _errata_across_languages(app, doctree, docname):
    """The Portuguese errata (docs/errata.pt.md) point to the English ones as errata.md, which
    on the Portuguese site is the page itself: send that link to the English site."""
    if app.config.language != "pt" or docname != "errata":
        return
    for ref in doctree.findall(nodes.reference):
        if ref.get("refuri") in ("", "#") and ref.astext() == "errata.md":
            ref["refuri"] = "../en/errata.html"
            ref["internal"] = False


def setup(app):
    app.connect("doctree-resolved", _errata_across_languages)
    app.connect("config-inited", _language_titles)
    app.connect("autodoc-process-docstring", _absolute_bars)
    return {"parallel_read_safe": True}
