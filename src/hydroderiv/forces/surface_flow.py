"""Flow at the wall: where the boundary layer runs back, and where the first cell leaves the wall law.

Reversed flow: the share of each body part's wetted area where the boundary layer runs back.

The wall shear stress gives the direction of the flow next to the wall. Where that flow runs against the
stream the body meets, the boundary layer has separated into a closed bubble: behind a blunt tail, or in
the corner where a sail or fin meets the hull. Linear eddy-viscosity models are least trustworthy there
(k-omega SST is known to make junction corner separations too large), and a bubble that sits on one side
of a symmetric body at zero incidence is a load the experiment will not show. So every condition reports
this share per part, beside its forces.

Open cross-flow separation on the lee side of a body at incidence is not counted: there the flow at the
wall still runs aft, only turned sideways.

y+ along the body: the first cell's y+ in slices along x (yplus_along_x), because the patch-wide mean hides
the regions, such as a tail cone without prism layers, where a wall-function mesh is out of its range. Each
slice gives OpenFOAM's y+ and the one from the wall shear stress: on a nutkWallFunction wall OpenFOAM's is
based on k, which reads ten times too low where the first cell sits in a resolved viscous sublayer.

Loads along the body: each part's side and vertical force in slices along x (loads_along_x), because a part's
total hides where it arises: a fin's lift belongs to its fore half, and a fin whose aft half pulls the other
way has lost it to its own boundary layer.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np
from foamlib import FoamFieldFile

from ..errors import HydroderivError
from ..mesh.quality import slices_along_x
from .coefficients import PrimeScales

FIELD = "wallShearStress"  # written by OpenFOAM's wallShearStress function object (see case/setup.py)
YPLUS_FIELD = "yPlus"  # written by OpenFOAM's yPlus function object
TURBULENCE_ENERGY_FIELD = "k"
EDDY_VISCOSITY_FIELD = "nut"
# Wall laws whose y+ (as OpenFOAM's yPlus function object reports it) is C_mu^0.25 k_P^0.5 y_P / nu, with k_P
# the turbulence energy of the first cell; the other wall conditions report y_P u_tau / nu.
K_BASED_WALL_LAWS = ("nutkWallFunction",)
DEFAULT_CMU = 0.09  # the wall functions' default C_mu
PRESSURE_FIELD = "p"  # simpleFoam's kinematic pressure, p / rho
# Above this y+ the first cell centre lies beyond the logarithmic layer that wall functions assume.
LOG_LAYER_TOP = 300.0


WallFaces = dict[str, tuple[np.ndarray, np.ndarray]]  # per patch: face centres and area vectors (patch_faces)


def _field_file(time_dir: str | Path, field: str, what: str) -> FoamFieldFile:
    path = Path(time_dir) / field
    if not path.is_file():
        raise HydroderivError(f"{path} is missing: the run wrote no {what}")
    return FoamFieldFile(path)


def _patch_values(file: FoamFieldFile, patch: str, n_faces: int, n_components: int) -> np.ndarray:
    """A field's values on one patch, (n_faces,) or (n_faces, n_components), a uniform value repeated."""
    values = np.asarray(file.boundary_field[patch]["value"], dtype=float)
    shape = (n_faces,) if n_components == 1 else (n_faces, n_components)
    if values.size not in (n_components, n_faces * n_components):
        raise HydroderivError(f"{file.path}: {values.size // n_components} values on {patch}, but the mesh has "
                              f"{n_faces} faces")
    return np.broadcast_to(values.reshape(-1, n_components).squeeze(-1) if n_components == 1
                           else values.reshape(-1, n_components), shape)


def reversed_flow(
    time_dir: str | Path, faces: WallFaces, inflow: np.ndarray, angular_velocity: np.ndarray = np.zeros(3),
) -> dict[str, dict]:
    """Per patch of ``faces``: wetted area (m^2) and the % of it where the flow at the wall runs against the
    stream.

    ``time_dir`` holds the wall shear stress field; ``faces`` the patches' faces, as read by patch_faces;
    ``inflow`` is U_inf and ``angular_velocity`` Omega, both in body axes. The body meets the stream
    U_inf - Omega x r at r (the same in the hybrid and the classic frames). OpenFOAM's wall shear stress is
    the stress the wall puts on the fluid, so it points against the flow next to the wall: the flow runs
    back where it has a positive component along that stream.
    """
    shear_file = _field_file(time_dir, FIELD, "wall shear stress")
    out = {}
    for patch, (centres, areas) in faces.items():
        shear = _patch_values(shear_file, patch, len(areas), 3)
        stream = np.asarray(inflow, dtype=float) - np.cross(np.asarray(angular_velocity, dtype=float), centres)
        back = np.einsum("ij,ij->i", shear, stream) > 0.0
        area = np.linalg.norm(areas, axis=1)
        total = float(area.sum())
        out[patch] = {
            "area_m2": round(total, 6),
            "reversed_pct": round(100.0 * float(area[back].sum()) / total, 3) if total > 0 else 0.0,
        }
    return out


def friction_yplus(time_dir: str | Path, patch: str, yplus: np.ndarray, owners: np.ndarray) -> np.ndarray | None:
    """The first cell's y+ on ``patch`` from the wall shear stress, y_P u_tau / nu with u_tau = |tau_w|^0.5,
    given OpenFOAM's ``yplus`` there and the cells next to the faces (``owners``); None without the fields.

    On a nutkWallFunction wall OpenFOAM reports C_mu^0.25 k_P^0.5 y_P / nu: the friction velocity a log layer
    in equilibrium would have. In a resolved sublayer k_P falls as y^2, so that reads about 0.1 where the first
    cell centre is at y+ 1. The distance y_P / nu is recovered from it, so no cell centres are needed:
    y+ = yplus |tau_w|^0.5 / (C_mu^0.25 k_P^0.5). Other wall conditions already report y_P u_tau / nu.
    """
    time_dir = Path(time_dir)
    if not (time_dir / FIELD).is_file() or not (time_dir / EDDY_VISCOSITY_FIELD).is_file():
        return None
    wall = FoamFieldFile(time_dir / EDDY_VISCOSITY_FIELD).boundary_field[patch]
    if wall.get("type") not in K_BASED_WALL_LAWS:
        return np.asarray(yplus, dtype=float)
    if not (time_dir / TURBULENCE_ENERGY_FIELD).is_file():
        return None
    shear = _patch_values(_field_file(time_dir, FIELD, "wall shear stress"), patch, len(yplus), 3)
    k = np.asarray(_field_file(time_dir, TURBULENCE_ENERGY_FIELD, "turbulence energy").internal_field, dtype=float)
    k_cell = k[owners] if k.ndim else np.full(len(owners), float(k))
    cmu = float(wall.get("Cmu", DEFAULT_CMU))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.sqrt(np.linalg.norm(shear, axis=1)) / (cmu**0.25 * np.sqrt(k_cell))
    # a cell with no turbulence energy left gives no distance: keep OpenFOAM's value there
    return np.where(k_cell > 0.0, yplus * ratio, yplus)


def yplus_along_x(time_dir: str | Path, faces: WallFaces, patch: str, bins: int = 8,
                  owners: np.ndarray | None = None) -> list[dict]:
    """First-cell y+ on one patch of ``faces`` in ``bins`` equal slices of its length along x, aft to fore.

    The patch-wide mean hides where the wall treatment leaves its range: on the medium AFF-8 hull it is 123,
    but 120-520 over the tail cone, where snappy drops the prism layers and the first cells are the hull's
    own surface cells. Each slice: its x range (m), faces, the area-weighted mean and the largest y+ as
    OpenFOAM reports it, and the % of its area above LOG_LAYER_TOP; given the cells next to the faces
    (``owners``, see mesh.quality.patch_owners), also the mean and largest y+ from the wall shear stress
    (``friction_mean``, ``friction_max``; see friction_yplus).
    """
    centres, areas = faces[patch]
    area = np.linalg.norm(areas, axis=1)
    yplus = _patch_values(_field_file(time_dir, YPLUS_FIELD, "y+"), patch, len(area), 1)
    friction = None if owners is None else friction_yplus(time_dir, patch, yplus, owners)

    def summary(inside: np.ndarray) -> dict:
        w, y = area[inside], yplus[inside]
        out = {"mean": round(float(np.average(y, weights=w)), 1), "max": round(float(y.max()), 1),
               "above_log_layer_pct": round(100.0 * float(w[y > LOG_LAYER_TOP].sum() / w.sum()), 1)}
        if friction is not None:
            out["friction_mean"] = _rounded(float(np.average(friction[inside], weights=w)))
            out["friction_max"] = _rounded(float(friction[inside].max()))
        return out

    return _slices(centres[:, 0], bins, summary)


def _rounded(value: float) -> float:
    """One decimal, or three significant figures below 10 (a resolved wall's y+ is about 1)."""
    return round(value, 1) if value >= 10 else float(f"{value:.3g}")


def loads_along_x(time_dir: str | Path, faces: WallFaces, owners: dict[str, np.ndarray], scales: PrimeScales,
                  bins: int = 8) -> dict[str, list[dict]]:
    """Per patch of ``faces``: its side and vertical force (Y', Z') in ``bins`` equal slices of its length
    along x, aft to fore.

    Each face carries rho (p S_f - |S_f| tau_w), the sum OpenFOAM's forces function object makes, so the
    slices add up to the part's recorded force: p is that of the cell next to the face (``owners``, see
    mesh.quality.patch_owners; the wall's zero-gradient condition), S_f points out of the fluid, and the wall
    shear stress tau_w is the stress on the fluid. Each slice: its x range (m), faces, Y' and Z'. The fields
    are read once for all patches (the pressure is the whole internal field).
    """
    pressure = np.asarray(_field_file(time_dir, PRESSURE_FIELD, "pressure").internal_field, dtype=float)
    shear_file = _field_file(time_dir, FIELD, "wall shear stress")
    out = {}
    for patch, (centres, areas) in faces.items():
        cells = owners[patch]
        if len(cells) != len(areas):
            raise HydroderivError(f"{patch}: {len(cells)} owner cells for {len(areas)} faces")
        p = pressure[cells] if pressure.ndim else np.full(len(cells), float(pressure))
        shear = _patch_values(shear_file, patch, len(areas), 3)
        force = scales.rho * (p[:, None] * areas - np.linalg.norm(areas, axis=1)[:, None] * shear) / scales.force
        out[patch] = _slices(centres[:, 0], bins, lambda inside, force=force: {
            "Y": float(f"{force[inside, 1].sum():.4g}"), "Z": float(f"{force[inside, 2].sum():.4g}")})
    return out


def _slices(x: np.ndarray, bins: int, summary: Callable[[np.ndarray], dict]) -> list[dict]:
    """For each of ``bins`` equal slices of the faces' x (aft to fore; empty slices left out): its x range (m),
    its number of faces and ``summary`` of the faces in it (given as a mask)."""
    edges, slot = slices_along_x(x, bins)
    return [{"x_from": round(float(edges[k]), 3), "x_to": round(float(edges[k + 1]), 3), "faces": int(inside.sum()),
             **summary(inside)} for k in range(bins) if (inside := slot == k).any()]


def slice_values(slices: list[dict], key: str) -> str | None:
    """The y+ ``key`` of each slice, aft to fore, as one line (None when a slice lacks it, as the records made
    before that key existed do); two figures below 10, where a resolved wall's y+ of about 1 lies."""
    if not slices or any(key not in s for s in slices):
        return None
    return " ".join(f"{s[key]:.2g}" if s[key] < 10 else f"{s[key]:.0f}" for s in slices)


def describe_yplus_along_x(report: dict) -> str | None:
    """One line per part: its y+ slice means aft to fore, with the % of each slice's area above the log layer."""
    if "error" in report:
        return f"y+ along x not reported: {report['error']}"
    lines = []
    for part, slices in report.items():
        above = " ".join(f"{s['above_log_layer_pct']:.0f}" for s in slices)
        line = f"{part} y+ along x, aft to fore: {slice_values(slices, 'mean')} (% of area above {LOG_LAYER_TOP:.0f}: {above})"
        if (friction := slice_values(slices, "friction_mean")) is not None:
            line += f"; from the wall shear stress: {friction}"
        lines.append(line)
    return "\n    ".join(lines) or None


NOTABLE_PCT = 1.0  # below this a part's reversed flow is a few faces at a trailing edge or a tip


def describe_reversed_flow(report: dict) -> str | None:
    """One line naming the parts with more than NOTABLE_PCT of their area reversed (None when none has)."""
    if "error" in report:
        return f"reversed flow not reported: {report['error']}"
    notable = [f"{part} {info['reversed_pct']:.1f} %" for part, info in report.items() if info["reversed_pct"] > NOTABLE_PCT]
    return f"reversed flow at the wall: {', '.join(notable)} of the area" if notable else None
