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

from kinelab.errors import ModelError, describe, quoted, shown, shown_path, suggest
from kinelab.model import MAX_LENGTH, MIN_LENGTH, real_array
from kinelab.sweep._metrics import (DEFAULT_HARMONICS, descriptor_names, descriptors,
                                    resample_closed)
from kinelab.solvers._arguments import seed as check_seed
from kinelab._files import file_path
from kinelab.sweep._run import read_parquet, run, write_parquet
from kinelab.synthesis import (MAX_PATH_POINTS, PathSolution, SolutionList, coupler_curves,
                               path_generation)

__all__ = ["Atlas", "RefinedPath", "atlas"]

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

    def refine(self, path: ArrayLike, k: int = 3, *, points: int | None = None,
               **options) -> SolutionList:
        """Linkages through the path, polished from the ``k`` nearest designs by
        :func:`kinelab.synthesis.path_generation`, each measured against every point given.

        Parameters
        ----------
        path : array_like, shape (n, 2)
            The closed path, its points in order, m.
        k : int
            How many of the nearest designs to start from.
        points : int, optional
            How many of the path's points the linkages are fitted through, 3 to 30
            (``MAX_PATH_POINTS``), taken evenly along it (by length, the first and the last
            among them); default (and at most) every point of the path, up to 30.  A last
            point that repeats the first (a path closed by hand) is not fitted twice.
        **options
            Of :func:`~kinelab.synthesis.path_generation`: runs, maxiter, popsize,
            samples, min_transmission_angle (30 deg by default), seed, refine, tolerance;
            by default one run.

        Returns
        -------
        SolutionList of RefinedPath
            Best first (the lowest RMS distance of the given points to the coupler curve).
            Each one's ``max_error`` and ``rms_error`` are the largest and RMS distance
            from **every** point of ``path`` to the linkage's coupler curve
            (``path_errors``), whatever points it was fitted through.
        """
        P = _path(path, self.harmonics, placed=True)
        count = MAX_PATH_POINTS if points is None else points
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) \
                or not 3 <= count <= MAX_PATH_POINTS:
            raise ModelError(f"points: expected a whole number from 3 to {MAX_PATH_POINTS}, got "
                             f"{describe(points)}")
        size = float(np.ptp(P, axis=0).max())
        # a closing repeat of the first point would be the same target twice
        given = P[:-1] if np.hypot(*(P[-1] - P[0])) <= 1e-12 * size else P
        chosen = _along(given, int(count))
        targets = given[chosen]
        for a in range(len(chosen) - 1):
            gaps = np.hypot(*(targets[a + 1:] - targets[a]).T)
            if gaps.min() <= 1e-12 * size:
                b = a + 1 + int(np.argmin(gaps))
                raise ModelError(f"path: points {chosen[a] + 1} and {chosen[b] + 1} are the "
                                 f"same place {_shown_xy(targets[a])}, which refine cannot fit "
                                 "twice (it fits the path's points in order); give each place "
                                 "once, or another number of points")
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
        initial = self.placed(P, k)
        try:
            found = path_generation(targets, initial=initial, **options)
        except ModelError as exc:
            # the targets are the path's points (or points along it): say so in its terms
            raise ModelError([f"path: {p[len('points: '):]}" if p.startswith("points: ") else p
                              for p in exc.problems]) from exc
        refined = [RefinedPath.of(s, P) for s in found]
        refined.sort(key=lambda s: s.rms_error)
        return SolutionList(refined, reason=found.reason)

    def to_parquet(self, path: str | os.PathLike) -> None:
        df = self.table.copy()
        df.attrs = {"harmonics": self.harmonics, "branch": self.branch}
        write_parquet(df, path)

    @classmethod
    def from_parquet(cls, path: str | os.PathLike) -> Atlas:
        """An atlas written by :meth:`to_parquet` (or ``kinelab atlas``), checked: the file
        (a regular one of at most 1 GiB, :func:`~kinelab.sweep.read_parquet`), its metadata
        (harmonics, branch), its columns (those of its harmonics, and no others), finite
        numbers in them, the bars' lengths and the coupler point within the model's sizes
        (1e-9 m to 1e9 m), descriptors from 0 to 1."""
        path = file_path(path)
        where = shown_path(path)
        df = read_parquet(path, "an atlas", "build one with kinelab atlas")
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
        extra = [str(c) for c in df.columns if c not in needed]
        if extra:
            raise ModelError(f"{where}: not an atlas of {harmonics} harmonics, as its metadata "
                             f"says: it also has the column(s) {quoted(extra, limit=4)}; rebuild "
                             "it with kinelab atlas")
        for c in needed:
            values = df[c].to_numpy()
            why = _column_problem(c, values)
            if why is not None:
                bad, expected = why
                raise ModelError(f"{where}: column {shown(c)}: expected {expected}, got "
                                 f"{describe(values[bad])} in row {bad}; rebuild it with "
                                 "kinelab atlas")
        df.attrs = {}
        return cls(df, harmonics, branch)


def _column_problem(name: str, values: np.ndarray) -> tuple[int, str] | None:
    """(row, what was expected) of the first value of an atlas's column that cannot be: not
    a finite number, beyond the model's sizes (a bar's length from MIN_LENGTH to
    MAX_LENGTH, the coupler point within MAX_LENGTH of its base), or a descriptor outside
    [0, 1] (one so far away would leave the search no finite distance)."""
    if not len(values):
        return None
    if values.dtype.kind not in "iuf":
        return 0, "finite numbers"
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        return int(bad[0]), "finite numbers"
    if name in COLUMNS[:4]:
        bad = np.flatnonzero((values < MIN_LENGTH) | (values > MAX_LENGTH))
        what = f"lengths from {MIN_LENGTH:g} m to {MAX_LENGTH:g} m"
    elif name in COLUMNS:
        bad = np.flatnonzero(np.abs(values) > MAX_LENGTH)
        what = f"coordinates of at most {MAX_LENGTH:g} m in size"
    else:                   # a descriptor: a harmonic's magnitude over the norm of them all
        bad = np.flatnonzero((values < 0) | (values > 1 + 1e-9))
        what = "descriptors from 0 to 1 (magnitudes of harmonics over their norm)"
    return (int(bad[0]), what) if bad.size else None


@dataclass(frozen=True, eq=False)
class RefinedPath(PathSolution):
    """A linkage refined from an atlas's designs onto a path, measured against the whole path.

    It is a :class:`~kinelab.synthesis.PathSolution` of the points it was fitted through
    (``points``, with ``q`` and ``errors`` at them), and besides:

    Attributes
    ----------
    path : ndarray, shape (n, 2)
        The path as given, m.
    path_errors : ndarray, shape (n,)
        The distance from each point of ``path`` to the linkage's coupler curve, m
        (:func:`kinelab.synthesis.curve_distances`: the engine's curve over every crank angle
        at which the loop closes on the linkage's assembly branch; exact to rounding).

    ``max_error`` and ``rms_error`` are the largest and RMS of ``path_errors``: how far the
    linkage misses the path the user gave, not only the points it was fitted through.
    """

    path: np.ndarray = None
    path_errors: np.ndarray = None

    @classmethod
    def of(cls, sol: PathSolution, path: np.ndarray) -> RefinedPath:
        from dataclasses import fields

        path = np.array(path, float)
        errors = sol.curve_distances(path)
        for a in (path, errors):
            a.setflags(write=False)
        return cls(**{f.name: getattr(sol, f.name) for f in fields(PathSolution)}, path=path,
                   path_errors=errors)

    @property
    def rms_error(self) -> float:
        """Root-mean-square distance of the path's points from the coupler curve, m."""
        return float(np.sqrt(np.mean(self.path_errors ** 2)))

    @property
    def max_error(self) -> float:
        """Largest distance of a point of the path from the coupler curve, m."""
        return float(self.path_errors.max())

    def __repr__(self) -> str:
        return (f"RefinedPath(largest distance of the {len(self.path)} path points to the "
                f"coupler curve={self.max_error:.3g} m, rms={self.rms_error:.3g} m, "
                f"{self.grashof.kind}, {self.state})")


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


def _along(P: np.ndarray, count: int) -> np.ndarray:
    """Indices of at most ``count`` of the points of a path (n, 2), in order, spread evenly
    along it by length: each the point nearest an even step, the first and last included."""
    if len(P) <= count:
        return np.arange(len(P))
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(P, axis=0).T))])
    steps = np.linspace(0.0, s[-1], count)
    right = np.clip(np.searchsorted(s, steps), 1, len(s) - 1)
    nearest = np.where(steps - s[right - 1] <= s[right] - steps, right - 1, right)
    return np.unique(nearest)


def _shown_xy(xy) -> str:
    return "(" + ", ".join(f"{float(v):.9g}" for v in xy) + ")"


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
