"""DARPA SUBOFF (DTRC model 5470) geometry from its defining equations.

Source: Groves, N.C., Huang, T.T. and Chang, M.S., "Geometric Characteristics of DARPA SUBOFF Models
(DTRC Model Nos. 5470 and 5471)", DTRC/SHD-1298-01, David Taylor Research Center, March 1989.

The equations are written as in the report: lengths in FEET, ``x`` measured aft from the nose along the
hull axis. :func:`suboff_body` converts the surfaces to metres and to the body axes of the captive tests
(Roddy 1990): origin at the moment centre 2.013 m aft of the nose, x forward, y starboard, z down.
"""

from __future__ import annotations

import numpy as np

from ..errors import ConfigurationError
from .body import Body, ReferenceQuantities
from .surfaces import TriSurface, loft, revolve, union_components

FOOT = 0.3048  # m

# Principal dimensions (ft), Groves et al. (1989).
R_MAX = 5.0 / 6.0
X_FOREBODY_END = 3.333333
X_PARALLEL_END = 10.645833
X_AFTERBODY_END = 13.979167  # aft perpendicular
X_CAP_END = 14.291667  # tail of the afterbody cap (overall length)

L_PP_M = 4.261  # length between perpendiculars used for the prime system (Roddy 1990)
MOMENT_CENTRE_FROM_NOSE_M = 2.013  # Roddy (1990): moment centre on the axis, 2.013 m aft of the nose

# Sail (fairwater), Groves et al. (1989): x in ft along the axis, height above the axis, half-thickness.
SAIL_X_LE = 3.032986
SAIL_X_FORE_END = 3.358507
SAIL_X_PARALLEL_END = 3.559028
SAIL_X_TE = 4.241319
SAIL_Z_MAX = 0.109375
SAIL_CAP_BASE = 1.507813  # the uniform section runs from the hull to this height

# Stern appendages, Groves et al. (1989).
APPENDAGE_TE_X = 13.146284  # trailing edge, baseline position
APPENDAGE_TIP_RADIUS = R_MAX  # each appendage runs out to the maximum hull radius
APPENDAGE_ANGLES = {  # angle around the axis, from top dead centre towards starboard
    "appendage_top": 0.0,
    "appendage_starboard": 90.0,
    "appendage_bottom": 180.0,
    "appendage_port": 270.0,
}

CONFIGURATIONS = {
    "AFF-1": ("hull",),
    "AFF-2": ("hull", "sail"),
    "AFF-3": ("hull", *APPENDAGE_ANGLES),
    "AFF-8": ("hull", "sail", *APPENDAGE_ANGLES),
}
CONFIGURATION_TITLES = {
    "AFF-1": "bare hull",
    "AFF-2": "hull + sail",
    "AFF-3": "hull + four stern appendages",
    "AFF-8": "fully appended: hull + sail + four stern appendages",
}


# ----------------------------------------------------------------------------------------------------
# Hull
# ----------------------------------------------------------------------------------------------------
def _bow_radius(x):
    a = 0.3 * x - 1.0
    inner = 1.126395101 * x * a**4 + 0.442874707 * x**2 * a**3 + 1.0 - a**4 * (1.2 * x + 1.0)
    return R_MAX * np.maximum(inner, 0.0) ** (1.0 / 2.1)


def _afterbody_radius(x):
    xi = (X_AFTERBODY_END - x) / 3.333333
    rh, k0, k1 = 0.1175, 10.0, 44.6244
    inner = (
        rh**2
        + rh * k0 * xi**2
        + (20 - 20 * rh**2 - 4 * rh * k0 - k1 / 3) * xi**3
        + (-45 + 45 * rh**2 + 6 * rh * k0 + k1) * xi**4
        + (36 - 36 * rh**2 - 4 * rh * k0 - k1) * xi**5
        + (-10 + 10 * rh**2 + rh * k0 + k1 / 3) * xi**6
    )
    return R_MAX * np.sqrt(np.maximum(inner, 0.0))


def _cap_radius(x):
    return 0.1175 * R_MAX * np.sqrt(np.maximum(1.0 - (3.2 * x - 44.733333) ** 2, 0.0))


def hull_radius(x_ft):
    """Hull radius (ft) at ``x_ft`` (ft aft of the nose), piecewise as in Groves et al. (1989)."""
    x = np.clip(np.asarray(x_ft, dtype=float), 0.0, X_CAP_END)
    return np.select(
        [x < X_FOREBODY_END, x < X_PARALLEL_END, x < X_AFTERBODY_END],
        [_bow_radius(x), np.full_like(x, R_MAX), _afterbody_radius(x)],
        default=_cap_radius(x),
    )


def hull_meridian(resolution_ft: float, max_turn_deg: float = 4.0):
    """Stations (x, R) in ft along the hull profile, nose and tail tip included.

    Spacing is at most ``resolution_ft`` along the arc, and finer where the profile curves so that the
    tangent turns by at most ``max_turn_deg`` between stations (the nose and the tail cap need this).
    The segment joins are always stations, so the radius there is exact.
    """
    joins = [0.0, X_FOREBODY_END, X_PARALLEL_END, X_AFTERBODY_END, X_CAP_END]
    dense = []
    for a, b in zip(joins[:-1], joins[1:]):
        # Cosine clustering resolves the infinite slopes at the nose and at the tip of the tail cap.
        t = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, 4001))
        dense.append(a + (b - a) * t[:-1])
    x = np.concatenate([*dense, [X_CAP_END]])
    r = hull_radius(x)
    ds = np.hypot(np.diff(x), np.diff(r))
    heading = np.arctan2(np.diff(r), np.diff(x))
    turn = np.abs(np.diff(heading, prepend=heading[0]))
    # Cost per dense segment: one unit per `resolution` of arc, one per `max_turn` of tangent rotation.
    cost = np.concatenate([[0.0], np.cumsum(ds / resolution_ft + turn / np.radians(max_turn_deg))])
    stations = {0, len(x) - 1}
    for j in joins[1:-1]:
        stations.add(int(np.argmin(np.abs(x - j))))
    cuts = sorted(stations)
    chosen = []
    for i0, i1 in zip(cuts[:-1], cuts[1:]):
        n = max(1, int(np.ceil((cost[i1] - cost[i0]) - 1e-9)))
        targets = np.linspace(cost[i0], cost[i1], n + 1)
        idx = np.searchsorted(cost[i0 : i1 + 1], targets) + i0
        chosen.extend(idx[:-1].tolist())
    chosen.append(len(x) - 1)
    idx = np.unique(chosen)
    xs, rs = x[idx], r[idx]
    # The printed constants of the cap make it close a hair before X_CAP_END; keep only true interior stations.
    interior = rs[1:-1] > 1e-6 * R_MAX
    xs = np.concatenate([[xs[0]], xs[1:-1][interior], [xs[-1]]])
    rs = np.concatenate([[0.0], rs[1:-1][interior], [0.0]])
    return xs, rs


# ----------------------------------------------------------------------------------------------------
# Sail
# ----------------------------------------------------------------------------------------------------
def sail_half_thickness(x_ft):
    """Half-thickness z1 (ft) of the sail section at ``x_ft`` (ft aft of the nose)."""
    x = np.asarray(x_ft, dtype=float)
    d = 3.072000 * (x - SAIL_X_LE)
    a = 2.0 * d * (d - 1.0) ** 4
    b = (1.0 / 3.0) * d**2 * (d - 1.0) ** 3
    c = 1.0 - (d - 1.0) ** 4 * (4.0 * d + 1.0)
    fore = SAIL_Z_MAX * np.sqrt(np.maximum(2.094759 * a + 0.2071781 * b + c, 0.0))
    e = (SAIL_X_TE - x) / 0.6822917
    aft = SAIL_Z_MAX * (
        2.238361 * e * (e - 1.0) ** 4 + 3.106529 * e**2 * (e - 1.0) ** 3 + 1.0 - (e - 1.0) ** 4 * (4.0 * e + 1.0)
    )
    z = np.select([x < SAIL_X_FORE_END, x <= SAIL_X_PARALLEL_END], [fore, np.full_like(x, SAIL_Z_MAX)], default=aft)
    return np.where((x < SAIL_X_LE) | (x > SAIL_X_TE), 0.0, np.maximum(z, 0.0))


def _chord_stations(n: int, lo: float = 0.0, hi: float = 1.0):
    """n+1 chordwise fractions between lo and hi, clustered at both ends (leading and trailing edge)."""
    t = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, n + 1))
    return lo + (hi - lo) * t


def sail_surface(resolution_ft: float) -> TriSurface:
    """Closed sail surface in report coordinates (x aft, height up, thickness), in ft.

    Built as a loft along x of cross-sections in the (height, thickness) plane: straight sides from
    inside the hull up to the cap base, then the elliptic cap. The root starts well inside the hull so
    that the union with the hull closes the junction without a gap.
    """
    root_height = 0.6  # ft; inside the hull everywhere under the sail (hull radius there >= 0.82 ft)
    chord = SAIL_X_TE - SAIL_X_LE
    n_chord = max(24, int(np.ceil(1.6 * chord / resolution_ft)))
    # The section is zero-thick at both edges; stop a hair short so every loft ring is a true polygon.
    xs = SAIL_X_LE + chord * _chord_stations(n_chord, 2e-4, 1.0 - 2e-4)
    n_side = max(4, int(np.ceil((SAIL_CAP_BASE - root_height) / resolution_ft)))
    n_cap = 16
    rings = []
    for x in xs:
        z1 = float(sail_half_thickness(x))
        h_side = np.linspace(root_height, SAIL_CAP_BASE, n_side + 1)
        phi = np.linspace(np.pi, 0.0, n_cap + 1)[1:-1]
        cap_h = SAIL_CAP_BASE + 0.5 * z1 * np.sin(phi)
        cap_t = z1 * np.cos(phi)
        heights = np.concatenate([h_side, cap_h, h_side[::-1]])
        thick = np.concatenate([np.full(n_side + 1, -z1), cap_t, np.full(n_side + 1, z1)])
        rings.append(np.column_stack([np.full_like(heights, x), heights, thick]))
    return loft(rings)


# ----------------------------------------------------------------------------------------------------
# Stern appendages
# ----------------------------------------------------------------------------------------------------
def appendage_chord(radius_ft):
    """Chord (ft) of a stern appendage at radial distance ``radius_ft`` from the hull axis."""
    return -0.466308 * np.asarray(radius_ft, dtype=float) + 0.88859


def appendage_half_thickness(xi):
    """NACA 0020-form half-thickness over chord at chordwise fraction xi (closed trailing edge)."""
    xi = np.asarray(xi, dtype=float)
    return 0.29690 * np.sqrt(xi) - 0.12600 * xi - 0.35160 * xi**2 + 0.28520 * xi**3 - 0.10450 * xi**4


def appendage_surface(resolution_ft: float) -> TriSurface:
    """One closed stern appendage in report coordinates (x aft, radial distance, thickness), in ft.

    Lofted spanwise through NACA 0020-form sections whose chord follows the linear chord law, with the
    trailing edge at the baseline station. The root starts inside the hull; the tip is flat at R_max.
    """
    root_radius = 0.18  # ft; inside the hull over the whole root chord (hull radius >= 0.271 ft there)
    n_chord = max(24, int(np.ceil(1.6 * appendage_chord(root_radius) / resolution_ft)))
    xi = _chord_stations(n_chord)
    n_span = max(6, int(np.ceil((APPENDAGE_TIP_RADIUS - root_radius) / resolution_ft)))
    rings = []
    for y in np.linspace(root_radius, APPENDAGE_TIP_RADIUS, n_span + 1):
        c = float(appendage_chord(y))
        x = APPENDAGE_TE_X + (xi - 1.0) * c
        t = c * appendage_half_thickness(xi)
        # Around the section: trailing edge -> leading edge on one side, back on the other.
        ring_x = np.concatenate([x[::-1], x[1:-1]])
        ring_t = np.concatenate([t[::-1], -t[1:-1]])
        rings.append(np.column_stack([ring_x, np.full_like(ring_x, y), ring_t]))
    return loft(rings)


# ----------------------------------------------------------------------------------------------------
# Assembly in body axes
# ----------------------------------------------------------------------------------------------------
def _to_body_axes(points_ft: np.ndarray, around_axis_deg: float) -> np.ndarray:
    """Map report coordinates (x aft, radial 'up' distance, thickness) in ft to body axes in metres.

    The component is first placed on top dead centre (radial distance = height above the axis, i.e. -z in
    body axes, thickness along +y), then rotated about the x axis by ``around_axis_deg`` from the top
    towards starboard.
    """
    x_aft, radial, thick = points_ft.T * FOOT
    x = MOMENT_CENTRE_FROM_NOSE_M - x_aft
    y0, z0 = thick, -radial
    a = np.radians(around_axis_deg)
    # Rotating the top (0, -1) towards starboard (+1, 0): y = y0 cos a - z0 sin a, z = y0 sin a + z0 cos a.
    y = y0 * np.cos(a) - z0 * np.sin(a)
    z = y0 * np.sin(a) + z0 * np.cos(a)
    return np.column_stack([x, y, z])


def suboff_body(config: str = "AFF-8", resolution: float = 0.02) -> Body:
    """A SUBOFF configuration (AFF-1, AFF-2, AFF-3 or AFF-8) as a :class:`Body` in body axes, metres.

    ``resolution`` is the target edge length of the surface triangulation in metres. The components are
    united into one watertight surface; each triangle keeps the name of the component it came from.
    """
    key = config.strip().upper()
    if key not in CONFIGURATIONS:
        raise ConfigurationError(f"unknown SUBOFF configuration {config!r}; choose one of {', '.join(CONFIGURATIONS)}")
    if not (0.001 <= resolution <= 0.1):
        raise ConfigurationError(f"surface resolution {resolution} m is outside the sensible range 0.001-0.1 m")
    res_ft = resolution / FOOT

    xs, rs = hull_meridian(res_ft)
    hull = revolve(xs, rs, n_around=max(24, int(np.ceil(2 * np.pi * R_MAX / res_ft))))
    parts = {"hull": hull.transformed(lambda p: _to_body_axes(p, 0.0))}
    if "sail" in CONFIGURATIONS[key]:
        parts["sail"] = sail_surface(res_ft / 2).transformed(lambda p: _to_body_axes(p, 0.0))
    if "appendage_top" in CONFIGURATIONS[key]:
        fin = appendage_surface(res_ft / 2)
        for name, angle in APPENDAGE_ANGLES.items():
            parts[name] = fin.transformed(lambda p, a=angle: _to_body_axes(p, a))
    surface, components = union_components(parts)

    reference = ReferenceQuantities(
        length=L_PP_M,
        moment_centre=(MOMENT_CENTRE_FROM_NOSE_M, 0.0, 0.0),
        moment_centre_frame="metres aft of the nose, on the hull axis",
        volume=surface.volume,
        wetted_area=surface.area,
        max_diameter=2 * R_MAX * FOOT,
    )
    return Body(
        name=f"SUBOFF {key}",
        surface=surface,
        component_names=tuple(parts),
        face_component=components,
        reference=reference,
    )
