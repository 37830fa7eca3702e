"""The ``kinelab`` command."""


def main() -> None:  # pragma: no cover - replaced by the full command line
    raise SystemExit("kinelab: no commands yet")
