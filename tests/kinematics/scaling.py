"""The same mechanism drawn at another size, for the tests that nothing depends on the unit a
model is written in."""
import dataclasses

import kinelab as kl


def scaled(m: kl.model.Mechanism, s: float) -> kl.model.Mechanism:
    """``m`` with every length multiplied by ``s``: the sketch, the links' lengths, exact
    places and sides, the prismatic joints' offsets, the gears' pitch radii, the lifts of cams
    whose followers slide, and the ranges and rates of slide inputs.  Masses stay; moments of inertia scale with s**2 (the same masses over a larger
    body)."""
    def length(v):
        return None if v is None else v * s

    points = tuple(dataclasses.replace(p, x=p.x * s, y=p.y * s, z=p.z * s) for p in m.points)
    links = tuple(dataclasses.replace(
        link, length=length(link.length), inertia=None if link.inertia is None else link.inertia * s * s,
        local=None if link.local is None else {k: (a * s, b * s) for k, (a, b) in link.local.items()},
        sides=None if link.sides is None else {
            k: {name: d if name == "side" else d * s for name, d in spec.items()}
            for k, spec in link.sides.items()})
        for link in m.links)
    def program(j):
        slides = any(x.type == "P" and x.links[1] == j.links[1] for x in m.joints)
        return j.program.scaled(s) if j.program is not None and slides else j.program
    joints = tuple(dataclasses.replace(j, offset=length(j.offset), radius=length(j.radius),
                                       radii=None if j.radii is None else tuple(r * s for r in j.radii),
                                       program=program(j))
                   for j in m.joints)
    inputs = tuple(dataclasses.replace(i, range=None if i.range is None else (i.range[0] * s, i.range[1] * s),
                                       speed=i.speed * s, acceleration=i.acceleration * s)
                   if is_slide(m, i) else i for i in m.inputs)
    return dataclasses.replace(m, points=points, links=links, joints=joints, inputs=inputs,
                               parameters={})


def is_slide(m: kl.model.Mechanism, inp: kl.model.Input) -> bool:
    return inp.joint is not None and m.joint(inp.joint).type == "P"


def input_units(m: kl.model.Mechanism, s: float):
    """What each input's values are multiplied by at scale s: s for a slide, 1 for an angle."""
    return [s if is_slide(m, i) else 1.0 for i in m.inputs]
