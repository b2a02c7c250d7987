"""A body-fitted mesh about a body of revolution: hexahedra, prisms on the axis, any first-cell y+.

Why: snappyHexMesh cannot keep prism layers thin enough for y+ ~ 1 on SUBOFF's tail cone (the layers
collapse there, see README), so the wall-function set-up could never be compared with a wall-resolved one
on the stern, which carries most of the rotary loads. A body of revolution needs no mesher: this module
places every point itself.

Topology: a structured grid in the meridian half-plane (s metres aft of the nose, rho), revolved about
the axis. Its inner edge runs along the axis from the inlet plane to the nose's tip, over the body's profile
to the tail's tip, and along the axis to the outlet plane. Its lines away from the edge leave along the
edge's normal and curve onto the outer cylinder rho = R_out, with geometric spacing from the wall. Points
on the axis are shared by every angle, so the cells there are prisms (wedges about the axis) and the
body's tips are fans of triangles. A first try with square-section core columns about the axis, in the
usual O-H topology, put cells with a 170-degree corner where the cores met the round body; simpleFoam
diverged there within ten iterations.

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
from ..geometry.suboff import FOOT, MOMENT_CENTRE_FROM_NOSE_M, X_CAP_END, hull_radius
from ..run.openfoam import run_application
from .design import checked_options, friction_velocity
from .interface import sphere_interface_spread
from .polymesh import write_polymesh
from .snappy import (FARFIELD, REPORT_FILE, ROTATING_ZONE, WALL_GROUP, _quality_gate, _write_meshing_controls,
                     reuse_finished_mesh)

# Grid spacings per level, m (along the body, and its points around the axis).
REVOLUTION_LEVELS = {
    "coarse": {"around": 32, "nose": 0.03, "middle": 0.06, "stern": 0.025},
    "medium": {"around": 40, "nose": 0.02, "middle": 0.04, "stern": 0.017},
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

    def __post_init__(self):
        if self.level not in REVOLUTION_LEVELS:
            raise ConfigurationError(f"unknown mesh level {self.level!r} for a body-fitted mesh; choose one of "
                                     f"{', '.join(REVOLUTION_LEVELS)}")
        if not 0.1 <= self.yplus_target <= 300:
            raise ConfigurationError(f"yplus_target {self.yplus_target} is outside 0.1-300")

    @property
    def spacing(self) -> dict:
        return REVOLUTION_LEVELS[self.level]

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


def _nodes(length: float, spacing: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """Node positions on [0, length] whose spacing follows ``spacing(sigma)``."""
    sigma = np.linspace(0.0, length, 20001)
    density = 1.0 / spacing(sigma)
    count = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1]) * np.diff(sigma))])
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


def _offset_from_wall(first: np.ndarray, wall: float, total: np.ndarray, n: int, blend: float = BLEND) -> np.ndarray:
    """Node distances along each eta line: first spacing ``first``, ``total`` in all, ``n`` cells.

    Every line shares one geometric distribution from the wall cell; a line that wants a larger first cell
    (along the axis) is shifted outwards by c (1 - exp(-d / blend)), which stretches only its first few
    cells. Giving each line its own geometric ratio instead would put the nodes of neighbouring lines at
    distances differing in proportion to the distance, and shear the cells far out into non-orthogonality
    wherever the first spacing changes along the edge.
    """
    shift = blend * np.maximum(first / wall - 1.0, 0.0)
    base = _geometric(np.full_like(total, wall), total - shift, n)
    return base + shift[:, None] * (1.0 - np.exp(-base / blend))


@dataclass
class MeridianGrid:
    s: np.ndarray  # (n_xi + 1, n_eta + 1)
    rho: np.ndarray
    nose: int  # xi index of the nose's tip
    tail: int  # xi index of the tail's tip


def meridian_grid(profile: Profile, d: RevolutionDesign) -> MeridianGrid:
    """The 2-D grid in the meridian half-plane, revolved by :func:`revolution_points_and_cells`."""
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
        return np.minimum(target, d.tip_cell + d.growth * np.minimum(g, body_len - g))

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
    # (y+ = 1 still diverges, now on the nose: see README).
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
    n_eta = math.ceil(math.log(1.0 + total.max() * (d.eta_ratio - 1.0) / d.wall_cell) / math.log(d.eta_ratio))
    dists = _offset_from_wall(first, d.wall_cell, total, n_eta)
    s_grid = np.empty((len(s0), n_eta + 1))
    r_grid = np.empty_like(s_grid)
    for i in range(len(s0)):
        s_grid[i] = np.interp(dists[i], arclen[i], curve[i, :, 0])
        r_grid[i] = np.interp(dists[i], arclen[i], curve[i, :, 1])
    s_grid[:, 0], r_grid[:, 0] = s0, r0
    return MeridianGrid(s_grid, r_grid, len(s_up) - 1, len(s_up) + len(s_body) - 2)


# ----------------------------------------------------------------------------------------------------
# The assembly in three dimensions
# ----------------------------------------------------------------------------------------------------
def revolution_points_and_cells(profile: Profile, d: RevolutionDesign, x_of_s: Callable[[np.ndarray], np.ndarray]):
    """Points (body axes), hexahedra as 8 point labels (collapsed on the axis), the hull's points, the shape."""
    grid = meridian_grid(profile, d)
    n_around = d.spacing["around"]
    theta = 2.0 * np.pi * np.arange(n_around) / n_around
    n_xi, n_eta = grid.s.shape[0] - 1, grid.s.shape[1] - 1
    shape3 = (n_xi + 1, n_eta + 1, n_around)
    xyz = np.stack([np.broadcast_to(x_of_s(grid.s)[:, :, None], shape3),
                    grid.rho[:, :, None] * np.cos(theta), grid.rho[:, :, None] * np.sin(theta)], axis=-1)
    # one label per distinct point: those on the axis are shared by every angle
    axis_rows = np.flatnonzero(grid.rho[:, 0] == 0.0)
    keep = np.ones(shape3, dtype=bool)
    keep[axis_rows, 0, 1:] = False
    label = np.full(shape3, -1)
    label[keep] = np.arange(np.count_nonzero(keep))
    label[axis_rows, 0, :] = label[axis_rows, 0, :1]
    points = xyz[keep]

    i, j, k = np.meshgrid(np.arange(n_xi), np.arange(n_eta), np.arange(n_around), indexing="ij")
    k1 = (k + 1) % n_around
    cells = np.stack([label[i, j, k], label[i + 1, j, k], label[i + 1, j, k1], label[i, j, k1],
                      label[i, j + 1, k], label[i + 1, j + 1, k], label[i + 1, j + 1, k1],
                      label[i, j + 1, k1]], axis=-1).reshape(-1, 8)
    hull = np.unique(label[grid.nose: grid.tail + 1, 0])
    shape = {"along": n_xi, "away": n_eta, "around": n_around}
    return points, cells, hull, shape


# ----------------------------------------------------------------------------------------------------
# Building the mesh case
# ----------------------------------------------------------------------------------------------------
# The body-fitted mesher's options: the RevolutionDesign fields a study may set.
REVOLUTION_OPTIONS = ("yplus_target", "sphere_radius_L", "tip_cell", "eta_ratio")


def revolution_options(options: Mapping[str, object], source: str = "mesh options") -> dict[str, float]:
    """The body-fitted mesher's options (a study's [mesh] table without ``mesher``), checked and converted."""
    return checked_options(options, dict.fromkeys(REVOLUTION_OPTIONS, float), source)


def build_revolution_mesh(
    body: Body,
    level: str,
    case: str | Path,
    design_speed: float = 3.344,
    log: Callable[[str], None] = print,
    options: Mapping[str, object] | None = None,
) -> dict:
    """The body-fitted mesh of a SUBOFF bare hull (AFF-1) in ``case``, checked; returns its report."""
    if tuple(body.component_names) != ("hull",) or "AFF-1" not in body.name:
        raise ConfigurationError(f"a body-fitted mesh needs the SUBOFF bare hull (AFF-1), not {body.name} "
                                 f"with {', '.join(body.component_names)}")
    case = Path(case)
    options = {k: v for k, v in (options or {}).items() if k != "mesher"}
    design = RevolutionDesign(level, body.reference.length, design_speed=design_speed,
                              **revolution_options(options))
    wanted = {"mesher": "revolution", **asdict(design)}
    finished = reuse_finished_mesh(case, wanted, log)
    if finished is not None:
        return finished
    t0 = time.monotonic()
    profile = Profile.suboff()
    points, cells, hull_points, shape = revolution_points_and_cells(
        profile, design, lambda s: MOMENT_CENTRE_FROM_NOSE_M - s)
    on_hull = np.zeros(len(points), dtype=bool)
    on_hull[hull_points] = True
    centres = points[cells].mean(axis=1)
    inside = np.linalg.norm(centres, axis=1) < design.sphere_radius  # the moment centre is the origin
    _write_meshing_controls(case)  # checkMesh reads controlDict and the numerics
    counts = write_polymesh(
        case / "constant/polyMesh", points, cells,
        lambda quads: np.where(on_hull[quads].all(axis=1), 1, 0),
        [(FARFIELD, {"type": "patch"}), ("hull", {"type": "wall", "inGroups": f"2({WALL_GROUP} wall)"})],
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
