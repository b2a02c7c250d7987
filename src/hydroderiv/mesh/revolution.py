"""A body-fitted mesh about a body of revolution, with or without fins: hexahedra, prisms on the axis, any
first-cell y+.

Why: snappyHexMesh cannot keep prism layers thin enough for y+ ~ 1 on SUBOFF's tail cone (the layers
collapse there, see docs/validation.md), so the wall-function set-up could never be compared with a
wall-resolved one on the stern, which carries most of the rotary loads. A body of revolution needs no
mesher: this module places every point itself.

Topology: a structured grid in the meridian half-plane (s metres aft of the nose, rho), revolved about
the axis. Its inner edge runs along the axis from the inlet plane to the nose's tip, over the body's profile
to the tail's tip, and along the axis to the outlet plane. Its lines away from the edge leave along the
edge's normal and curve onto the outer cylinder rho = R_out, with geometric spacing from the wall. Points
on the axis are shared by every angle, so the cells there are prisms (wedges about the axis) and the
body's tips are fans of triangles. A first try with square-section core columns about the axis, in the
usual O-H topology, put cells with a 170-degree corner where the cores met the round body; simpleFoam
diverged there within ten iterations. Fins are slits between sectors of the grid around the axis (see
:func:`revolution_points_and_cells`), so every cell stays a hexahedron that follows hull and fin alike.

The rotating sphere of the hybrid frames is the cellZone of cells whose centre lies within it, and its
border the faceZone of the same name. Unlike the snappy meshes' that border is a staircase, not faces on
the sphere, and MRF's flux through it disturbs the hybrid set-up (README): use the classic one here.
"""

from __future__ import annotations

import json
import math
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Callable, Mapping

import numpy as np

from .._io import atomic_write_text
from ..errors import ConfigurationError
from ..geometry import Body
from ..geometry.suboff import (APPENDAGE_ANGLES, APPENDAGE_TE_X, APPENDAGE_TIP_RADIUS, FOOT, MOMENT_CENTRE_FROM_NOSE_M,
                               X_CAP_END, appendage_chord, appendage_half_thickness, hull_radius)
from ..run.openfoam import run_application
from .design import checked_options, friction_velocity
from .interface import sphere_interface_spread
from .polymesh import write_polymesh
from .snappy import (FARFIELD, REPORT_FILE, ROTATING_ZONE, WALL_GROUP, _quality_gate, _write_meshing_controls,
                     reuse_finished_mesh)

# Grid spacings per level, m (along the body, and its points around the axis). With fins, each sector
# between two fins has ``sector`` cells around, clustered towards the fins with a first step of
# ``fin_first_deg``; ``fin_cell`` is the spacing along the body over the fins, and ``span_cell`` caps the
# spacing away from the wall out to ``span_reach`` (m), so that the fins' span is resolved.
REVOLUTION_LEVELS = {
    "coarse": {"around": 32, "nose": 0.03, "middle": 0.06, "stern": 0.025,
               "sector": 16, "fin_first_deg": 1.0, "fin_cell": 0.007, "fin_edge_cell": 0.0012, "span_cell": 0.014},
    "medium": {"around": 40, "nose": 0.02, "middle": 0.04, "stern": 0.017,
               "sector": 22, "fin_first_deg": 0.8, "fin_cell": 0.0045, "fin_edge_cell": 0.0008, "span_cell": 0.011},
}


@dataclass(frozen=True)
class RevolutionDesign:
    """Everything that sets the body-fitted mesh of a body of revolution at one level."""

    level: str
    length: float  # reference length L, m
    design_speed: float = 3.344
    nu: float = 0.001053 / 998.55
    yplus_target: float = 1.0  # at the first cell centre, at the design speed, from a flat-plate friction law
    sphere_radius_L: float = 2.0
    upstream_L: float = 2.5  # inlet plane ahead of the nose
    downstream_L: float = 3.5  # outlet plane behind the tail
    outer_radius_L: float = 3.0  # the outer cylinder about the axis
    tip_cell: float = 0.005  # spacing along the edge at the body's tips, m
    growth: float = 0.2  # spacing grows by at most this fraction of the distance from a tip
    far_cell_L: float = 0.25  # largest spacing along the axis, in L
    eta_ratio: float = 1.2  # largest geometric ratio away from the wall
    axis_cell: float = 0.03  # m: the first cell off the axis, away from the tips
    axis_shear: float = 0.5  # growth of the first cell along the axis, see meridian_grid
    turn_width: float = 0.3  # m: the eta lines' start directions are smoothed over this length of the edge
    span_reach: float = 0.2  # m: with fins, how far from the wall the spacing stays below span_cell
    sector_cells: int | None = None  # with fins: cells around between two fins (None: the level's)
    fin_first_deg: float | None = None  # with fins: the first step around off a fin (None: the level's)
    span_cell: float | None = None  # m, with fins: the cap on steps away from the wall (None: the level's)

    def __post_init__(self):
        if self.level not in REVOLUTION_LEVELS:
            raise ConfigurationError(f"unknown mesh level {self.level!r} for a body-fitted mesh; choose one of "
                                     f"{', '.join(REVOLUTION_LEVELS)}")
        if not 0.1 <= self.yplus_target <= 300:
            raise ConfigurationError(f"yplus_target {self.yplus_target} is outside 0.1-300")
        if self.fin_first_deg is not None and not 0.01 <= self.fin_first_deg <= 10:
            raise ConfigurationError(f"fin_first_deg {self.fin_first_deg} is outside 0.01-10 degrees")
        if self.span_cell is not None and not 0.001 <= self.span_cell <= 0.1:
            raise ConfigurationError(f"span_cell {self.span_cell} m is outside 0.001-0.1 m")

    @property
    def spacing(self) -> dict:
        """The level's spacings, with the ones a study has set instead."""
        overrides = {"sector": self.sector_cells, "fin_first_deg": self.fin_first_deg, "span_cell": self.span_cell}
        return {**REVOLUTION_LEVELS[self.level], **{k: v for k, v in overrides.items() if v is not None}}

    @property
    def wall_cell(self) -> float:
        """First cell height on the body: twice the distance of its centre at the target y+."""
        return 2.0 * self.yplus_target * self.nu / friction_velocity(self.design_speed, self.length, self.nu)

    @property
    def sphere_radius(self) -> float:
        return self.sphere_radius_L * self.length


# ----------------------------------------------------------------------------------------------------
# The profile
# ----------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Profile:
    """A body of revolution's meridian, dense: s (m aft of the nose) and rho (m), tip to tip."""

    s: np.ndarray
    rho: np.ndarray

    @classmethod
    def suboff(cls) -> Profile:
        # cosine clustering resolves the tips, where the slope is infinite
        t = 0.5 - 0.5 * np.cos(np.linspace(0.0, np.pi, 200001))
        s_ft = X_CAP_END * t
        return cls(s_ft * FOOT, hull_radius(s_ft) * FOOT)

    @property
    def arc(self) -> np.ndarray:
        return np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(self.s), np.diff(self.rho)))])


@dataclass(frozen=True)
class Fins:
    """Identical fins about a body of revolution: their section and where they stand around the axis.

    ``angles_deg`` are the fins' mid-planes in the mesher's angle theta (y = rho cos theta, z = rho sin
    theta, body axes) and ``names`` their patches. Only SUBOFF's four stern appendages are described
    (Groves et al. 1989): NACA 0020-form sections, a chord linear in the distance from the axis and a
    straight trailing edge, out to a flat tip at the hull's largest radius.
    """

    angles_deg: tuple[float, ...]
    names: tuple[str, ...]
    trailing_edge: float  # m aft of the nose
    tip_radius: float  # m from the axis

    @classmethod
    def suboff(cls) -> Fins:
        # APPENDAGE_ANGLES run from top dead centre (-z) towards starboard (+y): theta = angle - 90 degrees
        order = sorted(APPENDAGE_ANGLES, key=lambda name: (APPENDAGE_ANGLES[name] - 90.0) % 360.0)
        return cls(tuple((APPENDAGE_ANGLES[n] - 90.0) % 360.0 for n in order), tuple(order),
                   APPENDAGE_TE_X * FOOT, APPENDAGE_TIP_RADIUS * FOOT)

    def chord(self, y):
        return appendage_chord(np.asarray(y) / FOOT) * FOOT

    def half_thickness(self, s: np.ndarray, y: np.ndarray, span_trim: float = 0.0):
        """Half-thickness (m) at ``s`` m aft of the nose and ``y`` m from the axis; 0 off the fin.

        ``span_trim`` (m) counts as off the fin a strip of that width along the tip (see :meth:`half_angle`).
        """
        c = self.chord(y)
        xi = (s - self.trailing_edge) / c + 1.0
        on = (xi > 0.0) & (xi < 1.0) & (y <= self.tip_radius - span_trim)
        return np.where(on, c * appendage_half_thickness(np.clip(xi, 0.0, 1.0)), 0.0)

    def half_angle(self, s: np.ndarray, rho: np.ndarray, span_step: float) -> np.ndarray:
        """The angle (rad) between a fin's mid-plane and its surface through a point at (s, rho).

        The grid has lines on the edges (see :func:`_align_with_fins`) but not at the tip, where the fin
        runs on to the first point off it, on average half a step too far: points within half a step
        (``span_step``) of the tip count as off, so that on average the grid's span is the fin's. A point
        on an edge is off the fin whatever the rounding.
        """
        angle = np.zeros_like(rho)
        safe = np.maximum(rho, 1e-12)
        for _ in range(3):  # the section is given at the distance y = rho cos(angle) along the mid-plane
            y = rho * np.cos(angle)
            h = self.half_thickness(s, y, span_trim=0.5 * span_step)
            h = np.where(h > 1e-4 * self.chord(y), h, 0.0)
            angle = np.where(rho > 0.0, np.arcsin(np.clip(h / safe, 0.0, 0.9)), 0.0)
        return angle

    def footprint(self) -> tuple[float, float]:
        """A stretch of s (m aft of the nose) holding the fins: from the leading edge that the chord law
        gives on the axis (a little ahead of the root's) to the trailing edge."""
        return self.trailing_edge - float(self.chord(0.0)), self.trailing_edge


def _fin_spacing(fins: Fins, d: RevolutionDesign, s: np.ndarray) -> np.ndarray:
    """Spacing along the body about the fins: ``fin_cell`` over them, growing away from them.

    The eta lines leave the tail cone leaning aft: a margin behind the trailing edge keeps the lines that
    cross the fins' outer parts as close together as those at their roots.
    """
    lo, hi = fins.footprint()
    outside = np.maximum(lo - s, 0.0) + np.maximum(s - hi - 0.02, 0.0)
    return d.spacing["fin_cell"] + d.growth * outside


def _node_count(lo: float, hi: float, spacing: Callable[[np.ndarray], np.ndarray], samples: int):
    """Samples sigma on [lo, hi] and the number of cells of size ``spacing`` up to each (trapezoidal)."""
    sigma = np.linspace(lo, hi, samples)
    density = 1.0 / spacing(sigma)
    return sigma, np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(sigma))])


def _nodes(length: float, spacing: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """Node positions on [0, length] whose spacing follows ``spacing(sigma)``."""
    sigma, count = _node_count(0.0, length, spacing, 20001)
    n = max(2, math.ceil(count[-1]))
    return np.interp(np.linspace(0.0, count[-1], n + 1), count, sigma)


def _geometric(first: np.ndarray, total: np.ndarray, n: int) -> np.ndarray:
    """Distances of n + 1 nodes from 0 to ``total`` with first spacing ``first`` (per line, vectorised)."""
    lo, hi = np.full_like(total, 1.0 + 1e-9), np.full_like(total, 2.0)
    for _ in range(100):  # bisection for the ratio q: first (q^n - 1) / (q - 1) = total
        q = 0.5 * (lo + hi)
        too_long = first * (q**n - 1.0) / (q - 1.0) > total
        hi, lo = np.where(too_long, q, hi), np.where(too_long, lo, q)
    q = 0.5 * (lo + hi)
    k = np.arange(n + 1)
    d = first[:, None] * (q[:, None] ** k - 1.0) / (q[:, None] - 1.0)
    return d * (total / d[:, -1])[:, None]


BLEND = 2e-4  # m: the shift of a line's nodes off the wall fades in over this distance (_offset_from_wall)


def _capped_inner(wall: float, ratio: float, cap: float, reach: float) -> np.ndarray:
    """Node distances from the wall out to ``reach``, shared by every line: steps grow by ``ratio`` up to ``cap``."""
    d, step = [0.0], wall
    while d[-1] < reach:
        d.append(d[-1] + step)
        step = min(step * ratio, cap)
    return np.array(d)


def _offset_from_wall(first: np.ndarray, wall: float, total: np.ndarray, n: int, blend: float = BLEND,
                      inner: np.ndarray | None = None) -> np.ndarray:
    """Node distances along each eta line: first spacing ``first``, ``total`` in all, ``n`` cells.

    Every line shares one geometric distribution from the wall cell; a line that wants a larger first cell
    (along the axis) is shifted outwards by c (1 - exp(-d / blend)), which stretches only its first few
    cells. Giving each line its own geometric ratio instead would put the nodes of neighbouring lines at
    distances differing in proportion to the distance, and shear the cells far out into non-orthogonality
    wherever the first spacing changes along the edge. ``inner`` (from :func:`_capped_inner`) fixes the
    nodes near the wall; the rest grow geometrically from its last step.
    """
    shift = blend * np.maximum(first / wall - 1.0, 0.0)
    if inner is None:
        base = _geometric(np.full_like(total, wall), total - shift, n)
    else:
        m = len(inner) - 1
        outer = _geometric(np.full_like(total, inner[-1] - inner[-2]), total - shift - inner[-1], n - m)
        base = np.concatenate([np.broadcast_to(inner[:-1], (len(total), m)), inner[-1] + outer], axis=1)
    return base + shift[:, None] * (1.0 - np.exp(-base / blend))


@dataclass
class MeridianGrid:
    s: np.ndarray  # (n_xi + 1, n_eta + 1)
    rho: np.ndarray
    nose: int  # xi index of the nose's tip
    tail: int  # xi index of the tail's tip


def meridian_grid(profile: Profile, d: RevolutionDesign, fins: Fins | None = None) -> MeridianGrid:
    """The 2-D grid in the meridian half-plane, revolved by :func:`revolution_points_and_cells`.

    With ``fins`` the spacing along the body is ``fin_cell`` over them, and away from the wall at most
    ``span_cell`` out to ``span_reach``.
    """
    L = d.length
    sp = d.spacing
    arc = profile.arc
    s_in, s_out = -d.upstream_L * L, profile.s[-1] + d.downstream_L * L
    far = d.far_cell_L * L

    def from_tip(sigma, cap):
        return np.minimum(cap, d.tip_cell + d.growth * sigma)

    up = _nodes(-s_in, lambda g: from_tip(g, far))  # along the axis, from the nose's tip forwards
    body_len, length_overall = arc[-1], profile.s[-1]

    def body_spacing(g):
        s = np.interp(g, arc, profile.s)
        target = np.interp(s / length_overall, [0.0, 0.22, 0.32, 0.70, 0.78, 1.0],
                           [sp["nose"], sp["nose"], sp["middle"], sp["middle"], sp["stern"], sp["stern"]])
        target = np.minimum(target, d.tip_cell + d.growth * np.minimum(g, body_len - g))
        return target if fins is None else np.minimum(target, _fin_spacing(fins, d, s))

    along = _nodes(body_len, body_spacing)
    down = _nodes(s_out - length_overall, lambda g: from_tip(g, np.minimum(far, sp["stern"] + d.growth * g)))
    s_up, s_down = -up[::-1], length_overall + down
    s_body, rho_body = np.interp(along, arc, profile.s), np.interp(along, arc, profile.rho)
    rho_body[0] = rho_body[-1] = 0.0
    s0 = np.concatenate([s_up, s_body[1:], s_down[1:]])
    r0 = np.concatenate([np.zeros_like(s_up), rho_body[1:], np.zeros(len(s_down) - 1)])

    # eta lines start along the inner edge's normal, smoothed over ``turn_width``: each tip is a concave
    # right-angled corner of the grid, and lines leaving it along the true normals would cross within a
    # fraction of a millimetre
    ts, tr = np.gradient(s0), np.gradient(r0)
    norm = np.hypot(ts, tr)
    normal = np.column_stack([-tr / norm, ts / norm])
    along_edge = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(s0), np.diff(r0)))])
    weight = np.exp(-0.5 * ((along_edge[:, None] - along_edge[None, :]) / d.turn_width) ** 2)
    normal = weight @ normal
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    normal[0], normal[-1] = (0.0, 1.0), (0.0, 1.0)
    # On the outer cylinder the clustering of the inner edge is spread out: smoothing the spacing (not the
    # positions, which would drag the uniform ends towards the clusters) keeps the lines upright elsewhere.
    top_step = np.convolve(np.pad(np.diff(s0), 30, mode="edge"), np.ones(61) / 61, mode="valid")
    top_s = s0[0] + np.concatenate([[0.0], np.cumsum(top_step)]) * (s0[-1] - s0[0]) / top_step.sum()
    r_out = d.outer_radius_L * L

    # first spacing: the wall cell on the body, growing along the axis away from the tips. The axis is no
    # wall, and cells there as thin as the wall's (17 um at y+ = 1) made simpleFoam blow up behind the tail
    # (y+ = 1 still diverges, now on the nose: see README, mesh).
    # _offset_from_wall shifts a line's nodes by BLEND (first / wall - 1); growing that shift by
    # ``axis_shear`` per metre along the axis keeps neighbouring lines' nodes within that fraction of their
    # spacing, whatever the wall cell.
    dist = np.concatenate([-s_up, np.zeros(len(s_body) - 1), down[1:]])
    grown = d.wall_cell * (1.0 + d.axis_shear * dist / BLEND)
    first = 1.0 / (1.0 / d.axis_cell + 1.0 / grown)  # a smooth cap: a kink shears the cells too
    first = np.where(dist > 0, np.maximum(first, d.wall_cell), d.wall_cell)

    # cubic Bezier: out along the normal for about ``turn_width``, into the outer cylinder at right angles
    p0 = np.column_stack([s0, r0])
    q = np.column_stack([top_s, np.full_like(s0, r_out)])
    reach = np.linalg.norm(q - p0, axis=1)
    p1 = p0 + normal * d.turn_width
    p2 = q - np.column_stack([np.zeros_like(s0), 0.3 * reach])
    t = np.linspace(0.0, 1.0, 4001) ** 3
    b0, b1, b2, b3 = (1 - t) ** 3, 3 * t * (1 - t) ** 2, 3 * t**2 * (1 - t), t**3
    curve = sum(b[None, :, None] * p[:, None] for b, p in ((b0, p0), (b1, p1), (b2, p2), (b3, q)))
    seg = np.linalg.norm(np.diff(curve, axis=1), axis=2)
    arclen = np.concatenate([np.zeros((len(s0), 1)), np.cumsum(seg, axis=1)], axis=1)
    total = arclen[:, -1]
    if fins is None:
        inner, n_inner, step = None, 0, d.wall_cell
        reach = 0.0
    else:
        inner = _capped_inner(d.wall_cell, d.eta_ratio, sp["span_cell"], d.span_reach)
        n_inner, step, reach = len(inner) - 1, inner[-1] - inner[-2], inner[-1]
    n_eta = n_inner + math.ceil(math.log(1.0 + (total.max() - reach) * (d.eta_ratio - 1.0) / step)
                                / math.log(d.eta_ratio))
    dists = _offset_from_wall(first, d.wall_cell, total, n_eta, inner=inner)
    s_grid = np.empty((len(s0), n_eta + 1))
    r_grid = np.empty_like(s_grid)
    for i in range(len(s0)):
        s_grid[i] = np.interp(dists[i], arclen[i], curve[i, :, 0])
        r_grid[i] = np.interp(dists[i], arclen[i], curve[i, :, 1])
    s_grid[:, 0], r_grid[:, 0] = s0, r0
    grid = MeridianGrid(s_grid, r_grid, len(s_up) - 1, len(s_up) + len(s_body) - 2)
    if fins is None:
        return grid
    return _align_with_fins(grid, fins, d, profile, dists[grid.nose])


def _spaced(lo: float, hi: float, n: int, spacing: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """``n`` + 1 nodes from ``lo`` to ``hi`` whose spacing is in proportion to ``spacing(s)``."""
    sigma, count = _node_count(lo, hi, spacing, 2001)
    return np.interp(np.linspace(0.0, count[-1], n + 1), count, sigma)


def _align_with_fins(grid: MeridianGrid, fins: Fins, d: RevolutionDesign, profile: Profile,
                     away: np.ndarray) -> MeridianGrid:
    """Move the nodes about the fins along each eta line so that the fins' edges lie on grid lines.

    The leading edge is swept and would cross the lines; a node up to a step behind it left its rounded
    nose (radius 4.4 % of the chord) a blunt wedge, whose flow separated. Here, within ``span_reach`` of
    the wall, one line runs along the leading edge and one along the trailing edge, and the nodes cluster
    at both (``fin_edge_cell`` at the leading edge, twice that at the trailing edge); further out the lines
    return to their first places. ``away`` is the distance of each eta line from the wall.
    """
    sp = d.spacing
    lo, hi = fins.footprint()
    edge_s = grid.s[:, 0]
    body = np.arange(grid.nose, grid.tail + 1)
    i0 = body[np.searchsorted(edge_s[body], lo - 0.03) - 1]
    i1 = body[np.searchsorted(edge_s[body], hi + 0.04)]
    n_old = i1 - i0
    weight = np.clip(2.0 - away / d.span_reach, 0.0, 1.0)  # 1 out to span_reach, 0 from twice that
    window = slice(i0, i1 + 1)
    curves_s, curves_r = grid.s[window], grid.rho[window]

    def leading_edge(j):
        # the edge's s where the line's distance from the axis gives the chord; the wall's nodes are put
        # on the hull itself (below), the others on the line through the first nodes
        radius = (lambda s_: np.interp(s_, profile.s, profile.rho)) if j == 0 else (
            lambda s_: np.interp(s_, curves_s[:, j], curves_r[:, j]))
        s_le = hi - float(fins.chord(fins.tip_radius))
        for _ in range(30):
            s_le = hi - float(fins.chord(min(float(radius(s_le)), fins.tip_radius)))
        return s_le

    def spacing_about(s_le):
        def spacing(s):
            return np.minimum.reduce([_fin_spacing(fins, d, s), sp["fin_edge_cell"] + d.growth * np.abs(s - s_le),
                                      2.0 * sp["fin_edge_cell"] + d.growth * np.abs(s - hi)])
        return spacing

    # per aligned line: the bounds of its three stretches (ahead of, over and behind the fin) and its spacing
    stretches = {}
    for j in np.flatnonzero(weight > 0.0).tolist():
        s_le = leading_edge(j)
        stretches[j] = ([curves_s[0, j], s_le, hi, curves_s[-1, j]], spacing_about(s_le))
    counts = np.zeros(3, dtype=int)
    for bounds, spacing in stretches.values():  # the most cells any aligned line needs, per stretch
        for n in range(3):
            counts[n] = max(counts[n], math.ceil(_node_count(bounds[n], bounds[n + 1], spacing, 2001)[1][-1]))
    n_new = int(counts.sum())
    new_s = np.empty((n_new + 1, grid.s.shape[1]))
    new_r = np.empty_like(new_s)
    if np.any(np.diff(curves_s, axis=0) <= 0.0):
        raise ConfigurationError("the grid's lines about the fins do not run aft monotonically")
    for j in range(grid.s.shape[1]):
        # the line's first nodes, resampled to the new count, and (near the wall) the aligned ones
        first = np.interp(np.linspace(0.0, n_old, n_new + 1), np.arange(n_old + 1), curves_s[:, j])
        target = first
        if j in stretches:
            bounds, spacing = stretches[j]
            parts = [_spaced(bounds[n], bounds[n + 1], counts[n], spacing) for n in range(3)]
            target = weight[j] * np.concatenate([parts[0], parts[1][1:], parts[2][1:]]) + (1.0 - weight[j]) * first
        arc = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(curves_s[:, j]), np.diff(curves_r[:, j])))])
        at = np.interp(target, curves_s[:, j], arc)
        new_s[:, j] = np.interp(at, arc, curves_s[:, j])
        new_r[:, j] = np.interp(at, arc, curves_r[:, j])
    new_r[:, 0] = np.interp(new_s[:, 0], profile.s, profile.rho)  # on the hull itself, not its chords
    s_all = np.concatenate([grid.s[:i0], new_s, grid.s[i1 + 1:]])
    r_all = np.concatenate([grid.rho[:i0], new_r, grid.rho[i1 + 1:]])
    return MeridianGrid(s_all, r_all, grid.nose, grid.tail + n_new - n_old)


# ----------------------------------------------------------------------------------------------------
# The assembly in three dimensions
# ----------------------------------------------------------------------------------------------------
def _sector_fractions(n: int, first: float) -> np.ndarray:
    """``n`` + 1 fractions from 0 to 1, clustered alike towards both ends with first step ``first``."""
    if n % 2:
        raise ConfigurationError(f"a sector between fins needs an even number of cells, not {n}")
    d = _geometric(np.array([first]), np.array([0.5]), n // 2)[0]
    return np.concatenate([d, 1.0 - d[-2::-1]])


def revolution_points_and_cells(profile: Profile, d: RevolutionDesign, x_of_s: Callable[[np.ndarray], np.ndarray],
                                fins: Fins | None = None):
    """Points (body axes), hexahedra as 8 point labels (collapsed on the axis), surfaces, the grid's shape.

    ``surfaces`` maps "hull" and each fin's name to the labels of its points (a fin's: every point on its
    mid-plane, see below). Around the axis the grid runs in sectors from one fin to the next. A fin is a
    slit: the last line of one sector and the first of the next are both on the fin's mid-plane, and share
    their points wherever the fin has no thickness, so the cells on either side meet there; over the fin
    the two lines part to its two surfaces and the faces between them become the fin's boundary. The
    sections close at the leading and trailing edges; at the flat tip the slit closes over one cell away
    from the wall, so the tip is a narrow wedge of ``span_cell`` height. Without fins there is one sector
    all around, its two ends one line.
    """
    grid = meridian_grid(profile, d, fins)
    sp = d.spacing
    n_xi, n_eta = grid.s.shape[0] - 1, grid.s.shape[1] - 1
    if fins is None:
        starts, widths = np.array([0.0]), np.array([2.0 * np.pi])
        fractions = np.linspace(0.0, 1.0, sp["around"] + 1)
        half = np.zeros_like(grid.rho)
    else:
        starts = np.radians(np.asarray(fins.angles_deg))
        widths = np.diff(np.append(starts, starts[0] + 2.0 * np.pi))
        fractions = _sector_fractions(sp["sector"], math.radians(sp["fin_first_deg"]) / widths.min())
        half = fins.half_angle(grid.s, grid.rho, sp["span_cell"])
    n_sectors, m = len(starts), len(fractions) - 1
    a = half[:, :, None, None]
    theta = starts[None, None, :, None] + a + (widths[None, None, :, None] - 2.0 * a) * fractions
    rho = grid.rho[:, :, None, None]
    x = np.broadcast_to(x_of_s(grid.s)[:, :, None, None], theta.shape)
    xyz = np.stack([x, rho * np.cos(theta), rho * np.sin(theta)], axis=-1).reshape(-1, 3)

    # one label per distinct point: a sector's last line is the next one's first off the fins, and the
    # points on the axis are shared by every angle
    label = np.arange(theta.size).reshape(theta.shape)
    closed = half == 0.0
    for sector in range(n_sectors):
        following = (sector + 1) % n_sectors
        label[:, :, sector, m] = np.where(closed, label[:, :, following, 0], label[:, :, sector, m])
    axis_rows = np.flatnonzero(grid.rho[:, 0] == 0.0)
    label[axis_rows, 0] = label[axis_rows, 0, 0, 0][:, None, None]
    distinct, label = np.unique(label, return_inverse=True)
    label = label.reshape(theta.shape)
    points = xyz[distinct]

    i, j, sector, t = np.meshgrid(np.arange(n_xi), np.arange(n_eta), np.arange(n_sectors), np.arange(m), indexing="ij")
    cells = np.stack([label[i, j, sector, t], label[i + 1, j, sector, t], label[i + 1, j, sector, t + 1],
                      label[i, j, sector, t + 1], label[i, j + 1, sector, t], label[i + 1, j + 1, sector, t],
                      label[i + 1, j + 1, sector, t + 1], label[i, j + 1, sector, t + 1]], axis=-1).reshape(-1, 8)
    surfaces = {"hull": np.unique(label[grid.nose: grid.tail + 1, 0])}
    for n, name in enumerate(fins.names if fins is not None else ()):
        surfaces[name] = np.unique(np.concatenate([label[:, :, n, 0].ravel(), label[:, :, n - 1, m].ravel()]))
    shape = {"along": n_xi, "away": n_eta, "around": n_sectors * m}
    return points, cells, surfaces, shape


def classify_boundary_faces(quads: np.ndarray, surfaces: dict[str, np.ndarray], n_points: int) -> np.ndarray:
    """Index into ["farfield", *surfaces] of each boundary face: the first surface holding all its points.

    A fin's point set is its whole mid-plane, but the only boundary faces lying wholly in it are the fin's:
    the rest of the plane is inside the fluid.
    """
    names = [name for name in surfaces if name != "hull"] + ["hull"]
    patch = np.zeros(len(quads), dtype=int)
    for name in names:
        on = np.zeros(n_points, dtype=bool)
        on[surfaces[name]] = True
        wholly = on[quads].all(axis=1) & (patch == 0)
        patch[wholly] = 1 + list(surfaces).index(name)
    return patch


# ----------------------------------------------------------------------------------------------------
# Building the mesh case
# ----------------------------------------------------------------------------------------------------
# The body-fitted mesher's options: the RevolutionDesign fields a study may set.
REVOLUTION_OPTIONS = {"yplus_target": float, "sphere_radius_L": float, "tip_cell": float, "eta_ratio": float,
                      "sector_cells": int, "fin_first_deg": float, "span_cell": float}


def revolution_options(options: Mapping[str, object], source: str = "mesh options") -> dict[str, float]:
    """The body-fitted mesher's options (a study's [mesh] table without ``mesher``), checked and converted."""
    return checked_options(options, REVOLUTION_OPTIONS, source)


def build_revolution_mesh(
    body: Body,
    level: str,
    case: str | Path,
    design_speed: float = 3.344,
    log: Callable[[str], None] = print,
    options: Mapping[str, object] | None = None,
) -> dict:
    """The body-fitted mesh of SUBOFF's bare hull (AFF-1) or hull with stern appendages (AFF-3) in ``case``,
    checked; returns its report."""
    names = tuple(body.component_names)
    if "SUBOFF" not in body.name or names not in (("hull",), ("hull", *APPENDAGE_ANGLES)):
        raise ConfigurationError(f"a body-fitted mesh needs SUBOFF's bare hull (AFF-1) or hull with stern "
                                 f"appendages (AFF-3), not {body.name} with {', '.join(names)}")
    fins = None if names == ("hull",) else Fins.suboff()
    case = Path(case)
    options = {k: v for k, v in (options or {}).items() if k != "mesher"}
    design = RevolutionDesign(level, body.reference.length, design_speed=design_speed,
                              **revolution_options(options))
    wanted = {"mesher": "revolution", **asdict(design), "fins": list(fins.names) if fins else []}
    finished = reuse_finished_mesh(case, wanted, log)
    if finished is not None:
        return finished
    t0 = time.monotonic()
    profile = Profile.suboff()
    points, cells, surfaces, shape = revolution_points_and_cells(
        profile, design, lambda s: MOMENT_CENTRE_FROM_NOSE_M - s, fins)
    centres = points[cells].mean(axis=1)
    inside = np.linalg.norm(centres, axis=1) < design.sphere_radius  # the moment centre is the origin
    _write_meshing_controls(case)  # checkMesh reads controlDict and the numerics
    wall = {"type": "wall", "inGroups": f"2({WALL_GROUP} wall)"}
    counts = write_polymesh(
        case / "constant/polyMesh", points, cells,
        lambda quads: classify_boundary_faces(quads, surfaces, len(points)),
        [(FARFIELD, {"type": "patch"}), *((name, wall) for name in surfaces)],
        cell_zone=(ROTATING_ZONE, inside))
    log(f"  body-fitted mesh: {counts['cells']} cells ({shape['along']} along, {shape['away']} away, "
        f"{shape['around']} around), written in {time.monotonic() - t0:.0f} s")
    run_application(case, ["checkMesh", "-constant"], log_name="checkMesh")
    check = _quality_gate(case, log)
    report = {
        "level": level,
        "mesher": "revolution",
        "cells": check["cells"],
        "checkMesh": check,
        "meshing_seconds": round(time.monotonic() - t0, 1),
        "grid": shape,
        "first_cell_m": design.wall_cell,
        "design_yplus": {"speed_m_s": design_speed, "first_cell_centre": design.yplus_target},
        "rotating_sphere": {"radius_m": design.sphere_radius, "zone_cells": counts["zone_cells"],
                            "interface_on_sphere": False,
                            **sphere_interface_spread(case, design.sphere_radius, ROTATING_ZONE)},
        "layer_coverage": {},
        "components": list(body.component_names),
        "design": wanted,
    }
    atomic_write_text(case / REPORT_FILE, json.dumps(report, indent=2) + "\n")
    return report
