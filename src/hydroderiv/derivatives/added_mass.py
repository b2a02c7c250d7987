"""The acceleration derivatives (added mass) of a body, estimated from its shape.

Steady captive conditions give the loads that depend on the velocities; a manoeuvring simulation also needs
those that depend on the accelerations (Y'v., Y'r., N'v., N'r., Z'w., Z'q., M'w., M'q., X'u.), which a
planar motion mechanism measures and steady RANS does not give. To a good approximation they are the
inertia of the potential flow the body sets in motion, so they follow from its shape (e.g. Newman,
*Marine Hydrodynamics*, 1977, chapter 4). Here by strip theory (slender-body theory):

1. Each section x = const of the closed surface (hull, and the sail and fins where they stand) is a 2-D
   body; its added mass per unit length, a_yy(x) and a_zz(x), comes from a boundary-element (panel)
   method for the exterior potential flow, phi constant on each straight panel and the panels' influence
   integrated exactly: a_ij = -rho \\oint phi_i n_j ds, where phi_i is the potential of the section moving
   with unit speed in direction i (dphi_i/dn = n_i on the contour, n into the fluid).
   A circle gives rho pi R^2, a circle with two fins of tip radius s moving across them
   rho pi (s^2 - R^2 + R^4/s^2) (Bryson 1954): the tests hold the panel method to both.
2. A section at x moves across its plane with v + r x (sway and yaw; y starboard, r > 0 to starboard) or
   w - q x (heave and pitch; z down, q > 0 nose up). Its added-mass force -a (v. + r. x) summed over the
   length gives

       Y_v. = -\\int a_yy dx     Y_r. = N_v. = -\\int x a_yy dx     N_r. = -\\int x^2 a_yy dx
       Z_w. = -\\int a_zz dx     Z_q. = M_w. = +\\int x a_zz dx     M_q. = -\\int x^2 a_zz dx

   about the moment centre (the body's origin).
3. Strip theory takes each section's flow as two-dimensional, which overstates the added mass near the
   ends, where the flow passes round them too. For a prolate spheroid the exact (three-dimensional) values
   are known in closed form (Lamb 1932, the ellipsoid's inertia coefficients); in translation and in
   rotation the exact potential on the surface is the strip-theory one times a constant, k2 and
   k'(1 + b^2/a^2), with a and b the semi-axes. The strip values are corrected by these factors of the
   spheroid of the body's overall length and volume, as is usual in preliminary design: the translation
   terms by the first, the rotation terms by the second and the coupling terms (Y'r., N'v., Z'q., M'w.) by
   their geometric mean, which keeps the matrix symmetric and positive definite. The correction's size is
   reported: it is this estimate's main uncertainty (for SUBOFF 6 % in translation, 15 % in rotation).
4. X'u. is not a strip-theory quantity (the flow along a slender body is not two-dimensional). It comes from
   a 3-D boundary-element method (:func:`panel_added_mass`) on the body of revolution with the body's
   section areas (:func:`equivalent_body_of_revolution`). The equivalent spheroid's -k1 rho V, the usual
   shortcut, is reported beside it: for SUBOFF, whose parallel middle body and full ends carry more water
   along than a spheroid's, it is 20 % short.

The 3-D method also checks strip theory where it applies, on a body without thin parts: on SUBOFF's bare
hull the corrected strip values of Y'v. and N'r. come within 0.6 and 2.2 % of it (a test asks 2 and 4 %).

5. Roll. A section rolling about the body's axis (y = z = 0) with unit rate has dphi/dn = y n_z - z n_y; its
   added moment of inertia a_pp and its coupling with sway a_yp follow from the same panel method (an
   ellipse gives rho pi (a^2 - b^2)^2 / 8, a circle nothing: a body of revolution is rolled by its fins and
   sail alone). Summed over the length,

       K_p. = -\\int a_pp dx     K_v. = Y_p. = -\\int a_yp dx     K_r. = N_p. = -\\int x a_yp dx

   (the heave-roll coupling vanishes on a body that is its own mirror image port to starboard). The
   spheroid's 3-D factors do not apply to roll, so these are strip theory as it stands, which takes each
   fin's flow as two-dimensional across its whole chord; K'v. and K'r. come from the sail, standing on one
   side of the axis.

Prime system on L (Gertler & Hagen 1967): Y'v. = Y_v. / (0.5 rho L^3), Y'r. = Y_r. / (0.5 rho L^4),
N'r. = N_r. / (0.5 rho L^5), K'p. = K_p. / (0.5 rho L^5), K'v. = K_v. / (0.5 rho L^4).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import GeometryError
from ..geometry import Body
from ..geometry.surfaces import TriSurface, cross_section_areas, cross_section_contours, revolve

# name -> (plane, moment of the section's added mass along x, sign): see the module's equations; the moment
# (0, 1, 2) also says which 3-D correction the term takes (translation, coupling, rotation)
STRIP_TERMS = {
    "Yvdot": ("horizontal", 0, -1.0), "Yrdot": ("horizontal", 1, -1.0), "Nvdot": ("horizontal", 1, -1.0),
    "Nrdot": ("horizontal", 2, -1.0),
    "Zwdot": ("vertical", 0, -1.0), "Zqdot": ("vertical", 1, +1.0), "Mwdot": ("vertical", 1, +1.0),
    "Mqdot": ("vertical", 2, -1.0),
}
# name -> (column of strip_added_mass's sections, moment along x): the roll terms, strip theory as it stands
ROLL_TERMS = {"Kpdot": (2, 0), "Kvdot": (3, 0), "Ypdot": (3, 0), "Krdot": (3, 1), "Npdot": (3, 1)}
# the power of length in each column of strip_added_mass's sections (a_yy, a_zz in m^2, a_pp in m^4, a_yp in
# m^3): a term's moment k along x then has the power 1 + this + k, the power of L that makes it prime
_SECTION_LENGTH_POWER = (2, 2, 4, 3)
_PANELS_PER_SECTION = 480


def _panel_influence(points: np.ndarray, start: np.ndarray, tangent: np.ndarray, normal: np.ndarray,
                     length: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """At ``points``, the integrals over straight panels of G = ln(r) / (2 pi) (the potential of a unit
    source per unit length spread over the panel) and of dG/dn_q, n_q the panel's normal (that of a doublet
    layer, with the sign of Green's identity), both exact. In a panel's own axes the point lies at (xi, eta),
    the panel on eta = 0 from xi = 0 to l:

        \\int G = [F(xi) - F(xi - l)] / (4 pi),  F(s) = s ln(s^2 + eta^2) - 2 s + 2 eta atan(s / eta)
        \\int dG/dn_q = -[atan2(eta, xi - l) - atan2(eta, xi)] / (2 pi)   (the angle the panel subtends)

    A panel's own middle (eta = 0 on it) gets the principal value of the second, zero: set by the caller."""
    offset = points[:, None, :] - start[None, :, :]
    xi = np.einsum("ijk,jk->ij", offset, tangent)
    eta = np.einsum("ijk,jk->ij", offset, normal)
    eta_safe = np.where(eta == 0.0, 1.0, eta)

    def antiderivative(s):
        r2 = s * s + eta * eta
        log_term = np.where(r2 > 0.0, s * np.log(np.where(r2 > 0.0, r2, 1.0)), 0.0)
        return log_term - 2.0 * s + np.where(eta == 0.0, 0.0, 2.0 * eta * np.arctan(s / eta_safe))

    xi_end = xi - length[None, :]
    single_layer = (antiderivative(xi) - antiderivative(xi_end)) / (4.0 * np.pi)
    double_layer = -(np.arctan2(eta, xi_end) - np.arctan2(eta, xi)) / (2.0 * np.pi)
    return single_layer, double_layer


def _panels(contours: list[np.ndarray], n_panels: int) -> tuple[np.ndarray, np.ndarray]:
    """Panel end points (start, end) of the contours, each edge split into as many panels as the total
    perimeter over ``n_panels`` goes into it; the contours' own vertices are kept (fin edges stay sharp)."""
    perimeter = sum(float(np.linalg.norm(np.roll(c, -1, axis=0) - c, axis=1).sum()) for c in contours)
    target = perimeter / n_panels
    starts, ends = [], []
    for contour in contours:
        a, b = contour, np.roll(contour, -1, axis=0)
        pieces = np.maximum(1, np.ceil(np.linalg.norm(b - a, axis=1) / target).astype(int))
        for p, q, k in zip(a, b, pieces):
            # cosine spacing: the flow is singular at a corner (a fin's edge), so the panels crowd there
            fractions = 0.5 * (1.0 - np.cos(np.pi * np.arange(k + 1) / k))[:, None]
            nodes = p + fractions * (q - p)
            starts.append(nodes[:-1])
            ends.append(nodes[1:])
    start, end = np.vstack(starts), np.vstack(ends)
    keep = np.linalg.norm(end - start, axis=1) > 1e-12 * max(perimeter, 1e-300)
    return start[keep], end[keep]


def section_added_mass(contours: list[np.ndarray], n_panels: int = _PANELS_PER_SECTION,
                       with_roll: bool = False) -> np.ndarray:
    """The 2x2 added-mass matrix per unit length and unit density, [[a_yy, a_yz], [a_zy, a_zz]] in m^2, of a
    2-D section whose closed ``contours`` ((n, 2) arrays of (y, z)) turn from +y towards +z (holes the other
    way), as :func:`~hydroderiv.geometry.surfaces.cross_section_contours` gives them. ``with_roll`` adds the
    roll about the origin (y = z = 0) as a third motion: 3x3, a_pp in m^4 and a_yp, a_zp in m^3."""
    size = 3 if with_roll else 2
    contours = [np.asarray(c, dtype=float) for c in contours if len(c) >= 3]
    if not contours:
        return np.zeros((size, size))
    start, end = _panels(contours, n_panels)
    length = np.linalg.norm(end - start, axis=1)
    tangent = (end - start) / length[:, None]
    # the contour turns from +y towards +z, so the body lies to the left of its direction and the fluid to
    # the right: the outward normal (into the fluid) is the tangent turned by -90 degrees
    normal = np.column_stack([tangent[:, 1], -tangent[:, 0]])
    middle = 0.5 * (start + end)
    single_layer, double_layer = _panel_influence(middle, start, tangent, normal, length)
    np.fill_diagonal(double_layer, 0.0)
    # dphi/dn of each unit motion: sway n_y, heave n_z and, rolling about the origin, y n_z - z n_y
    modes = (np.column_stack([normal, middle[:, 0] * normal[:, 1] - middle[:, 1] * normal[:, 0]]) if with_roll
             else normal)
    # Green's identity for the exterior flow at each panel's middle, phi piecewise constant (a direct
    # method: it solves for phi itself, which stays accurate across a thin fin, where a source layer needs
    # panels finer than the fin's thickness to carry the jump in phi from one face to the other):
    #     phi_i / 2 + sum_j phi_j \int_j dG/dn = sum_j (dphi/dn)_j \int_j G
    phi = np.linalg.solve(0.5 * np.eye(len(length)) + double_layer, single_layer @ modes)
    return -(phi * length[:, None]).T @ modes


def strip_added_mass(surface: TriSurface, n_stations: int = 160,
                     n_panels: int = _PANELS_PER_SECTION) -> tuple[np.ndarray, np.ndarray]:
    """Stations x (cosine-spaced, end points included) and each section's a_yy and a_zz (m^2, per unit
    density), a_pp (m^4) and a_yp (m^3, roll about the x axis) of a closed surface in body axes: arrays (n,)
    and (n, 4)."""
    lo, hi = surface.bounds[:, 0]
    if not hi > lo:
        raise GeometryError("the surface has no extent along x")
    # cosine spacing crowds the stations where the sections change fastest, at the nose and the tail
    x = 0.5 * (lo + hi) - 0.5 * (hi - lo) * np.cos(np.pi * np.arange(n_stations + 1) / n_stations)
    sections = np.zeros((len(x), 4))
    for k, contours in enumerate(cross_section_contours(surface, x[1:-1]), start=1):
        matrix = section_added_mass(contours, n_panels, with_roll=True)
        sections[k] = matrix[0, 0], matrix[1, 1], matrix[2, 2], matrix[0, 2]
    return x, sections


def _triangle_self_integral(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    """\\int_T dA / r over each flat triangle from a point inside it, in its plane, exactly: the sum over the
    edges of h ln[(s2 + r2) / (s1 + r1)], with h the point's distance from the edge's line, s1 and s2 the
    edge's ends along it and r1, r2 their distances from the point."""
    total = np.zeros(len(triangles))
    for k in range(3):
        a, b = triangles[:, k], triangles[:, (k + 1) % 3]
        direction = (b - a) / np.linalg.norm(b - a, axis=1)[:, None]
        s1 = np.einsum("ij,ij->i", a - points, direction)
        s2 = np.einsum("ij,ij->i", b - points, direction)
        h = np.linalg.norm((a - points) - s1[:, None] * direction, axis=1)
        total += h * np.log((s2 + np.linalg.norm(b - points, axis=1)) / (s1 + np.linalg.norm(a - points, axis=1)))
    return total


def panel_added_mass(surface: TriSurface, block: int = 1024) -> np.ndarray:
    """The 6x6 added-mass matrix per unit density of a closed surface (translations x, y, z, then rotations
    about x, y, z through the origin) by a 3-D boundary-element method: the direct method of
    :func:`section_added_mass` with G = -1 / (4 pi r), phi constant on each triangle, the neighbours'
    influence taken at their centroids and a panel's own single layer integrated exactly. For a body
    without thin parts (its triangles must be small against its thickness everywhere); it checks strip
    theory and gives the axial added mass, which strip theory cannot."""
    triangles = surface.triangles
    cross = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
    area = 0.5 * np.linalg.norm(cross, axis=1)
    normal = cross / (2.0 * area[:, None])  # outward, into the fluid
    centre = triangles.mean(axis=1)
    n = len(area)
    single_layer, double_layer = np.empty((n, n)), np.empty((n, n))
    for start in range(0, n, block):  # by rows: the pairwise offsets of all panels at once would be n^2 x 3
        rows = slice(start, min(start + block, n))
        offset = centre[rows, None, :] - centre[None, :, :]
        distance = np.linalg.norm(offset, axis=2)
        own = np.arange(rows.start, rows.stop)
        distance[own - start, own] = 1.0
        single_layer[rows] = -area[None, :] / (4.0 * np.pi * distance)
        double_layer[rows] = -np.einsum("ijk,jk->ij", offset, normal) * area[None, :] / (4.0 * np.pi * distance**3)
    np.fill_diagonal(double_layer, 0.0)  # a flat panel does not see its own doublet layer
    single_layer[np.arange(n), np.arange(n)] = -_triangle_self_integral(triangles, centre) / (4.0 * np.pi)
    modes = np.column_stack([normal, np.cross(centre, normal)])  # dphi/dn of each unit motion
    phi = np.linalg.solve(0.5 * np.eye(n) + double_layer, single_layer @ modes)
    return -(phi * area[:, None]).T @ modes


def equivalent_body_of_revolution(surface: TriSurface, n_stations: int = 80, n_around: int = 36) -> TriSurface:
    """The body of revolution with the surface's section areas at each x (radius sqrt(A / pi)): what the
    axial added mass of a slender body depends on, its fins' area spread round the hull."""
    lo, hi = surface.bounds[:, 0]
    x = 0.5 * (lo + hi) - 0.5 * (hi - lo) * np.cos(np.pi * np.arange(n_stations + 1) / n_stations)
    radius = np.zeros_like(x)
    radius[1:-1] = np.sqrt(cross_section_areas(surface, x[1:-1]) / np.pi)
    if np.any(radius[1:-1] <= 0):
        raise GeometryError("the body has a station without a section: it is not one slender body")
    # only its axial added mass is used, so how revolve turns the section plane does not matter
    return revolve(x, radius, n_around)


def spheroid_coefficients(semi_major: float, semi_minor: float) -> dict[str, float]:
    """Lamb's (1932) inertia coefficients of a prolate spheroid (semi-axes a > b = c): k1 (along its axis),
    k2 (across it) and k' (rotation about a minor axis), as fractions of the displaced mass and of the
    displaced water's moment of inertia m (a^2 + b^2) / 5."""
    a, b = float(semi_major), float(semi_minor)
    if not (a > b > 0):
        raise GeometryError(f"a prolate spheroid needs semi-axes a > b > 0, not a = {a}, b = {b}")
    e = np.sqrt(1.0 - (b / a) ** 2)
    log_term = np.log((1.0 + e) / (1.0 - e))
    alpha0 = 2.0 * (1.0 - e * e) / e**3 * (0.5 * log_term - e)
    beta0 = 1.0 / (e * e) - (1.0 - e * e) / (2.0 * e**3) * log_term
    k_rotation = e**4 * (beta0 - alpha0) / ((2.0 - e * e) * (2.0 * e * e - (2.0 - e * e) * (beta0 - alpha0)))
    return {"k1": float(alpha0 / (2.0 - alpha0)), "k2": float(beta0 / (2.0 - beta0)), "k_rotation": float(k_rotation)}


@dataclass(frozen=True)
class AccelerationDerivatives:
    """The acceleration derivatives of a body, estimated from its shape (see the module's docstring).

    ``values``: prime units (Gertler & Hagen 1967) on ``length``, keys Xudot, Yvdot, Yrdot, Nvdot, Nrdot,
    Zwdot, Zqdot, Mwdot, Mqdot and the roll terms Kpdot, Kvdot = Ypdot, Krdot = Npdot (strip theory as it
    stands); ``strip``: the same before the 3-D correction (no Xudot); ``factors``: the
    equivalent spheroid's k1, k2, k', the corrections applied to translation, coupling and rotation, and
    the spheroid's X'u. (``Xudot_spheroid``) beside the one computed."""

    values: dict[str, float]
    strip: dict[str, float]
    factors: dict[str, float]
    length: float
    method: str = field(default="strip theory (2-D boundary elements per section), corrected by the "
                                  "equivalent spheroid's 3-D factors (Lamb 1932); X'u. by 3-D boundary elements "
                                  "on the body of revolution with the same section areas")

    def as_dict(self) -> dict:
        return {"values": dict(self.values), "strip_theory": dict(self.strip), "factors": dict(self.factors),
                "length_m": self.length, "method": self.method}


def acceleration_derivatives(body: Body, n_stations: int = 160,
                             n_panels: int = _PANELS_PER_SECTION) -> AccelerationDerivatives:
    """The acceleration derivatives of ``body`` about its moment centre, in prime units on its L."""
    surface, length = body.surface, body.reference.length
    x, sections = strip_added_mass(surface, n_stations, n_panels)
    moments = np.array([[np.trapezoid(x**k * sections[:, j], x) for j in range(sections.shape[1])] for k in range(3)])
    # the equivalent spheroid: the body's overall length and volume
    lo, hi = surface.bounds[:, 0]
    semi_major = 0.5 * (hi - lo)
    semi_minor = np.sqrt(3.0 * surface.volume / (4.0 * np.pi * semi_major))
    lamb = spheroid_coefficients(semi_major, semi_minor)
    translation = lamb["k2"]  # strip theory gives a spheroid exactly its displaced mass across it
    rotation = float(lamb["k_rotation"] * (1.0 + (semi_minor / semi_major) ** 2))
    correction = (translation, float(np.sqrt(translation * rotation)), rotation)

    def prime(column: int, moment: int) -> float:
        """A column's k-th moment along x in prime units: over 0.5 L^(1 + its sections' power + k), so Y_v.
        over L^3, N_r. and K_p. over L^5, K_v. over L^4."""
        return float(moments[moment, column] / (0.5 * length ** (1 + _SECTION_LENGTH_POWER[column] + moment)))

    strip, values = {}, {}
    for name, (plane, moment, sign) in STRIP_TERMS.items():
        strip[name] = sign * prime(0 if plane == "horizontal" else 1, moment)
        values[name] = strip[name] * correction[moment]
    for name, (column, moment) in ROLL_TERMS.items():
        strip[name] = values[name] = -prime(column, moment)
    axial = panel_added_mass(equivalent_body_of_revolution(surface))[0, 0]
    values = {"Xudot": float(-axial / (0.5 * length**3)), **values}
    factors = {**lamb, "translation": correction[0], "coupling": correction[1], "rotation": correction[2],
               "spheroid_semi_axes_m": [float(semi_major), float(semi_minor)],
               "Xudot_spheroid": float(-lamb["k1"] * surface.volume / (0.5 * length**3))}
    return AccelerationDerivatives(values, strip, factors, float(length))
