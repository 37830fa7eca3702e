"""kinelab: analysis and synthesis of mechanisms."""
from kinelab import errors, model, structure
from kinelab.model import Mechanism

__all__ = ["errors", "model", "Mechanism"]
