"""Running a study: the designs in chunks of bounded memory, in this process or on a Dask
cluster; the same chunk function either way (:func:`~kinelab.sweep.evaluate_chunk`)."""
from __future__ import annotations

import json
import os
import sys
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from kinelab import _memory as memory
from kinelab._files import atomic_write, byte_size, file_path, read_file
from kinelab.errors import KinelabError, ModelError, describe, one_line, shown
from kinelab.solvers._arguments import flag
from kinelab.sweep._designs import DesignTable
from kinelab.sweep._family import Family, family as make_family
from kinelab.sweep._metrics import (DEFAULT_HARMONICS, MAX_SAMPLES, check_harmonics,
                                    check_metrics, check_samples, check_speed, evaluate_chunk,
                                    metric_columns)

__all__ = ["run", "connect", "chunk_size_for", "read_parquet", "write_parquet",
           "STANDARD_METRICS", "MAX_SAMPLES", "PARQUET_BYTES"]

STANDARD_METRICS = ("assembles", "grashof", "transmission_min", "transmission_max",
                    "time_ratio", "swing")
_CHUNK_BYTES = 32 << 20      # a chunk's working arrays: large enough that numpy's per-call
                             # cost vanishes, small enough to stay near the caches
_DASK_CHUNKS = 16           # a Dask task holds this many local chunks by default
_ARRAYS_PER_SAMPLE = 48      # float arrays (D, S) a chunk holds at once, at most (estimate)
_CONNECT_TIMEOUT = 5.0       # s to reach a scheduler before saying it cannot be reached
PARQUET_BYTES = 1 << 30      # a Parquet file's size: an atlas of a few million designs


def chunk_size_for(samples: int, requested: int | None = None, *, distributed: bool = False) -> int:
    """Designs per chunk: ``requested`` (or what fits in 32 MiB of working arrays, 16 times
    that for a Dask task, whose scheduling costs about a millisecond), lowered so that a
    chunk stays within a quarter of the memory budget."""
    per_design = 8 * _ARRAYS_PER_SAMPLE * max(samples, 1)
    fits = max(1, memory.memory_budget() // 4 // per_design)
    default = _CHUNK_BYTES * (_DASK_CHUNKS if distributed else 1) // per_design
    wanted = requested if requested is not None else max(1, default)
    return int(min(wanted, fits))


def _progress_bar(total: int) -> Callable[[int], None] | None:
    """A bar on stderr when it is a terminal (nothing otherwise)."""
    if not sys.stderr.isatty():
        return None
    import click

    bar = click.progressbar(length=total, label="sweep", file=sys.stderr)
    bar.__enter__()
    state = {"done": 0}

    def update(done: int) -> None:
        bar.update(done - state["done"])
        state["done"] = done
        if done >= total:
            bar.__exit__(None, None, None)
    return update


def connect(scheduler: Any):
    """A ``dask.distributed.Client`` for a client (returned as is) or a scheduler address
    (``"tcp://host:8786"``); an address that cannot be reached within 5 s is a ModelError."""
    try:
        from distributed import Client
    except ImportError:
        raise ModelError("client: running on Dask needs dask.distributed; install it with "
                         "pip install 'kinelab[sweep]'") from None
    if isinstance(scheduler, Client):
        return scheduler
    if not isinstance(scheduler, str):
        raise ModelError(f"client: expected a dask.distributed.Client or a scheduler address "
                         f"such as 'tcp://host:8786', got {describe(scheduler)}")
    _check_reachable(scheduler)
    try:
        return Client(scheduler, timeout=_CONNECT_TIMEOUT, set_as_default=False)
    except Exception as exc:     # refused, timed out, or something else answered there
        raise ModelError(f"scheduler: no Dask scheduler answered at {scheduler!r} within "
                         f"{_CONNECT_TIMEOUT:g} s ({type(exc).__name__}); check the address and that "
                         "the scheduler is running") from None


def _check_reachable(address: str) -> None:
    """Refuse at once a TCP scheduler address where nothing listens (a Dask client would
    retry until its timeout, and its threads would keep the process alive a while longer)."""
    import socket

    from distributed.comm import parse_address, parse_host_port

    try:
        protocol, location = parse_address(address)
        if protocol not in ("tcp", "tls"):
            return
        host, port = parse_host_port(location)
    except (ValueError, TypeError):
        raise ModelError(f"scheduler: expected an address such as 'tcp://host:8786', got "
                         f"{describe(address)}") from None
    try:
        socket.create_connection((host, port), timeout=_CONNECT_TIMEOUT).close()
    except OSError as exc:
        raise ModelError(f"scheduler: cannot reach {address!r} within {_CONNECT_TIMEOUT:g} s "
                         f"({exc.strerror or type(exc).__name__}); check the address and that the "
                         "scheduler is running") from None


def run(family: str | Family, designs, *, samples=72, metrics=None, client=None,
        chunk_size: int | None = None, progress: bool | Callable[[int, int], None] | None = None,
        speed: float = 1.0, harmonics: int = DEFAULT_HARMONICS, path=None) -> "pandas.DataFrame":
    """Metrics of every design of a family, over a turn of its input.

    Parameters
    ----------
    family : str, Mechanism or Family
        ``"fourbar"`` (design columns ``ground, crank, coupler, rocker`` and optionally
        ``coupler_point_along, coupler_point_perpendicular``, m), another catalogue kind, a
        mechanism read from a model file, or a :func:`family`.
    designs : DataFrame, mapping of columns, or array (D, P)
        One row per design (see :func:`grid`, :func:`random`, :func:`sobol`).
    samples : int or array_like, shape (S,)
        Samples of the input over a full turn (evenly from 0; 4 to :data:`MAX_SAMPLES`), or
        the input values, rad.
    metrics : sequence or mapping, optional
        Names among :data:`METRICS`, and functions of the kinematics (a :class:`Batch`,
        arrays (D, S)) returning one value per design, named by their ``__name__`` or by the
        mapping's keys.  Default: the family's among ``assembles, grashof,
        transmission_min, transmission_max, time_ratio, swing``.
    client : dask.distributed.Client or str, optional
        Run the chunks on this Dask cluster (a client, or a scheduler address): the same
        results as in this process.
    chunk_size : int, optional
        Designs per chunk (default: 32 MiB of working arrays, 16 times that on Dask); always
        lowered to a quarter of :func:`kinelab.memory_budget`.
    progress : bool or callable, optional
        A bar on stderr (default: when it is a terminal), or ``progress(done, total)``.
    speed : float
        Constant input speed for ``peak_torque``, rad/s, at most
        :data:`kinelab.model.MAX_RATE` (1e100) in size.
    harmonics : int
        Harmonics of the coupler-curve ``descriptors`` (columns ``fd+1, fd-1, ...``).
    path : str or path, optional
        Also write the table as Parquet there (needs pyarrow).

    Returns
    -------
    pandas.DataFrame
        One row per design, in the order given (the table's index when it is a DataFrame),
        one column per metric: ``assembles`` (bool: at every sample), ``reachable_from`` and
        ``reachable_to`` (the longest input interval where it assembles, rad), ``grashof``
        (:attr:`kinelab.mechanisms.Grashof.kind`), ``transmission_min`` and
        ``transmission_max`` (the acute transmission angle over the samples, rad),
        ``time_ratio`` (slow over fast stroke), ``swing`` (of the output, rad or m),
        ``fd+1, fd-1 ...`` (:func:`descriptors` of the coupler curve) and ``peak_torque``
        (N m).  Values that are not defined (a design that does not assemble over the whole
        turn, an output that does not reverse twice) are NaN.  Rows that cannot be analysed
        (a NaN or a negative length) are NaN too, and their reasons are in
        ``df.attrs["problems"]`` (row label -> message).

    Raises
    ------
    ModelError
        Unknown family, metric or column; an unreachable scheduler; more samples than
        :data:`MAX_SAMPLES` or a speed beyond ``MAX_RATE``.
    MemoryBudgetError
        One chunk's working arrays (designs x samples) beyond :func:`kinelab.memory_budget`.

    Examples
    --------
    >>> d = {"ground": [3.0, 1.0], "crank": [1.0, 2.0], "coupler": [3.0, 1.0], "rocker": [2.5, 1.5]}
    >>> df = kl.sweep.run("fourbar", d, metrics=("assembles", "grashof", "transmission_min"))
    >>> df["assembles"].tolist(), df["grashof"].tolist()
    ([True, False], ['crank-rocker', 'triple-rocker'])
    >>> round(float(np.degrees(df["transmission_min"][0])), 6)    # at q = 0: cos mu = (9 + 6.25 - 4) / 15
    41.409622
    """
    import pandas

    fam = make_family(family)
    if path is not None:        # checked before the study, not after it
        path = str(file_path(path))
    samples = check_samples(samples)
    harmonics = check_harmonics(harmonics)
    speed = check_speed(speed)
    if progress is not None and not callable(progress):
        if not isinstance(progress, (bool, np.bool_)):
            raise ModelError(f"progress: expected True, False or a function progress(done, total), "
                             f"got {describe(progress)}")
        progress = flag("progress", progress)
    if metrics is None:
        metrics = [m for m in STANDARD_METRICS
                   if _available(fam, m, isinstance(samples, int))]
    checked = check_metrics(fam, metrics, isinstance(samples, int))
    S = samples if isinstance(samples, int) else len(samples)
    if "descriptors" in checked.values() and S < 2 * harmonics + 1:
        raise ModelError(f"harmonics: {harmonics} harmonics of the coupler curve need at least "
                         f"{2 * harmonics + 1} samples, got {S}; ask for more samples or fewer "
                         "harmonics")
    table = DesignTable(designs, fam)
    if "descriptors" in checked.values() and not fam.has_point(table.columns):
        raise ModelError("metrics: 'descriptors' needs the family's coupler point: add the columns "
                         "coupler_point_along and coupler_point_perpendicular (m) to the designs")
    S = samples if isinstance(samples, int) else len(samples)
    if chunk_size is not None and (isinstance(chunk_size, bool)
                                   or not isinstance(chunk_size, (int, np.integer)) or chunk_size < 1):
        raise ModelError(f"chunk_size: expected a whole number >= 1, got {describe(chunk_size)}")
    size = chunk_size_for(S, chunk_size, distributed=client is not None)
    # a chunk holds its designs' arrays (D, S); one design's alone may exceed the budget
    held = min(size, max(table.size, 1))
    memory.require(8 * _ARRAYS_PER_SAMPLE * S * held,
                   f"the working arrays of {held:,} design(s) at {S:,} samples each",
                   "ask for fewer samples per turn")
    bounds = list(range(0, table.size, size)) + [table.size]
    chunks = list(zip(bounds[:-1], bounds[1:]))
    if progress is None:
        progress = True if sys.stderr.isatty() else False
    report = (_progress_bar(table.size) if progress is True else
              (lambda done: progress(done, table.size)) if callable(progress) else None)
    options = dict(samples=samples, metrics=checked, speed=speed, harmonics=int(harmonics))
    if client is None:
        parts = []
        for lo, hi in chunks:
            parts.append(evaluate_chunk(fam, table.chunk(lo, hi), table.problems[lo:hi], **options))
            if report:
                report(hi)
    else:
        dask_client = connect(client)
        try:
            parts = _on_dask(dask_client, fam, table, chunks, options, report)
        finally:
            if dask_client is not client:       # made here from an address: closed here
                dask_client.close()
    columns = {}
    for name in metric_columns(checked, harmonics):
        pieces = [p[name] for p in parts]
        columns[name] = np.concatenate(pieces) if pieces else np.empty(0)
    problems = np.concatenate([p["_problems"] for p in parts]) if parts else np.empty(0, object)
    df = pandas.DataFrame(columns, index=table.index)
    if "grashof" in df:
        df["grashof"] = df["grashof"].astype(object)
    bad = np.flatnonzero(problems != "")
    # the row labels as Python values (numbers, text, tuples of a MultiIndex), not numpy's
    df.attrs["problems"] = dict(zip(table.index[bad].tolist(), map(str, problems[bad])))
    if path is not None:
        write_parquet(df, path)
    return df


def _available(fam: Family, metric: str, full_turn: bool) -> bool:
    try:
        check_metrics(fam, (metric,), full_turn)
        return True
    except KinelabError:
        return False


def _on_dask(client, fam, table, chunks, options, report):
    """The chunks as tasks on a Dask cluster, gathered in order."""
    from distributed import as_completed

    futures = [client.submit(evaluate_chunk, fam, table.chunk(lo, hi), table.problems[lo:hi],
                             **options, pure=False) for lo, hi in chunks]
    position = {f.key: hi - lo for f, (lo, hi) in zip(futures, chunks)}
    done = 0
    try:
        for f in as_completed(futures):
            if f.status == "error":
                f.result()           # raises the worker's exception here
            done += position[f.key]
            if report:
                report(done)
        return client.gather(futures)
    finally:
        for f in futures:
            f.release()


# what an object column may hold to be written as Parquet (pandas' infer_dtype names)
_PARQUET_OBJECTS = ("string", "empty", "boolean", "integer", "floating", "mixed-integer-float",
                    "bytes")


def read_parquet(path, what: str = "a table", instead: str = "") -> "pandas.DataFrame":
    """The table of a Parquet file, with its metadata (``df.attrs``), read within bounds.

    The file is checked (a regular file of at most ``PARQUET_BYTES``) and read by
    :func:`kinelab._files.read_file` before pyarrow sees it, and the table its metadata
    describes must fit the memory budget (a few compressed bytes can unpack into gigabytes).
    Every refusal is a :class:`ModelError` "PATH: cannot read ``what``: why", ending with
    ``instead`` (what to do) when the file is not Parquet.
    """
    import io

    import pandas

    path = file_path(path)
    try:
        import pyarrow.parquet as pq
    except ImportError:
        raise ModelError(f"cannot read {what}: Parquet needs the optional dependency pyarrow; "
                         "install it with pip install 'kinelab[sweep]'", source=str(path)) from None
    try:
        data = read_file(path, PARQUET_BYTES, note=" (an atlas of a few million designs)")
    except ModelError as exc:
        raise ModelError(f"cannot read {what}: {exc.problems[0]}", source=str(path)) from None
    try:
        meta = pq.ParquetFile(io.BytesIO(data)).metadata
        unpacked = sum(meta.row_group(i).total_byte_size for i in range(meta.num_row_groups))
        unpacked = max(unpacked, 8 * meta.num_rows * meta.num_columns)
        # the table twice (Arrow's and pandas') beside the file's bytes
        memory.require(2.0 * unpacked + len(data), f"reading it ({byte_size(len(data))} "
                       f"unpacking to {byte_size(unpacked)})", "read a smaller table",
                       source=str(path))
        return pandas.read_parquet(io.BytesIO(data))
    except ModelError:
        raise
    except Exception as exc:     # pyarrow's own errors: not a Parquet file, damaged
        raise ModelError(f"cannot read {what}: not a Parquet file ({one_line(type(exc).__name__)})"
                         + (f"; {instead}" if instead else ""), source=str(path)) from None


def write_parquet(df, path) -> None:
    """Write a study's table as Parquet, atomically (never a half-written file).

    The row problems (``df.attrs["problems"]``) travel in the file's metadata, keyed by the
    row labels as text (``str(label)``: a file's metadata is JSON, whose keys are text),
    whatever the index (numbers, dates, a MultiIndex)."""
    import pandas

    if not isinstance(df, pandas.DataFrame):
        raise ModelError(f"df: expected a pandas DataFrame (a study's table), got {describe(df)}")
    path = str(file_path(path))
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        raise ModelError("path: Parquet needs the optional dependency pyarrow; install it with "
                         "pip install 'kinelab[sweep]'") from None
    for name, column in df.items():
        kind = (pandas.api.types.infer_dtype(column, skipna=True) if column.dtype == object
                else "complex" if column.dtype.kind == "c" else "")
        if kind and kind not in _PARQUET_OBJECTS:
            raise ModelError(f"df: column {shown(str(name))}: expected numbers, booleans or text "
                             f"to write as Parquet, got {kind} values; convert the column first")
    attrs = dict(df.attrs)
    problems = attrs.get("problems")
    if isinstance(problems, Mapping):
        attrs["problems"] = {str(label): str(message) for label, message in problems.items()}
    try:
        json.dumps(attrs)
    except (TypeError, ValueError):
        raise ModelError("df.attrs: expected plain data (text keys; numbers, text, lists and "
                         "tables as values) to keep in the file's metadata; remove the others "
                         "from df.attrs") from None
    frame = df.copy(deep=False)
    frame.attrs = attrs
    atomic_write(os.fspath(path), lambda f: frame.to_parquet(f), binary=True)
