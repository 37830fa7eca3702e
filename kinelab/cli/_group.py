"""The ``kinelab`` command group: its options, its commands loaded when they run, and kinelab
errors turned into one line each with exit status 2.

This module imports click and nothing heavy: ``kinelab --help`` lists the commands from the
summaries they are registered with (``kinelab/cli/__init__.py``), and a command's module,
with the rooms and libraries it needs, is imported only when that command runs (or its own
``--help`` is asked for)."""
from __future__ import annotations

import importlib
import os
import sys
from collections.abc import MutableMapping

import click

from kinelab.errors import KinelabError, one_line

__all__ = ["main", "BAD_INPUT"]

BAD_INPUT = 2      # exit status for a bad file, option or input value


class _Commands(MutableMapping):
    """A group's commands by name, each imported from its module on first use.

    Listing the names imports nothing; looking a command up imports the module it lives in.
    Commands added as objects (``add_command``) are kept as they are."""

    def __init__(self):
        self._loaded: dict[str, click.Command] = {}
        self._where: dict[str, tuple[str, str, str]] = {}      # name: module, attribute, summary

    def register(self, name: str, where: str, summary: str) -> None:
        module, _, attribute = where.partition(":")
        self._loaded.pop(name, None)
        self._where[name] = (module, attribute, summary)

    def loaded(self, name: str) -> bool:
        return name in self._loaded

    def summary(self, name: str) -> str:
        return self._where[name][2]

    def __getitem__(self, name: str) -> click.Command:
        if name not in self._loaded:
            module, attribute, _ = self._where[name]     # KeyError: no such command
            self._loaded[name] = getattr(importlib.import_module(module), attribute)
        return self._loaded[name]

    def __setitem__(self, name: str, command: click.Command) -> None:
        self._where.pop(name, None)
        self._loaded[name] = command

    def __delitem__(self, name: str) -> None:
        if name not in self._loaded and name not in self._where:
            raise KeyError(name)
        self._loaded.pop(name, None)
        self._where.pop(name, None)

    def __iter__(self):
        return iter(dict.fromkeys([*self._where, *self._loaded]))

    def __len__(self) -> int:
        return len(self._where.keys() | self._loaded.keys())

    def __contains__(self, name: object) -> bool:
        return name in self._where or name in self._loaded


class _Group(click.Group):
    """A click group whose commands report kinelab errors in one line each, no traceback:
    exit status 2 for bad input (the errors that are also ValueErrors, and outputs that
    cannot be written, and options the command line cannot parse), 1 otherwise.

    Its commands are registered by name, module and summary (:meth:`add_lazy_command`) and
    imported when they run; the list in ``--help`` is made from the summaries."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        commands, self.commands = self.commands, _Commands()
        self.commands.update(commands)

    def add_lazy_command(self, name: str, where: str, summary: str) -> None:
        """Register the command ``name``, the object ``where`` names (``"module:attribute"``),
        imported when the command is first looked up.  ``summary`` is the first sentence of
        its help, which ``kinelab --help`` shows (shortened as click shortens the help of a
        command it has loaded, so the list reads the same either way)."""
        self.commands.register(name, where, summary)

    def format_commands(self, ctx: click.Context, formatter: click.HelpFormatter) -> None:
        """The list of commands with their short help, as click writes it, without importing
        their modules: a command not loaded yet is listed by a stand-in whose help is its
        summary."""
        rows = []
        for name in self.list_commands(ctx):
            command = (self.commands[name] if self.commands.loaded(name)
                       else click.Command(name, help=self.commands.summary(name)))
            if not command.hidden:
                rows.append((name, command))
        if rows:
            limit = formatter.width - 6 - max(len(name) for name, _ in rows)
            with formatter.section("Commands"):
                formatter.write_dl([(name, c.get_short_help_str(limit)) for name, c in rows])

    def main(self, args=None, prog_name=None, complete_var=None, standalone_mode=True, **extra):
        """click's main, with its usage errors (an unknown option, a value of the wrong
        type, a missing file) on one line like every other error, pointing to --help."""
        if not standalone_mode:
            return super().main(args, prog_name, complete_var, False, **extra)
        try:
            code = super().main(args, prog_name, complete_var, False, **extra)
        except click.exceptions.NoArgsIsHelpError as exc:     # a bare 'kinelab': the help
            exc.show()
            sys.exit(exc.exit_code)
        except click.ClickException as exc:
            ctx = getattr(exc, "ctx", None)
            hint = f" (see '{ctx.command_path} --help')" if ctx is not None else ""
            click.echo(f"kinelab: error: {one_line(exc.format_message())}{hint}", err=True)
            sys.exit(exc.exit_code)
        except click.Abort:
            click.echo("Aborted!", err=True)
            sys.exit(1)
        sys.exit(code if isinstance(code, int) else 0)

    def invoke(self, ctx: click.Context):
        try:
            return super().invoke(ctx)
        except KinelabError as exc:
            for line in str(exc).splitlines() or [type(exc).__name__]:
                click.echo(f"kinelab: error: {line}", err=True)
            ctx.exit(BAD_INPUT if isinstance(exc, ValueError) else 1)
        except BrokenPipeError:     # the reader went away (| head): nothing more to say
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
            ctx.exit(1)
        except OSError as exc:      # an output that cannot be written: say where, no traceback
            where = f" {exc.filename}" if exc.filename else ""
            click.echo(f"kinelab: error: cannot write{where}: {exc.strerror or exc}", err=True)
            ctx.exit(BAD_INPUT)


def _set_budget(ctx, param, value):
    from kinelab._memory import memory_budget
    if value is not None:
        try:
            memory_budget(value)
        except KinelabError as exc:
            raise click.BadParameter(str(exc).removeprefix("max_bytes: ")) from None
    else:       # the environment's budget, read now: a bad one is said before any work
        try:
            memory_budget()
        except KinelabError as exc:
            raise click.UsageError(str(exc)) from None
    return value


@click.group("kinelab", cls=_Group, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="kinelab")
@click.option("--memory-budget", metavar="SIZE", default=None, expose_value=False, is_eager=True,
              callback=_set_budget,
              help="Largest result kinelab builds, e.g. 8G (default 2G, or the environment "
                   "variable KINELAB_MEMORY_BUDGET); larger requests are refused, with the "
                   "estimate.")
def main() -> None:
    """kinelab: analysis of planar mechanisms described in model files.

    A model file (TOML or JSON, see docs/model-format.md) describes a linkage; the commands
    check it, sweep its input and write tables, plots and animations.
    """
