"""Placeholder demo: builds a model and prints it (the full demo arrives with the engine)."""
from kinelab.model import Input, Joint, Link, Mechanism, Point

m = Mechanism("pendulum", (Point("O", 0, 0), Point("A", 1, 0)),
              (Link("ground", ("O",), ground=True), Link("arm", ("O", "A"))),
              (Joint("pivot", "R", ("ground", "arm"), point="O"),), (Input(joint="pivot"),))
print(m)
