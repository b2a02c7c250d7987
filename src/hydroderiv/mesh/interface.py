"""The interface of the rotating sphere: put exactly on the sphere, and measured.

Why it matters: OpenFOAM's MRF makes the flux relative, phi - (Omega x r_f) . S_f, on every face of a
rotating-zone cell, the interface faces included, while the inertial cell beyond keeps absolute fluxes on
its other faces. On a true sphere centred at the rotation centre B, Omega x r is tangent to the interface,
the correction there vanishes, and uniform flow is an exact solution in both zones. snappyHexMesh leaves
the interface points scattered within about 0.5 % of the radius about the sphere. Their faces then tilt away
from it (2.3 degrees median, 21 degrees at most on the coarse AFF-8 mesh), and the correction through them
disturbed uniform flow by 2.6 % of U next to the interface in a turn of r' = 0.3. Moving every interface
point radially onto the sphere leaves the faces tilted by 0.3 degrees at most, and the disturbance falls
to 0.06 %.

The price: where snapping folded a step of the castellated surface onto the sphere, the two cells of an
interface face sit side by side rather than across it, and with the face now exactly on the sphere its
non-orthogonality grows: on the coarse AFF-8 mesh 2,130 of the 21,792 interface faces exceed 70 degrees
(12 faces in the whole mesh before), at most 78 degrees (73 before). The sphere is far from the body,
where the flow is nearly uniform, and the numerics limit the non-orthogonal correction; the main job's
derivatives moved by 0.01 % (static) and 0.6 % (rotary) with the change.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from .._io import atomic_write_text
from ..errors import HydroderivError
from .quality import face_geometry, poly_list, read_points, read_points_file

ZONE = "rotatingZone"


def face_zone_faces(mesh_dir: str | Path, zone: str = ZONE) -> list[np.ndarray]:
    """The point labels of each face of a faceZone of an ascii polyMesh."""
    mesh_dir = Path(mesh_dir)
    zones = (mesh_dir / "faceZones").read_text()
    match = re.search(rf"{re.escape(zone)}\s*\{{.*?faceLabels\s+List<label>\s+(\d+)\s*\((.*?)\)", zones, re.S)
    if match is None:
        raise HydroderivError(f"{mesh_dir / 'faceZones'} has no faceZone {zone!r}")
    faces = re.findall(r"\d+\(([\d ]+)\)", poly_list(mesh_dir / "faces"))
    return [np.array(faces[i].split(), dtype=int) for i in np.array(match.group(2).split(), dtype=int)]


def _centres_and_areas(points: np.ndarray, faces: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    geometry = [face_geometry(points, face) for face in faces]
    return np.array([c for c, _ in geometry]).reshape(-1, 3), np.array([a for _, a in geometry]).reshape(-1, 3)


def _tilt(centres: np.ndarray, areas: np.ndarray) -> np.ndarray:
    sine = np.linalg.norm(np.cross(centres, areas), axis=1) / (
        np.linalg.norm(centres, axis=1) * np.linalg.norm(areas, axis=1))
    return np.degrees(np.arcsin(np.minimum(sine, 1.0)))


def tilt_degrees(points: np.ndarray, faces: list[np.ndarray], origin=(0.0, 0.0, 0.0)) -> np.ndarray:
    """Angle of each face's normal from the radial line through its centre, in degrees.

    The MRF flux through a face of a sphere centred at ``origin``, (Omega x r_f) . S_f, is |Omega x r_f| |S_f|
    times the sine of this angle at most.
    """
    centres, areas = _centres_and_areas(points, faces)
    return _tilt(centres - np.asarray(origin, dtype=float), areas)


def sphere_interface_spread(case: str | Path, radius: float, zone: str = ZONE) -> dict:
    """How far the interface faces lie from the true sphere about the origin (face-centre radii), and tilt."""
    mesh = Path(case) / "constant/polyMesh"
    try:
        points = read_points(mesh)
        faces = face_zone_faces(mesh, zone)
    except (FileNotFoundError, ValueError, HydroderivError):
        return {}
    centres, areas = _centres_and_areas(points, faces)  # once, for both the radii and the tilt
    r = np.linalg.norm(centres, axis=1)
    tilt = _tilt(centres, areas)
    return {
        "faces": int(len(r)),
        "face_radius_min_m": round(float(r.min()), 4),
        "face_radius_max_m": round(float(r.max()), 4),
        "max_deviation_pct_of_radius": round(100.0 * float(np.abs(r - radius).max()) / radius, 3),
        "tilt_deg_median": round(float(np.median(tilt)), 3),
        "tilt_deg_max": round(float(tilt.max()), 3),
    }


def project_interface_onto_sphere(case: str | Path, radius: float, zone: str = ZONE) -> dict:
    """Move every point of the interface faceZone radially onto the sphere of ``radius`` about the origin.

    Rewrites constant/polyMesh/points atomically; only those points move. Running it again changes nothing.
    Returns the number of points moved and the largest move, in % of the radius.
    """
    mesh = Path(case) / "constant/polyMesh"
    header, points = read_points_file(mesh)
    labels = np.unique(np.concatenate(face_zone_faces(mesh, zone)))
    r = np.linalg.norm(points[labels], axis=1)
    if np.any(r <= 0.0):
        raise HydroderivError(f"{mesh}: a point of faceZone {zone!r} sits at the sphere's centre")
    largest = float(np.abs(r - radius).max())
    if largest > 0.05 * radius:
        # snapping keeps the points within about a cell; far beyond that the zone is not this sphere
        raise HydroderivError(f"{mesh}: faceZone {zone!r} is not the sphere of radius {radius:g} m about the "
                              f"origin (a point lies {largest:.3g} m from it)")
    off = np.abs(r - radius) > 1e-12 * radius  # points already on it stay as they are, bit for bit
    points[labels[off]] *= (radius / r[off])[:, None]
    rows = "\n".join(f"({x:.15g} {y:.15g} {z:.15g})" for x, y, z in points)
    atomic_write_text(mesh / "points", f"{header}\n\n\n{len(points)}\n(\n{rows}\n)\n")
    return {"points": int(len(labels)), "largest_move_pct_of_radius": round(100.0 * largest / radius, 3)}
