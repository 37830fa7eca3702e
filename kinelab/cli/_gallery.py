"""``kinelab gallery``: the gallery of classic mechanisms, listed, and one's model file
written out to work on."""
from __future__ import annotations

import shutil
import textwrap

import click

from kinelab import gallery as _gallery
from kinelab._files import outputs
from kinelab.cli._main import said_written
from kinelab.errors import ModelError

__all__ = ["gallery"]


@click.command()
@click.argument("name", required=False)
@click.option("--out", "-o", "out", default=None, metavar="DIR",
              help="Directory to write NAME.toml into (default: the current directory).")
def gallery(name, out):
    """List the gallery of classic mechanisms, or print NAME's history and write its model
    file, NAME.toml, into --out.

    The file is an ordinary model file: check, analyse, plot or animate it with the other
    commands (kinelab analyze NAME.toml --out out/), or change it to make a design of your
    own.
    """
    from kinelab.gallery._gallery import unknown

    if name is None:
        if out is not None:
            raise click.UsageError("--out: give NAME too, the entry whose model file to write")
        entries = _gallery.entries()
        width = max(len(e.name) for e in entries)
        for e in entries:
            click.echo(f"{e.name:<{width}}  {e.title}")
        return
    if name not in _gallery.names():
        raise ModelError(f"NAME: {unknown(name)}; 'kinelab gallery' lists the "
                         f"{len(_gallery.names())} entries")
    e = _gallery.entry(name)
    with outputs("." if out is None else out) as files:
        written = files.write(f"{e.name}.toml", lambda p: shutil.copyfile(e.path, p))
    click.echo(e.title)
    click.echo(textwrap.fill(e.history, width=88))
    said_written([written])
