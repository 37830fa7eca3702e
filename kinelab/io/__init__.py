"""Model files in and out, results export, interchange formats.

- model files: :func:`load`, :func:`save`, :class:`ModelFile` (TOML or JSON, units declared
  in the file, SI inside; see ``docs/model-format.md``), :func:`from_toml` / :func:`to_toml`,
  :func:`from_json` / :func:`to_json`.
"""
from kinelab.io._modelfile import (ANGLE_UNITS, LENGTH_UNITS, SCHEMA, ModelFile, Outputs, Units,
                                   from_json, from_toml, load, save, to_json, to_toml)

__all__ = ["load", "save", "ModelFile", "Units", "Outputs", "SCHEMA", "LENGTH_UNITS",
           "ANGLE_UNITS", "from_toml", "to_toml", "from_json", "to_json"]
