"""An atlas of four-bar coupler curves, searched by shape.

The atlas keeps, for every design that turns its crank fully, the normalised Fourier
descriptors of its coupler curve (:func:`~kinelab.sweep.descriptors`): they do not depend
on where the curve is, how it is turned or how large it is, so one atlas of designs with
O2O4 = (ground, 0) serves every target.  A target path is matched by its own descriptors
(a k-d tree, scipy.spatial), both ways round, since a mirrored or backwards curve swaps
the harmonics +k and -k; a match is then moved, turned and scaled onto the target (least
squares over the start of the curve) and polished by
:func:`kinelab.synthesis.path_generation`.
"""
from __future__ import annotations

import functools
import os
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError, describe, one_line, quoted, shown, shown_path, suggest
from kinelab.model import MAX_LENGTH, MIN_LENGTH, real_array
from kinelab.sweep._metrics import (DEFAULT_HARMONICS, descriptor_names, descriptors,
                                    resample_closed)
from kinelab.solvers._arguments import seed as check_seed
from kinelab._files import file_path
from kinelab.sweep._run import run, write_parquet
from kinelab.synthesis import MAX_PATH_POINTS, coupler_curves, path_generation

__all__ = ["Atlas", "atlas"]

COLUMNS = ("ground", "crank", "coupler", "rocker", "coupler_point_along",
           "coupler_point_perpendicular")
_MAX_HARMONICS = 1000       # descriptors per curve (2 per harmonic), at most, in a file
_CURVE_SAMPLES = 256        # samples of a matched curve when it is fitted onto the target


def atlas(designs, *, branch: str = "open", samples: int = 180,
          harmonics: int = DEFAULT_HARMONICS, client=None, progress=None, chunk_size=None) -> Atlas:
    """The coupler curves of many four-bars, ready to be searched by shape.

    Parameters
    ----------
    designs : DataFrame or mapping of columns
        ``ground, crank, coupler, rocker, coupler_point_along, coupler_point_perpendicular``
        (m), e.g. ``kl.sweep.sobol(2**16, ...)``.
    branch : {"open", "crossed"}
    samples, harmonics, client, progress, chunk_size
        As for :func:`run` (``client`` spreads the atlas over a Dask cluster).

    Returns
    -------
    Atlas
        The designs that turn their crank fully, with their descriptors.

    Examples
    --------
    >>> designs = kl.sweep.sobol(256, seed=1, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4),
    ...                          rocker=(1, 4), coupler_point_along=(-1, 2),
    ...                          coupler_point_perpendicular=(-1, 1))
    >>> a = kl.sweep.atlas(designs)
    >>> fb = kl.mechanisms.fourbar(2.5, 0.6, 2.8, 2.2, coupler_point=(1.2, 0.7))
    >>> path = kl.analyze(fb, np.linspace(0, 2 * np.pi, 90, endpoint=False)).position("P")
    >>> a.nearest(path, k=3).shape[0]
    3
    """
    from kinelab.sweep._family import family

    fam = family("fourbar", branch=branch)
    df = run(fam, designs, samples=samples, metrics=("assembles", "descriptors"),
             harmonics=harmonics, client=client, progress=progress, chunk_size=chunk_size)
    import pandas

    table = designs if isinstance(designs, pandas.DataFrame) else pandas.DataFrame(designs)
    missing = [c for c in COLUMNS if c not in table]
    if missing:
        raise ModelError(f"designs: an atlas needs the columns {', '.join(missing)}")
    keep = df["assembles"].to_numpy()
    rows = table.loc[keep, list(COLUMNS)].reset_index(drop=True)
    fd = df.loc[keep, descriptor_names(harmonics)].reset_index(drop=True)
    return Atlas(pandas.concat([rows, fd], axis=1), harmonics, branch)


@dataclass(frozen=True, eq=False)
class Atlas:
    """Four-bar designs (O2 at the origin, O4 at (ground, 0)) with the descriptors of their
    coupler curves.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per design: :data:`COLUMNS` and the descriptors ``fd+1, fd-1, ...``.
    harmonics : int
    branch : str
    """

    table: "pandas.DataFrame"
    harmonics: int
    branch: str

    def __len__(self) -> int:
        return len(self.table)

    @functools.cached_property
    def _tree(self):
        from scipy.spatial import cKDTree
        return cKDTree(self.table[descriptor_names(self.harmonics)].to_numpy())

    def nearest(self, path: ArrayLike, k: int = 5) -> "pandas.DataFrame":
        """The ``k`` designs whose coupler curves are nearest in shape to a closed path.

        Parameters
        ----------
        path : array_like, shape (n, 2)
            Points along the path, in order (n > 2 * harmonics), m, at least 1e-9 m across.
            Only its shape counts: it is moved and scaled to a unit size first, so any size
            finds the same designs.

        Returns
        -------
        pandas.DataFrame
            Their rows of :attr:`table`, nearest first, with ``distance`` (between
            descriptors, 0 for the same shape) and ``mirrored`` (matched with the harmonics
            swapped: the path backwards or mirrored).
        """
        P = _path(path, self.harmonics)
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 1:
            raise ModelError(f"k: expected a whole number >= 1, got {describe(k)}")
        if len(self) == 0:
            raise ModelError("atlas: it holds no design that turns its crank fully; build it "
                             "from more or other designs")
        fd = descriptors(_normalised(P), self.harmonics)
        swapped = fd.reshape(-1, 2)[:, ::-1].ravel()
        k = min(int(k), len(self))
        found = {}
        for mirrored, target in ((False, fd), (True, swapped)):
            dist, idx = self._tree.query(target, k=k)
            for d, i in zip(np.atleast_1d(dist), np.atleast_1d(idx)):
                if i not in found or d < found[i][0]:
                    found[i] = (float(d), mirrored)
        best = sorted(found.items(), key=lambda item: item[1][0])[:k]
        out = self.table.iloc[[i for i, _ in best]].copy()
        out["distance"] = [d for _, (d, _) in best]
        out["mirrored"] = [m for _, (_, m) in best]
        return out

    def placed(self, path: ArrayLike, k: int = 5) -> np.ndarray:
        """The ``k`` nearest designs moved, turned and scaled onto the path: (k, 10) in the
        form of :func:`kinelab.synthesis.coupler_curves` (pivots A0, B0, lengths, coupler
        point, branch)."""
        P = _path(path, self.harmonics, placed=True)
        near = self.nearest(P, k)
        sigma = 1.0 if self.branch == "open" else -1.0
        target = _resampled(P[None], _CURVE_SAMPLES)[0]
        target = target[:, 0] + 1j * target[:, 1]
        placed = []
        for _, row in near.iterrows():
            g, c, b, r, u, v = (float(row[name]) for name in COLUMNS)
            best = None
            for mirror in (1.0, -1.0):       # the mirror image: v and the branch change sign
                design = np.array([0, 0, g, 0, c, b, r, u, mirror * v, mirror * sigma])
                q = np.linspace(0, 2 * np.pi, _CURVE_SAMPLES, endpoint=False)
                curve = _resampled(coupler_curves(design[None], q)[0], _CURVE_SAMPLES)[0]
                z = curve[:, 0] + 1j * curve[:, 1]
                for zz in (z, z[::-1]):
                    fit = _similarity(zz, target)
                    if best is None or fit[0] < best[0]:
                        best = (*fit, design)
            _, a, shift, design = best
            pivots = a * np.array([0j, design[2]]) + shift
            out = design.copy()
            out[0:4] = [pivots[0].real, pivots[0].imag, pivots[1].real, pivots[1].imag]
            out[4:9] *= abs(a)
            placed.append(out)
        return np.array(placed)

    def refine(self, path: ArrayLike, k: int = 3, *, points: int = 8, **options):
        """Linkages through ``points`` points of the path, polished from the ``k`` nearest
        designs by :func:`kinelab.synthesis.path_generation` (its ``options``: runs,
        maxiter, seed, tolerance ...; by default one run)."""
        P = _path(path, self.harmonics, placed=True)
        if isinstance(points, bool) or not isinstance(points, (int, np.integer)) \
                or not 3 <= points <= MAX_PATH_POINTS:
            raise ModelError(f"points: expected a whole number from 3 to {MAX_PATH_POINTS}, got "
                             f"{describe(points)}")
        targets = _resampled(P[None], int(points))[0]
        # points taken evenly along the closed path: on a path that goes back over itself (an
        # open line, closed by its way back) two of them can fall on one place
        gaps = np.hypot(*(targets[:, None, :] - targets[None, :, :]).transpose(2, 0, 1))
        gaps[np.diag_indices(len(targets))] = np.inf
        if gaps.min() <= 1e-12 * float(np.ptp(targets, axis=0).max()):
            raise ModelError(f"path: the {int(points)} points refine takes evenly along it (closing it "
                             "from its last point to its first) fall on one place twice: it goes "
                             "back over itself, as an open line does; give a closed path, or "
                             "another number of points")
        for key in options:
            if key not in _REFINE_OPTIONS:
                hint = ("; refine starts from the atlas's nearest designs: for designs of your own, "
                        "call kinelab.synthesis.path_generation" if key in ("initial", "points")
                        else suggest(key, _REFINE_OPTIONS))
                raise ModelError(f"{shown(key)}: unknown option of refine{hint}; its options are k, "
                                 f"points, {quoted(_REFINE_OPTIONS)}")
        if "seed" in options:
            options["seed"] = check_seed(options["seed"])
        options = {"runs": 1, **options}
        return path_generation(targets, initial=self.placed(P, k), **options)

    def to_parquet(self, path: str | os.PathLike) -> None:
        df = self.table.copy()
        df.attrs = {"harmonics": self.harmonics, "branch": self.branch}
        write_parquet(df, path)

    @classmethod
    def from_parquet(cls, path: str | os.PathLike) -> Atlas:
        """An atlas written by :meth:`to_parquet` (or ``kinelab atlas``), checked: its
        metadata (harmonics, branch), its columns and finite numbers in them."""
        import pandas

        path = str(file_path(path))
        where = shown_path(path)
        if os.path.isdir(path):      # pyarrow would read the files in it as one table
            raise ModelError(f"{where}: cannot read an atlas: a directory, not a file; name the "
                             "atlas's file")
        try:
            df = pandas.read_parquet(path)
        except FileNotFoundError:
            raise ModelError(f"{where}: cannot read an atlas: no such file; check the path") from None
        except OSError as exc:
            raise ModelError(f"{where}: cannot read an atlas: "
                             f"{exc.strerror or one_line(exc, 200)}; check the path") from None
        except Exception as exc:     # pyarrow's own errors: not a Parquet file, damaged
            raise ModelError(f"{where}: cannot read an atlas: not a Parquet file written by "
                             f"kinelab ({one_line(type(exc).__name__)}); build one with kinelab "
                             "atlas") from None
        attrs = dict(df.attrs)
        if "harmonics" not in attrs or "branch" not in attrs:
            raise ModelError(f"{where}: not an atlas (no harmonics and branch in its "
                             "metadata); build one with kinelab atlas")
        harmonics, branch = attrs["harmonics"], attrs["branch"]
        if isinstance(harmonics, bool) or not isinstance(harmonics, int) \
                or not 1 <= harmonics <= _MAX_HARMONICS:
            raise ModelError(f"{where}: harmonics in its metadata: expected a whole number from 1 "
                             f"to {_MAX_HARMONICS}, got {describe(harmonics)}; rebuild it with "
                             "kinelab atlas")
        if branch not in ("open", "crossed"):
            raise ModelError(f"{where}: branch in its metadata: expected one of 'open', "
                             f"'crossed', got {describe(branch)}; rebuild it with kinelab atlas")
        needed = [*COLUMNS, *descriptor_names(harmonics)]
        missing = [c for c in needed if c not in df.columns]
        if missing:
            raise ModelError(f"{where}: not an atlas of {harmonics} harmonics: no column "
                             f"{quoted(missing, limit=4)}; rebuild it with kinelab atlas")
        for c in needed:
            values = df[c].to_numpy()
            if values.dtype.kind not in "iuf" or not np.isfinite(values).all():
                bad = np.flatnonzero(~np.isfinite(values)) if values.dtype.kind in "iuf" else [0]
                raise ModelError(f"{where}: column {shown(c)}: expected finite numbers, got "
                                 f"{describe(values[bad[0]])} in row {int(bad[0])}; rebuild it "
                                 "with kinelab atlas")
        df.attrs = {}
        return cls(df, harmonics, branch)


# path_generation's options that refine passes on (it gives the points and initial designs)
_REFINE_OPTIONS = ("runs", "maxiter", "popsize", "samples", "min_transmission_angle", "seed",
                   "refine", "tolerance")


def _path(path, harmonics: int, placed: bool = False) -> np.ndarray:
    """The path as an array (n, 2), refused when it has no extent, or (``placed``: a linkage
    is to go through it) when it lies beyond the model's lengths."""
    P = real_array(path)
    if P is None or P.ndim != 2 or P.shape[1] != 2 or len(P) <= 2 * harmonics \
            or not np.isfinite(P).all():
        raise ModelError(f"path: expected more than {2 * harmonics} finite points, shape (n, 2), "
                         f"got {describe(path)}")
    scale = float(np.abs(P).max())
    # measured on the path scaled to 1, so that neither a huge nor a tiny one over- or underflows
    extent = scale * float(np.ptp(P / scale, axis=0).max()) if scale > 0 else 0.0
    if not extent >= MIN_LENGTH:
        raise ModelError(f"path: its points span {extent:.3g} m, expected a closed path at least "
                         f"{MIN_LENGTH:g} m across (points that do not all coincide)")
    if placed and scale > MAX_LENGTH:
        raise ModelError(f"path: a linkage through it needs points within {MAX_LENGTH:g} m of the "
                         f"origin, got one {scale:.3g} m away; scale the path down (its shape "
                         "alone finds the same designs)")
    return P


def _normalised(P: np.ndarray) -> np.ndarray:
    """The path moved to its centroid and scaled to a largest coordinate of 1: its shape,
    in numbers that neither overflow nor underflow whatever its size."""
    unit = P / np.abs(P).max()
    unit = unit - unit.mean(axis=0)
    return unit / np.abs(unit).max()


def _resampled(P: np.ndarray, n: int) -> np.ndarray:
    return resample_closed(P, n)[0]


def _similarity(z: np.ndarray, target: np.ndarray):
    """The map w = a z + b (a complex: turn and scale) that best fits z, started at any of
    its samples, onto the target (both resampled evenly): (residual, a, b)."""
    zc, tc = z - z.mean(), target - target.mean()
    n = len(z)
    # <tc, roll(zc, s)> for every shift s at once, by FFT
    cross = np.fft.ifft(np.fft.fft(tc) * np.conj(np.fft.fft(zc)))   # sum_j tc[j] conj(zc[j - s])
    a_all = cross / np.vdot(zc, zc)
    residual = np.vdot(tc, tc).real - np.abs(cross) ** 2 / np.vdot(zc, zc).real
    s = int(np.argmin(residual))
    a = a_all[s]
    return float(max(residual[s], 0.0) / n), a, target.mean() - a * z.mean()
