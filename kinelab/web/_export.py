"""Downloads: the files the command line writes, made from the page's model and sent as
content (nothing is written where the page could name a place)."""
from __future__ import annotations

import tempfile
import threading
from pathlib import Path

from starlette.responses import Response

from kinelab import _progress as progress
from kinelab import io
from kinelab._deadline import within
from kinelab.errors import ModelError, describe, quoted
from kinelab.io._modelfile import errors_from
from kinelab.web import _api, _limits

__all__ = ["export", "is_long", "KINDS", "ANIMATION_SECONDS"]

_FIGURES = threading.Lock()      # pyplot keeps global state: one figure at a time

ANIMATION_SECONDS = 60.0
"""The longest the server draws one animation (a few seconds for a six-bar; a chain of 200
links takes minutes)."""

KINDS = {"csv": "text/csv", "json": "application/json", "gif": "image/gif",
         "dxf": "application/dxf", "svg": "image/svg+xml"}
"""What can be downloaded: the sweep's table (as ``kinelab analyze`` writes it), the
animation (``kinelab animate --format gif``), the links' outlines (``kinelab export --to
dxf`` / ``svg``)."""


def is_long(body: dict) -> bool:
    """Whether an export is long work (an animation: seconds to minutes of drawing)."""
    return body.get("kind") == "gif"


def export(body: dict) -> Response:
    """The file ``body["kind"]`` of ``body["model"]``, as an attachment named after it."""
    kind = body.get("kind")
    if not isinstance(kind, str) or kind not in KINDS:
        raise ModelError(f"kind: expected one of {quoted(list(KINDS))}, got {describe(kind)}")
    mf = _api.read_model(body)
    stem = Path(mf.source).stem if mf.source else (mf.mechanism.name or "model")
    with tempfile.TemporaryDirectory(prefix="kinelab-web-") as folder:
        path = Path(folder) / f"result.{kind}"      # the name the user sees is in the header
        if kind in ("csv", "json"):
            samples = _api.samples_of(body, mf)
            _limits.check_sweep(mf, samples, "csv" if kind == "csv" else "rows", "the table")
            sol = mf.analyze(samples)
            io.write_results(sol, path, format=kind, units=mf.units)
        elif kind == "gif":
            import matplotlib
            matplotlib.use("Agg")          # files only, from a worker thread: no window
            import matplotlib.pyplot as plt  # before the clock starts

            from kinelab import plot
            samples = _api.samples_of(body, mf)
            _limits.check_sweep(mf, samples, "none", "the animation's sweep")
            progress.report("the sweep", 0.0)
            sol = mf.analyze(samples)

            def draw():
                with errors_from(mf), progress.part(0.1, 1.0):
                    plot.animate(sol, path, frames=60, fps=20, units=mf.units)
            with _FIGURES:
                try:
                    within(ANIMATION_SECONDS, draw, message=(
                        f"kind: the animation of {len(mf.mechanism.links)} links took more than "
                        f"{ANIMATION_SECONDS:g} s; make it with kinelab animate, which has no "
                        "such limit"))
                finally:
                    plt.close("all")        # a figure an animation stopped midway left open
        else:
            _limits.check_sweep(mf, 181, "none", "the outlines' sweep")
            sol = mf.analyze(181)          # slots span the sliders' travel, as the CLI's
            write = io.to_svg if kind == "svg" else io.to_dxf
            with errors_from(mf):
                write(mf.mechanism, path, unit=mf.units.length, sol=sol)
        content = path.read_bytes()
    return Response(content, media_type=KINDS[kind],
                    headers={"Content-Disposition": attachment(f"{stem}.{kind}")})


def attachment(name: str) -> str:
    """A Content-Disposition header for a download named ``name``, whatever its characters:
    an ASCII ``filename`` for old clients (other characters, quotes, backslashes and
    controls as ``_``) and the exact name as RFC 6266's ``filename*`` (UTF-8, percent-encoded).

    Examples
    --------
    >>> print(attachment('crank "rocker".csv'))
    attachment; filename="crank _rocker_.csv"; filename*=UTF-8''crank%20%22rocker%22.csv
    """
    from urllib.parse import quote
    plain = "".join(c if " " <= c <= "~" and c not in '"\\' else "_" for c in name)
    exact = quote(name.encode("utf-8", "surrogatepass"), safe="")
    return f'attachment; filename="{plain}"; filename*=UTF-8\'\'{exact}'
