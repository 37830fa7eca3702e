"""``kinelab mobility`` and ``kinelab types``: the structure room at the command line.

Two click commands of the main ``kinelab`` group.  They parse, call
:mod:`kinelab.structure` and print; every computation lives there, and the group turns
kinelab errors into one-line messages with exit status 2.
"""
from __future__ import annotations

import json

import click

from kinelab import structure
from kinelab.cli._main import about

__all__ = ["mobility", "types"]

# the largest count an option takes: the structure room says why beyond its own, smaller
# bounds (12 links, a space's freedoms); this one refuses a huge number before any work
_MOST = 1_000_000
_COUNT = click.IntRange(1, _MOST)


def _load(path: str):
    from kinelab import io     # looked up at call time (tests may stand in a loader)
    return io.load(path)


@click.command("mobility")
@click.argument("model", type=click.Path(exists=True, dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def mobility(model: str, as_json: bool) -> None:
    """Mobility of MODEL: Kutzbach-Gruebler's count and the exact value, with the reason
    they differ."""
    m = _load(model)
    with about(model):
        result = structure.mobility(m)
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=2, ensure_ascii=False))
        return
    pairs = ", ".join(f"{n} of class P{j}" for j, n in result.pairs.items())
    click.echo(f"{m.name}: {result.space}, {result.links} links, pairs: {pairs or 'none'}")
    click.echo(result.explanation)


def _print_chains(links: int, mobility_: int, limit: int | None, as_json: bool) -> None:
    chains = structure.planar_chains(links, mobility_)
    rows = [{"name": c.name, "assortment": c.assortment, "joints": [list(j) for j in c.joints],
             "inversions": [i.description for i in c.inversions()]} for c in chains]
    if as_json:
        click.echo(json.dumps({"links": links, "mobility": mobility_, "chains": rows[:limit]},
                              indent=2))
        return
    total = sum(len(r["inversions"]) for r in rows)
    click.echo(f"{len(chains)} planar chains with {links} links and mobility {mobility_} "
               f"(simple revolute joints, no rigid part); {total} inversions")
    for r in rows[:limit]:
        a = ", ".join(f"{n}×{d}" for d, n in r["assortment"].items())
        click.echo(f"  {r['name']}: links by joints carried {a}; {len(r['inversions'])} inversions")


@click.command("types")
@click.option("--space", type=click.Choice(["planar", "spherical", "spatial"]), required=True,
              help="The motion space (lambda = 3, 3, 6).")
@click.option("--mobility", "mobility_", type=_COUNT, default=None,
              help="M, the freedoms of the end link (or of the chain with --links).")
@click.option("--method", type=click.Choice(["open", "active", "passive", "alternative"]),
              default="active", show_default=True,
              help="Number synthesis of an open chain, active-chain enumeration, passive-"
                   "chain addition, or the alternative method (*Mecanismos*, §3).")
@click.option("--motion", default=None,
              help="Wanted motion of the end link, e.g. 'Tx Ty' or 'Rx Ry Tr'.")
@click.option("--joints", default=None, help="Pair types to use, e.g. RPUS.")
@click.option("--max-joints", type=_COUNT, default=3, show_default=True,
              help="At most this many pairs per chain.")
@click.option("--links", type=_COUNT, default=None,
              help="Planar only: list every kinematic chain with this many links instead.")
@click.option("--limit", type=_COUNT, default=50, show_default=True,
              help="Print at most this many architectures.")
@click.option("--json", "as_json", is_flag=True, help="Print the result as JSON.")
def types(space, mobility_, method, motion, joints, max_joints, links, limit, as_json) -> None:
    """Type synthesis: candidate architectures for a space and a mobility."""
    if links is not None:
        if space != "planar":
            raise click.UsageError("--links lists planar kinematic chains; use --space planar")
        _print_chains(links, 1 if mobility_ is None else mobility_, limit, as_json)
        return
    options = {"max_joints": max_joints}
    if joints:
        options["joints"] = tuple(joints.replace(",", "").replace(" ", ""))
    if method == "open":
        options.pop("max_joints")
    s = structure.type_synthesis(space, mobility_, method=method, motion=motion, **options)
    archs = s.architectures(limit)
    if as_json:
        click.echo(json.dumps({
            "method": s.method, "space": s.space, "lambda": s.lam, "mobility": s.mobility,
            "total_connectivity": s.total_connectivity,
            "connectivities": [list(c) for c in s.connectivities], "count": s.count(),
            "table": [[n, str(ne)] for n, ne in s.table],
            "architectures": [{"name": a.name, "connectivities": list(a.connectivities)}
                              for a in archs]}, indent=2))
        return
    head = f"{s.method}, {s.space} (λ = {s.lam}), M = {s.mobility}"
    if s.motion is not None:
        head += f", motion {s.motion}"
    click.echo(head)
    for n, ne in s.table:
        click.echo(f"  nP1 = {n}: Ne = {ne}" + ("" if ne.denominator > 1 else "  (consistent)"))
    if s.method != "open chain":
        sets = "; ".join(str(c) for c in s.connectivities)
        click.echo(f"  C_T = {s.total_connectivity}; chain connectivities {sets}")
    more = f" (first {len(archs)})" if len(archs) < s.count() else ""
    click.echo(f"{s.count()} architecture{'' if s.count() == 1 else 's'}{more}:")
    for a in archs:
        click.echo(f"  {a.name}")
