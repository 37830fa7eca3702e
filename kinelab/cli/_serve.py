"""``kinelab serve``: the browser app."""
from __future__ import annotations

import warnings

import click

from kinelab.cli._main import read_model

__all__ = ["serve"]


@click.command("serve")
@click.argument("model", required=False, type=click.Path(dir_okay=False))
@click.option("--port", type=click.IntRange(0, 65535), default=8000, show_default=True,
              help="Port to listen on (0: any free port).")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to listen on; anything but loopback is served with a warning.")
def serve(model, port, host):
    """Open kinelab in the browser: a local web app to draw, drag, animate and plot MODEL
    (or a catalogue mechanism or example chosen on the page).  Prints the address to open;
    stop it with Ctrl-C."""
    from kinelab import web

    start = None
    if model is not None:
        mf = read_model(model)
        start = {"model": mf.to_dict(), "source": mf.source}

    def announce(address):
        click.echo(f"kinelab: serving at {address} (Ctrl-C to stop)")
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = lambda message, *a, **k: click.echo(f"kinelab: warning: {message}",
                                                                    err=True)
        web.serve(start, host=host, port=port, announce=announce)
