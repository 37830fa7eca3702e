"""Bennett's linkage: the spatial 4R loop that moves, by its input-output relation in closed
form."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from kinelab.errors import ModelError
from kinelab.spatial._cardan import _follow
from kinelab.spatial._common import as_angles, as_length, as_number

__all__ = ["BennettPositions", "bennett"]

# a / sin(alpha) and b / sin(beta) agree to this, relative: Bennett's condition, which a
# file's three or four typed digits meet only to their own precision
_CONDITION = 1e-6
# |sin((beta - alpha) / 2)| below this: twists so nearly equal that the linkage only folds
_DISTINCT = 1e-9


@dataclass(frozen=True)
class BennettPositions:
    """The joint angles of a Bennett linkage, and its Denavit-Hartenberg transforms.

    Attributes
    ----------
    theta : ndarray, shape (4,) or (N, 4)
        Joint angles theta1 ... theta4, rad: ``theta3 = -theta1``, ``theta4 = -theta2``.
    lengths : ndarray, shape (4,)
        ``a, b, a, b``, m: the common normals between consecutive axes.
    twists : ndarray, shape (4,)
        ``alpha, beta, alpha, beta``, rad: the angles between consecutive axes.
    """

    theta: np.ndarray
    lengths: np.ndarray
    twists: np.ndarray

    def transforms(self) -> np.ndarray:
        """The four link transforms ``T_k = Rot(z, theta_k) Trans(x, a_k) Rot(x, alpha_k)``,
        shape (4, 4, 4) or (N, 4, 4, 4); their product ``T_1 T_2 T_3 T_4`` is the identity
        (the loop closes)."""
        th = self.theta[..., :, None, None]
        a, al = self.lengths[:, None, None], self.twists[:, None, None]
        ct, st = np.cos(th), np.sin(th)
        ca, sa = np.cos(al), np.sin(al)
        zero, one = np.zeros_like(ct), np.ones_like(ct)
        rows = [[ct, -st * ca, st * sa, a * ct], [st, ct * ca, -ct * sa, a * st],
                [zero, sa + zero, ca + zero, zero], [zero, zero, zero, one]]
        return np.block(rows)

    def joints(self) -> tuple[np.ndarray, np.ndarray]:
        """The joints' places and axes in the frame of joint 1 (axis 1 along z through the
        origin, the ground link along x): points and unit axes, each shape (4, 3) or
        (N, 4, 3), m and dimensionless; joint k+1 is where the common normal from axis k
        meets axis k+1."""
        T = self.transforms()
        frames = [np.broadcast_to(np.eye(4), T.shape[:-3] + (4, 4))]
        for k in range(3):
            frames.append(frames[-1] @ T[..., k, :, :])
        F = np.stack(frames, axis=-3)
        return F[..., :3, 3], F[..., :3, 2]


def bennett(theta1: ArrayLike, a: float, b: float, alpha: float, beta: float) -> BennettPositions:
    """Joint angles of Bennett's linkage over its input angle: the closed form.

    Four revolute joints on four skew axes, links ``a, b, a, b`` long (the common normals
    of consecutive axes) and twisted by ``alpha, beta, alpha, beta`` (the angles between
    consecutive axes), with Bennett's condition ``a / sin(alpha) = b / sin(beta)``
    (Bennett, 1903).  Kutzbach-Gruebler's count gives a spatial 4R loop ``6·3 − 5·4 = −2``
    degrees of freedom; this one moves with one.  In Denavit-Hartenberg form (offsets
    zero, ``T_k = Rot(z, theta_k) Trans(x, a_k) Rot(x, alpha_k)``, ``T_1 T_2 T_3 T_4 = I``):

        theta3 = −theta1,   theta4 = −theta2,
        tan(theta1 / 2) tan(theta2 / 2) = sin((beta + alpha) / 2) / sin((beta − alpha) / 2),

    theta2 taken continuously over any number of turns (K the right-hand side: theta2 = π
    at theta1 = 0, and the output turns once as the input turns once).

    Parameters
    ----------
    theta1 : float or array_like, shape () or (N,)
        Input angle, rad: of link 2 (``a``) about axis 1, from the ground link (``b``).
    a, b : float
        Link lengths, m, positive.
    alpha, beta : float
        Twists, rad, in (0, π), unequal.

    Returns
    -------
    BennettPositions
        ``theta`` of shape (4,) for one input, (N, 4) for N.

    Raises
    ------
    ModelError
        If the lengths and twists miss Bennett's condition (by more than 1e-6 relative),
        or the twists are equal (the linkage then only folds).

    References
    ----------
    G. T. Bennett, "A new mechanism", *Engineering* 76 (1903), 777-778; the relation as in
    K. J. Waldron, "The Bennett linkage", in *Kinematics of Mechanisms*.

    Examples
    --------
    a = 1, b = √3, alpha = 30°, beta = 60°: ``K = sin 45° / sin 15° = 1 + √3``.

    >>> p = kl.spatial.bennett(np.radians(90.0), 1.0, np.sqrt(3.0), np.pi / 6, np.pi / 3)
    >>> np.degrees(p.theta).round(6)
    array([  90.      ,  139.792181,  -90.      , -139.792181])
    >>> T = p.transforms()
    >>> bool(np.allclose(T[0] @ T[1] @ T[2] @ T[3], np.eye(4), rtol=0, atol=1e-12))
    True
    """
    theta1 = as_angles("theta1", theta1)
    a, b = as_length("a", a, positive=True), as_length("b", b, positive=True)
    alpha, beta = as_number("alpha", alpha), as_number("beta", beta)
    for name, value in (("alpha", alpha), ("beta", beta)):
        if not 0.0 < value < np.pi:
            raise ModelError(f"{name}: expected a twist in (0, π) rad, got {value:.6g} rad")
    if abs(np.sin((beta - alpha) / 2)) < _DISTINCT:
        raise ModelError(f"alpha, beta: expected unequal twists, got {alpha:.6g} and "
                         f"{beta:.6g} rad; with equal twists (and then a = b) the loop only "
                         f"folds flat")
    left, right = a / np.sin(alpha), b / np.sin(beta)
    if abs(left - right) > _CONDITION * max(left, right):
        raise ModelError(f"a, b, alpha, beta: expected Bennett's condition a / sin(alpha) = "
                         f"b / sin(beta), got {left:.9g} and {right:.9g} m; choose b = "
                         f"{a * np.sin(beta) / np.sin(alpha):.9g} m for these a, alpha, beta")
    K = np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2)
    # tan(theta2 / 2) = K tan(u), u = π/2 - theta1/2: followed continuously, as a Cardan
    # joint's output is (tan(out) = k tan(in), k > 0)
    s = np.sign(K)
    theta2 = 2.0 * _follow(s * (np.pi / 2 - theta1 / 2), abs(K))
    theta = np.stack([theta1, theta2, -theta1, -theta2], axis=-1)
    return BennettPositions(theta=theta, lengths=np.array([a, b, a, b]),
                            twists=np.array([alpha, beta, alpha, beta]))
