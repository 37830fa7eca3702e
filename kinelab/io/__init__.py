"""Model files in and out, results export, interchange formats.

- model files: :func:`load`, :func:`save`, :class:`ModelFile` (TOML or JSON, units declared
  in the file, SI inside; see ``docs/model-format.md``), :func:`from_toml` / :func:`to_toml`,
  :func:`from_json` / :func:`to_json`;
- interchange: :func:`from_pyslvs` / :func:`to_pyslvs` (Pyslvs mechanism expressions),
  :func:`from_linkage2d_json`; link outlines for drawings and cutting, :func:`to_svg` and
  :func:`to_dxf`;
- measured curves: :func:`read_curve` (a CSV of an abscissa and a displacement, for
  :func:`kinelab.solvers.differentiate`);
- synthesis tasks: :func:`load_task` / :func:`read_task` (a task file, or its content),
  :func:`solve_task`, :func:`task_summary` (what ``kinelab synth`` prints and writes, as data);
- results: :func:`write_results` (CSV, JSON, Parquet), :func:`results_json` and
  :func:`summary` (a sweep at a glance,
  as data).
"""
from kinelab._lazy import exports

# each public name, imported from its module on first use (see kinelab._lazy)
__getattr__, __dir__ = exports(__name__, {
    "kinelab.io._modelfile": ("ANGLE_UNITS", "LENGTH_UNITS", "SCHEMA", "ModelFile", "Outputs",
                              "Units", "from_json", "from_toml", "load", "save", "to_json",
                              "to_toml"),
    "kinelab.io._curves": ("MeasuredCurve", "read_curve"),
    "kinelab.io._linkage2d": ("from_linkage2d_json",),
    "kinelab.io._outline": ("Outline", "outlines", "to_dxf", "to_svg"),
    "kinelab.io._pyslvs": ("IMPORT_SPEEDS", "from_pyslvs", "to_pyslvs"),
    "kinelab.io._results": ("RESULT_FORMATS", "result_format", "results_json", "write_results"),
    "kinelab.io._task": ("Task", "TASK_KINDS", "load_task", "read_task", "solve_task",
                         "task_summary"),
    "kinelab.io._summary": ("Extreme", "QuickReturn", "Summary", "Transmission", "default_outputs",
                            "summary"),
})

__all__ = ["load", "save", "ModelFile", "Units", "Outputs", "SCHEMA", "LENGTH_UNITS",
           "ANGLE_UNITS", "from_toml", "to_toml", "from_json", "to_json", "write_results",
           "result_format", "results_json", "RESULT_FORMATS", "summary", "Summary", "Extreme", "Transmission", "QuickReturn",
           "default_outputs", "from_pyslvs", "to_pyslvs", "IMPORT_SPEEDS", "from_linkage2d_json",
           "to_svg", "to_dxf", "outlines", "Outline", "read_curve", "MeasuredCurve",
           "Task", "TASK_KINDS", "load_task", "read_task", "solve_task", "task_summary"]
