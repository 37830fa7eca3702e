"""Studies over many designs: a family of mechanisms, a table of designs, metrics per design.

In this process by default, vectorised over designs and samples in chunks of bounded memory
(every family in one call of the kernel per chunk),
or on a Dask cluster with the same call and the same results (``client=``).

- :func:`run` -- the metrics of every design, as a pandas DataFrame (and Parquet);
- :func:`family` -- a catalogue kind or a model's points as named parameters;
- :func:`grid`, :func:`random`, :func:`sobol` -- design tables from parameter ranges;
- :func:`descriptors` -- normalised Fourier descriptors of closed curves;
- :func:`atlas`, :class:`Atlas` -- coupler curves of many four-bars, searched by shape, and
  refined into linkages (:class:`RefinedPath`) measured against the whole path;
- :func:`tolerance` -- Monte Carlo of an output's error under dimensional tolerances.
"""
from kinelab.sweep._atlas import Atlas, RefinedPath, atlas
from kinelab.sweep._batch import Batch
from kinelab.sweep._designs import grid, random, sobol
from kinelab.sweep._family import CATALOGUE, Family, family
from kinelab.sweep._metrics import METRICS, descriptors, evaluate_chunk
from kinelab.sweep._run import STANDARD_METRICS, connect, read_parquet, run, write_parquet
from kinelab.sweep._tolerance import ToleranceStudy, tolerance

__all__ = ["run", "family", "Family", "Batch", "grid", "random", "sobol", "descriptors",
           "evaluate_chunk", "connect", "atlas", "Atlas", "RefinedPath", "tolerance",
           "ToleranceStudy", "read_parquet", "write_parquet", "METRICS", "STANDARD_METRICS",
           "CATALOGUE"]
