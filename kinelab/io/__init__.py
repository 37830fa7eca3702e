"""Model files in and out, results export, interchange formats.

- model files: :func:`load`, :func:`save`, :class:`ModelFile` (TOML or JSON, units declared
  in the file, SI inside; see ``docs/model-format.md``), :func:`from_toml` / :func:`to_toml`,
  :func:`from_json` / :func:`to_json`;
- interchange: :func:`from_pyslvs` / :func:`to_pyslvs` (Pyslvs mechanism expressions),
  :func:`from_linkage2d_json`; link outlines for drawings and cutting, :func:`to_svg` and
  :func:`to_dxf`;
- measured curves: :func:`read_curve` (a CSV of an abscissa and a displacement, for
  :func:`kinelab.solvers.differentiate`);
- results: :func:`write_results` (CSV, JSON, Parquet), :func:`results_json` and
  :func:`summary` (a sweep at a glance,
  as data).
"""
from kinelab.io._modelfile import (ANGLE_UNITS, LENGTH_UNITS, SCHEMA, ModelFile, Outputs, Units,
                                   from_json, from_toml, load, save, to_json, to_toml)
from kinelab.io._curves import MeasuredCurve, read_curve
from kinelab.io._linkage2d import from_linkage2d_json
from kinelab.io._outline import Outline, outlines, to_dxf, to_svg
from kinelab.io._pyslvs import IMPORT_SPEEDS, from_pyslvs, to_pyslvs
from kinelab.io._results import RESULT_FORMATS, result_format, results_json, write_results
from kinelab.io._summary import (Extreme, QuickReturn, Summary, Transmission, default_outputs,
                                 summary)

__all__ = ["load", "save", "ModelFile", "Units", "Outputs", "SCHEMA", "LENGTH_UNITS",
           "ANGLE_UNITS", "from_toml", "to_toml", "from_json", "to_json", "write_results",
           "result_format", "results_json", "RESULT_FORMATS", "summary", "Summary", "Extreme", "Transmission", "QuickReturn",
           "default_outputs", "from_pyslvs", "to_pyslvs", "IMPORT_SPEEDS", "from_linkage2d_json",
           "to_svg", "to_dxf", "outlines", "Outline", "read_curve", "MeasuredCurve"]
