"""Reversed flow at the wall: the share of each body part's wetted area where the boundary layer runs back.

The wall shear stress gives the direction of the flow next to the wall. Where that flow runs against the
stream the body meets, the boundary layer has separated into a closed bubble: behind a blunt tail, or in
the corner where a sail or fin meets the hull. Linear eddy-viscosity models are least trustworthy there
(k-omega SST is known to make junction corner separations too large), and a bubble that sits on one side
of a symmetric body at zero incidence is a load the experiment will not show. So every condition reports
this share per part, beside its forces.

Open cross-flow separation on the lee side of a body at incidence is not counted: there the flow at the
wall still runs aft, only turned sideways.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from foamlib import FoamFieldFile

from ..errors import HydroderivError
from ..mesh.quality import patch_faces

FIELD = "wallShearStress"  # written by OpenFOAM's wallShearStress function object (see case/setup.py)


def reversed_flow(
    time_dir: str | Path, mesh_dir: str | Path, patches: tuple[str, ...] | list[str], inflow: np.ndarray,
    angular_velocity: np.ndarray = np.zeros(3),
) -> dict[str, dict]:
    """Per patch: wetted area (m^2) and the % of it where the flow at the wall runs against the stream.

    ``time_dir`` holds the wall shear stress field; ``inflow`` is U_inf and ``angular_velocity`` Omega, both
    in body axes. The body meets the stream U_inf - Omega x r at r (the same in the hybrid and the classic
    frames). OpenFOAM's wall shear stress is the stress the wall puts on the fluid, so it points against
    the flow next to the wall: the flow runs back where it has a positive component along that stream.
    """
    path = Path(time_dir) / FIELD
    if not path.is_file():
        raise HydroderivError(f"{path} is missing: the run wrote no wall shear stress")
    boundary = FoamFieldFile(path).boundary_field
    geometry = patch_faces(mesh_dir, patches)
    out = {}
    for patch in patches:
        centres, areas = geometry[patch]
        shear = np.asarray(boundary[patch]["value"], dtype=float).reshape(-1, 3)
        if len(shear) != len(areas):
            raise HydroderivError(f"{path}: {len(shear)} values on {patch}, but the mesh has {len(areas)} faces")
        stream = np.asarray(inflow, dtype=float) - np.cross(np.asarray(angular_velocity, dtype=float), centres)
        back = np.einsum("ij,ij->i", shear, stream) > 0.0
        area = np.linalg.norm(areas, axis=1)
        total = float(area.sum())
        out[patch] = {
            "area_m2": round(total, 6),
            "reversed_pct": round(100.0 * float(area[back].sum()) / total, 3) if total > 0 else 0.0,
        }
    return out


NOTABLE_PCT = 1.0  # below this a part's reversed flow is a few faces at a trailing edge or a tip


def describe_reversed_flow(report: dict) -> str | None:
    """One line naming the parts with more than NOTABLE_PCT of their area reversed (None when none has)."""
    if "error" in report:
        return f"reversed flow not reported: {report['error']}"
    notable = [f"{part} {info['reversed_pct']:.1f} %" for part, info in report.items() if info["reversed_pct"] > NOTABLE_PCT]
    return f"reversed flow at the wall: {', '.join(notable)} of the area" if notable else None
