"""Model files in and out, results export, interchange formats.

- model files: :func:`load`, :func:`save`, :class:`ModelFile` (TOML or JSON, units declared
  in the file, SI inside; see ``docs/model-format.md``), :func:`from_toml` / :func:`to_toml`,
  :func:`from_json` / :func:`to_json`;
- results: :func:`write_results` (CSV, JSON, Parquet) and :func:`summary` (a sweep at a glance,
  as data).
"""
from kinelab.io._modelfile import (ANGLE_UNITS, LENGTH_UNITS, SCHEMA, ModelFile, Outputs, Units,
                                   from_json, from_toml, load, save, to_json, to_toml)
from kinelab.io._results import RESULT_FORMATS, write_results
from kinelab.io._summary import (Extreme, QuickReturn, Summary, Transmission, default_outputs,
                                 reachable, summary)

__all__ = ["load", "save", "ModelFile", "Units", "Outputs", "SCHEMA", "LENGTH_UNITS",
           "ANGLE_UNITS", "from_toml", "to_toml", "from_json", "to_json", "write_results",
           "RESULT_FORMATS", "summary", "Summary", "Extreme", "Transmission", "QuickReturn",
           "default_outputs", "reachable"]
