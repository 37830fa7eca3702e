"""kinelab: analysis and synthesis of mechanisms."""
from kinelab import errors, model, spatial
from kinelab.model import Mechanism

__all__ = ["errors", "model", "Mechanism"]
