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
the regions, such as a tail cone without prism layers, where a wall-function mesh is out of its range.

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


def yplus_along_x(time_dir: str | Path, faces: WallFaces, patch: str, bins: int = 8) -> list[dict]:
    """First-cell y+ on one patch of ``faces`` in ``bins`` equal slices of its length along x, aft to fore.

    The patch-wide mean hides where the wall treatment leaves its range: on the medium AFF-8 hull it is 123,
    but 120-520 over the tail cone, where snappy drops the prism layers and the first cells are the hull's
    own surface cells. Each slice: its x range (m), faces, the area-weighted mean and the largest y+, and
    the % of its area above LOG_LAYER_TOP.
    """
    centres, areas = faces[patch]
    area = np.linalg.norm(areas, axis=1)
    yplus = _patch_values(_field_file(time_dir, YPLUS_FIELD, "y+"), patch, len(area), 1)

    def summary(inside: np.ndarray) -> dict:
        w, y = area[inside], yplus[inside]
        return {"mean": round(float(np.average(y, weights=w)), 1), "max": round(float(y.max()), 1),
                "above_log_layer_pct": round(100.0 * float(w[y > LOG_LAYER_TOP].sum() / w.sum()), 1)}

    return _slices(centres[:, 0], bins, summary)


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


def describe_yplus_along_x(report: dict) -> str | None:
    """One line per part: its y+ slice means aft to fore, with the % of each slice's area above the log layer."""
    if "error" in report:
        return f"y+ along x not reported: {report['error']}"
    lines = []
    for part, slices in report.items():
        means = " ".join(f"{s['mean']:.2g}" if s["mean"] < 10 else f"{s['mean']:.0f}" for s in slices)  # resolved walls: y+ ~ 1
        above = " ".join(f"{s['above_log_layer_pct']:.0f}" for s in slices)
        lines.append(f"{part} y+ along x, aft to fore: {means} (% of area above {LOG_LAYER_TOP:.0f}: {above})")
    return "\n    ".join(lines) or None


NOTABLE_PCT = 1.0  # below this a part's reversed flow is a few faces at a trailing edge or a tip


def describe_reversed_flow(report: dict) -> str | None:
    """One line naming the parts with more than NOTABLE_PCT of their area reversed (None when none has)."""
    if "error" in report:
        return f"reversed flow not reported: {report['error']}"
    notable = [f"{part} {info['reversed_pct']:.1f} %" for part, info in report.items() if info["reversed_pct"] > NOTABLE_PCT]
    return f"reversed flow at the wall: {', '.join(notable)} of the area" if notable else None
