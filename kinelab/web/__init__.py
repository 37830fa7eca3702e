"""kinelab in the browser: ``kinelab serve [MODEL]`` opens a local web app to draw, drag,
animate and plot a linkage, see its instant centres and its derivation.

The server is a small Starlette app (:func:`create_app`) whose routes call the same
functions the command line calls and answer with the same JSON it writes; the page is
static files shipped in the package (``kinelab/web/static/``: plain JavaScript modules and
SVG, maths as MathML, which browsers typeset themselves), so nothing is fetched from the
network.  See ``docs/web.md`` for the routes.
"""
from kinelab.web._app import MAX_BODY, create_app
from kinelab.web._api import MAX_SAMPLES
from kinelab.web._serve import serve

__all__ = ["create_app", "serve", "MAX_BODY", "MAX_SAMPLES"]
