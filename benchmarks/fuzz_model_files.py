"""Fuzzing kinelab's command line with hostile files, at scale.

Each case is a valid file mutated (``tests/fuzzing/grammar.py``) and read by the command
that reads it: model files field by field (``check``, ``dynamics``), task files of every
kind (``synth``), CSV tables as text (a measured curve for ``differentiate``, designs for
``sweep`` and ``atlas build``, a path for ``atlas find``) and atlases as Parquet tables and
bytes (``atlas find``).  The property: the command succeeds, or ends with one bounded line
per problem, each naming the file, and exit status 2, within TIMEOUT seconds and MEMORY
bytes.  Two more kinds of input: requests to the web app (``web``: the page's requests
mutated as JSON and as bytes, other methods; each answered 2xx, or 4xx with a one-line
``{"error": ...}``, never 5xx, a traceback or an error in the server's log) and hostile names
(``names``: models, points, links, tasks and tables named with paths, separators, device
names, controls and mathtext, through every command that writes files; nothing written
outside ``--out``, no unsafe file name, no staging directory left).  Prints the count of
each outcome for each kind of file and a few examples of every finding.

    python benchmarks/fuzz_model_files.py                  # 100,000 cases on every core
    python benchmarks/fuzz_model_files.py --cases 2000 --seed 7 --files csv,atlas
    python benchmarks/fuzz_model_files.py --cases 2000 --files web,names

Cases run in worker processes (one per core), each with its address space limited to MEMORY
and each case interrupted after TIMEOUT seconds (SIGALRM).
"""
from __future__ import annotations

import argparse
import collections
import multiprocessing
import os
import random
import resource
import shutil
import signal
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

TIMEOUT = 30            # seconds per case
MEMORY = 6 * 2**30      # bytes of address space per worker (the budget is 2 GiB)


class _Timeout(BaseException):     # not an Exception: the command line runner lets it pass
    pass


def _alarm(signum, frame):
    raise _Timeout


def _start_worker():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    signal.signal(signal.SIGALRM, _alarm)
    os.chdir(tempfile.mkdtemp(prefix="kinelab-fuzz-"))


FILES = ("model", "task", "csv", "atlas", "web", "names")


def _one(job: tuple[int, tuple[str, ...]]) -> tuple[str, str, str, str]:
    from tests.fuzzing import grammar

    seed, files = job
    rng = random.Random(seed)
    try:
        c = grammar.case(rng) if files == ("model",) else grammar.any_case(rng, files)
    except MemoryError:         # the generator's own fault: said, and the run goes on
        return "generator", "memory", "", f"seed {seed}: making the case"
    directory = Path(tempfile.mkdtemp(dir="."))
    # a request is bounded by the app's own limits (up to a minute), then by the case's
    signal.alarm(int(grammar.WEB_SECONDS) + 10 if c.family == "web" else TIMEOUT)
    try:
        outcome, detail = grammar.run(c, directory)
    except _Timeout:
        outcome, detail = "timeout", ""
    except MemoryError:
        outcome, detail = "memory", ""
    finally:
        signal.alarm(0)
        shutil.rmtree(directory, ignore_errors=True)     # a case's files: up to a few MB
    where = " ".join(c.command) if c.family == "web" else \
        f"{' '.join(c.command)} on a {c.suffix} file"
    return c.family, outcome, detail, f"seed {seed}: {where}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--files", default=",".join(FILES),
                        help="kinds of file, comma-separated: " + ", ".join(FILES) + " (model "
                             "alone: the cases of the first 100,000-case runs, seed for seed)")
    args = parser.parse_args()
    files = tuple(f.strip() for f in args.files.split(","))
    if not files or not set(files) <= set(FILES):
        parser.error(f"--files: expected some of {', '.join(FILES)}, got {args.files!r}")
    counts: collections.Counter = collections.Counter()
    by_file: collections.Counter = collections.Counter()
    examples: dict[str, list[str]] = collections.defaultdict(list)
    start = time.perf_counter()
    jobs = ((seed, files) for seed in range(args.seed, args.seed + args.cases))
    with multiprocessing.get_context("fork").Pool(args.workers, initializer=_start_worker,
                                                  maxtasksperchild=2000) as pool:
        for i, (family, outcome, detail, where) in enumerate(pool.imap_unordered(_one, jobs,
                                                                                  chunksize=20)):
            counts[outcome] += 1
            by_file[family, outcome] += 1
            if outcome not in ("success", "error") and len(examples[outcome]) < 5:
                examples[outcome].append(f"{where}: {detail}")
            if (i + 1) % 5000 == 0:
                print(f"  {i + 1:,} cases, {time.perf_counter() - start:.0f} s", file=sys.stderr)
    elapsed = time.perf_counter() - start
    print(f"kinelab fuzzing: {args.cases:,} hostile files (seeds {args.seed}..{args.seed + args.cases - 1}), "
          f"{elapsed:.0f} s on {args.workers} workers")
    for outcome, n in counts.most_common():
        print(f"  {outcome:<16} {n:>8,}  {100 * n / args.cases:6.2f} %")
    print("  by kind of file:")
    for family in sorted({f for f, _ in by_file}):
        total = sum(n for (f, _), n in by_file.items() if f == family)
        parts = ", ".join(f"{o} {n:,}" for (f, o), n in sorted(by_file.items()) if f == family)
        print(f"    {family:<8} {total:>8,}: {parts}")
    findings = sum(n for o, n in counts.items() if o not in ("success", "error"))
    print(f"  findings: {findings:,}")
    for outcome, lines in examples.items():
        print(f"  {outcome}:")
        for line in lines:
            print(f"    {line[:300]}")


if __name__ == "__main__":
    main()
