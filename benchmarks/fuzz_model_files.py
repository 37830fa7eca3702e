"""Fuzzing kinelab's command line with hostile model and task files, at scale.

Each case is a valid file mutated field by field (``tests/fuzzing/grammar.py``), read by the
command that reads it (``check``, ``dynamics``, ``synth``).  The property: the command
succeeds, or ends with one bounded line per problem and exit status 2, within TIMEOUT
seconds and MEMORY bytes.  Prints the count of each outcome and a few examples of every
finding.

    python benchmarks/fuzz_model_files.py                  # 100,000 cases on every core
    python benchmarks/fuzz_model_files.py --cases 2000 --seed 7

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
import signal
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

TIMEOUT = 30            # seconds per case
MEMORY = 6 * 2**30      # bytes of address space per worker (the budget is 2 GiB)


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout


def _start_worker():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))
    signal.signal(signal.SIGALRM, _alarm)
    os.chdir(tempfile.mkdtemp(prefix="kinelab-fuzz-"))


def _one(seed: int) -> tuple[str, str, str]:
    from tests.fuzzing import grammar

    rng = random.Random(seed)
    c = grammar.case(rng)
    directory = Path(tempfile.mkdtemp(dir="."))
    signal.alarm(TIMEOUT)
    try:
        outcome, detail = grammar.run(c, directory)
    except _Timeout:
        outcome, detail = "timeout", ""
    except MemoryError:
        outcome, detail = "memory", ""
    finally:
        signal.alarm(0)
    return outcome, detail, f"seed {seed}: {' '.join(c.command)} on a {c.suffix} file"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=100_000)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    args = parser.parse_args()
    counts: collections.Counter = collections.Counter()
    examples: dict[str, list[str]] = collections.defaultdict(list)
    start = time.perf_counter()
    seeds = range(args.seed, args.seed + args.cases)
    with multiprocessing.get_context("fork").Pool(args.workers, initializer=_start_worker,
                                                  maxtasksperchild=2000) as pool:
        for i, (outcome, detail, where) in enumerate(pool.imap_unordered(_one, seeds, chunksize=20)):
            counts[outcome] += 1
            if outcome not in ("success", "error") and len(examples[outcome]) < 5:
                examples[outcome].append(f"{where}: {detail}")
            if (i + 1) % 5000 == 0:
                print(f"  {i + 1:,} cases, {time.perf_counter() - start:.0f} s", file=sys.stderr)
    elapsed = time.perf_counter() - start
    print(f"kinelab fuzzing: {args.cases:,} hostile files (seeds {args.seed}..{args.seed + args.cases - 1}), "
          f"{elapsed:.0f} s on {args.workers} workers")
    for outcome, n in counts.most_common():
        print(f"  {outcome:<16} {n:>8,}  {100 * n / args.cases:6.2f} %")
    findings = sum(n for o, n in counts.items() if o not in ("success", "error"))
    print(f"  findings: {findings:,}")
    for outcome, lines in examples.items():
        print(f"  {outcome}:")
        for line in lines:
            print(f"    {line[:300]}")


if __name__ == "__main__":
    main()
