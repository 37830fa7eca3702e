"""An atlas of four-bar coupler curves for the tests: ``n`` Sobol designs over wide ranges."""
import kinelab as kl


def sobol_atlas(n: int) -> "kl.sweep.Atlas":
    designs = kl.sweep.sobol(n, seed=1, ground=(1, 4), crank=(0.3, 1), coupler=(1, 4),
                             rocker=(1, 4), coupler_point_along=(-1, 2),
                             coupler_point_perpendicular=(-1, 1))
    return kl.sweep.atlas(designs)
