"""Drive layout: the belt's path around the pulleys and the tensioner's take-up.

The belt runs through the pulleys in the order the input lists them (its
travel direction). A pulley inside the belt loop is wrapped the way the loop
turns; a ``backside`` pulley (the belt's back on it) the other way. With the
signed radius ``rho = sigma r`` (``sigma = +1`` for a counter-clockwise wrap),
the span from circle 1 to circle 2 leaves at ``P1 = c1 - rho1 n(u)`` and arrives
at ``P2 = c2 - rho2 n(u)``, ``n(u)`` the left normal of the travel direction
``u``; ``(c2 - c1) . n(u) = rho2 - rho1`` gives

    a = beta - asin((rho2 - rho1) / D),   L = sqrt(D^2 - (rho2 - rho1)^2)

(``D, beta``: distance and direction of the centres; the common tangent of
two circles). The wrap on a pulley is the turn from its arriving to its leaving
span direction, counted in its wrap sense.

Take-up (Hwang, Perkins, Ulsoy 1994; Beikmann, Perkins, Ulsoy 1996): the arm
swings the tensioner pulley by ``dX = l_a (-sin phi, cos phi) dphi``; the
arriving span lengthens by ``u_in . dX`` and the leaving span by
``-u_out . dX`` (projection of the pulley's motion on each span). Their sum is
the derivative of the whole path (spans and wraps, the envelope theorem);
:func:`path_length_mm` gives the path, and the tests check the sum against
its numerical derivative.

Lengths in mm, angles in radians unless a name says ``_deg``.

>>> g = span_geometry(np.array([[0.0, 0.0], [100.0, 0.0]]), np.array([10.0, 10.0]), np.array([1.0, 1.0]))
>>> [round(float(x), 3) for x in g["length_mm"]], [round(float(w), 4) for w in np.degrees(g["wrap_rad"])]
([100.0, 100.0], [180.0, 180.0])
"""

from __future__ import annotations

import numpy as np

from synth.errors import InputError, Problem

__all__ = ["loop_orientation", "span_geometry", "effective_length_mm", "path_length_mm", "tensioner_centre_mm",
           "take_up"]


def loop_orientation(centres_mm) -> float:
    """``+1`` when the route of pulley centres runs counter-clockwise (shoelace area > 0), else ``-1``.

    >>> loop_orientation([[0, 0], [1, 0], [0, 1]]), loop_orientation([[0, 0], [0, 1], [1, 0]])
    (1.0, -1.0)
    """
    c = np.asarray(centres_mm, dtype=float)
    x, y = c[:, 0], c[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return 1.0 if area >= 0 else -1.0


def span_geometry(centres_mm, radii_mm, sigma, names=None, *, strict: bool = True) -> dict:
    """Spans and wraps of a closed belt path through circles in travel order.

    ``sigma[i]`` is ``+1`` where the belt wraps pulley ``i`` counter-clockwise, ``-1`` clockwise. Span ``j``
    runs from pulley ``j`` to pulley ``j + 1`` (the last back to the first). Returns ``length_mm`` and
    ``direction`` (unit travel vectors) per span, ``wrap_rad`` per pulley, the tangent points ``start_mm``,
    ``end_mm`` per span and ``closed``: the travel direction turns once round the loop, ``sum(sigma wrap) =
    2 pi`` times the loop's sense (a pulley the belt has left, its wrap through zero, breaks it).

    ``centres_mm`` may carry leading axes (``(..., n, 2)``: many layouts at once, for a sweep of arm angles);
    ``strict=False`` then marks a layout the belt cannot run (no common tangent, or not closed) NaN instead of
    raising. With ``strict`` such a layout is an input error naming the pulleys.
    """
    c = np.asarray(centres_mm, dtype=float)
    r = np.asarray(radii_mm, dtype=float)
    s = np.asarray(sigma, dtype=float)
    rho = s * r
    n = c.shape[-2]
    nxt = (np.arange(n) + 1) % n
    d = c[..., nxt, :] - c
    dist = np.hypot(d[..., 0], d[..., 1])
    drho = rho[nxt] - rho
    no_tangent = np.abs(drho) >= dist
    if strict and no_tangent.any():
        label = names or [f"pulley {i + 1}" for i in range(n)]
        first = np.argwhere(no_tangent.reshape(-1, n))[0][0]  # the first layout with a span that cannot exist
        bad = np.flatnonzero(no_tangent.reshape(-1, n)[first])
        dd = dist.reshape(-1, n)[first]
        raise InputError([Problem(f"pulleys ({label[j]} -> {label[nxt[j]]})", f"{dd[j]:.4g} mm apart",
                                  "pulleys the belt can span: centre distance above the difference of the signed "
                                  f"radii ({abs(drho[j]):.4g} mm here; a pulley inside another, or wrap sides that "
                                  "cross)") for j in bad])
    beta = np.arctan2(d[..., 1], d[..., 0])
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(no_tangent, np.nan, drho / np.where(dist > 0, dist, 1.0))
    a = beta - np.arcsin(ratio)
    u = np.stack([np.cos(a), np.sin(a)], axis=-1)
    left = np.stack([-u[..., 1], u[..., 0]], axis=-1)
    start = c - rho[:, None] * left
    end = c[..., nxt, :] - rho[nxt][:, None] * left
    length = np.sqrt(np.where(no_tangent, np.nan, dist ** 2 - drho ** 2))
    a_in = np.roll(a, 1, axis=-1)  # the span arriving at pulley i is span i - 1
    turn = np.where(s > 0, a - a_in, a_in - a)
    wrap = np.mod(turn, 2.0 * np.pi)
    total = np.sum(s * wrap, axis=-1)
    closed = np.abs(np.abs(total) - 2.0 * np.pi) < 1e-6
    if strict and not np.all(closed):
        label = names or [f"pulley {i + 1}" for i in range(n)]
        raise InputError(Problem("pulleys", ", ".join(label), "a belt path that closes: the belt turns once round "
                                 f"the loop (here {np.degrees(float(np.ravel(total)[0])):.1f} deg instead of "
                                 "360; a pulley the belt no longer touches, or wrap sides that cross)"))
    return {"length_mm": length, "direction": u, "wrap_rad": wrap, "start_mm": start, "end_mm": end,
            "angle_rad": a, "closed": closed}


def effective_length_mm(geometry: dict, effective_radii_mm):
    """Belt length on the effective line: the spans (pitch-line tangents) plus each wrap on its effective radius
    [mm] (broadcasts over the leading axes of :func:`span_geometry`).

    The drive reports measure belt length on the effective line (ISO 9981: the effective diameter of a grooved
    pulley is its outside diameter, a flat backside pulley's is its diameter plus the belt's thickness to that
    line); the pitch line (the cord) sets the tangents and the speed ratios.

    >>> g = span_geometry(np.array([[0.0, 0.0], [100.0, 0.0]]), np.array([10.0, 10.0]), np.array([1.0, 1.0]))
    >>> round(float(effective_length_mm(g, [9.0, 9.0])), 4)  # 2 x 100 + 2 pi 9
    256.5487
    """
    return np.sum(geometry["length_mm"], axis=-1) + np.sum(geometry["wrap_rad"] * np.asarray(effective_radii_mm,
                                                                                               float), axis=-1)


def path_length_mm(centres_mm, radii_mm, sigma) -> float:
    """Whole belt path: spans plus wrapped arcs [mm].

    >>> round(path_length_mm([[0, 0], [100, 0]], [10, 10], [1, 1]), 4)  # 2 x 100 + 2 pi 10
    262.8319
    """
    g = span_geometry(centres_mm, radii_mm, sigma)
    return float(np.sum(g["length_mm"]) + np.sum(np.asarray(radii_mm, float) * g["wrap_rad"]))


def tensioner_centre_mm(pivot_mm, arm_length_mm, arm_angle_rad):
    """Tensioner pulley centre: pivot plus the arm at angle ``phi`` (counter-clockwise from +x) [mm].

    >>> [round(float(v), 6) for v in tensioner_centre_mm([1.0, 2.0], 5.0, np.pi / 2)]
    [1.0, 7.0]
    """
    p = np.asarray(pivot_mm, dtype=float)
    return p + arm_length_mm * np.array([np.cos(arm_angle_rad), np.sin(arm_angle_rad)])


def take_up(direction, tensioner_index: int, arm_length_mm: float, arm_angle_rad: float) -> dict:
    """Span lengthening per radian of arm rotation, by projection [mm/rad].

    ``dL_j/dphi``: ``u_in . dX/dphi`` for the span arriving at the tensioner, ``-u_out . dX/dphi`` for the one
    leaving it, 0 for the others; ``total`` is their sum (the path's derivative). ``sign`` is the arm's
    take-up sense (``+1``: counter-clockwise rotation lengthens the path); the drive's arm coordinate is
    ``psi = sign (phi - phi_nominal)``, so ``sign * dL_j/dphi`` is the take-up per radian of ``psi``.
    """
    u = np.asarray(direction, dtype=float)
    n = len(u)
    dx = arm_length_mm * np.array([-np.sin(arm_angle_rad), np.cos(arm_angle_rad)])
    t = int(tensioner_index)
    g = np.zeros(n)
    g[(t - 1) % n] += float(u[(t - 1) % n] @ dx)
    g[t] += -float(u[t] @ dx)
    total = float(g.sum())
    return {"dl_dphi_mm": g, "total_mm": total, "sign": 1.0 if total >= 0 else -1.0}
