"""The rotating sphere's interface put onto the sphere, on a hand-made polyMesh (no OpenFOAM needed)."""

import numpy as np
import pytest

from hydroderiv.errors import HydroderivError
from hydroderiv.mesh.interface import (
    face_zone_faces,
    project_interface_onto_sphere,
    sphere_interface_spread,
    tilt_degrees,
)
from hydroderiv.mesh.quality import read_points

RADIUS = 2.0
HEADER = """FoamFile
{{
    version     2.0;
    format      {format};
    class       {cls};
    location    "constant/polyMesh";
    object      {name};
}}
"""


def _write(mesh, name, cls, body, fmt="ascii"):
    (mesh / name).write_text(HEADER.format(format=fmt, cls=cls, name=name) + "\n\n" + body)


def _mesh(tmp_path, jitter=0.01, radius=RADIUS):
    """A band of quads between latitudes -60 and 60 degrees, their corners scattered about the sphere in
    radius as snapping leaves them, plus two points that belong to no zone face."""
    rng = np.random.default_rng(7)
    lats, lons = np.radians(np.linspace(-60, 60, 9)), np.radians(np.linspace(0, 360, 25)[:-1])
    grid = np.array([[np.cos(a) * np.cos(b), np.cos(a) * np.sin(b), np.sin(a)] for a in lats for b in lons])
    grid *= radius * (1.0 + jitter * rng.uniform(-1, 1, len(grid)))[:, None]
    points = np.vstack([[[0.1, 0.2, 0.3], [5.0, -4.0, 3.0]], grid])
    n = len(lons)
    faces = [[2 + i * n + j, 2 + i * n + (j + 1) % n, 2 + (i + 1) * n + (j + 1) % n, 2 + (i + 1) * n + j]
             for i in range(len(lats) - 1) for j in range(n)]
    mesh = tmp_path / "constant/polyMesh"
    mesh.mkdir(parents=True)
    _write(mesh, "points", "vectorField",
           f"{len(points)}\n(\n" + "\n".join("(%.12g %.12g %.12g)" % tuple(p) for p in points) + "\n)\n")
    _write(mesh, "faces", "faceList",
           f"{len(faces)}\n(\n" + "\n".join(f"4({' '.join(map(str, f))})" for f in faces) + "\n)\n")
    labels = " ".join(str(i) for i in range(len(faces)))
    _write(mesh, "faceZones", "regIOobject",
           f"1\n(\nrotatingZone\n{{\n    type faceZone;\nfaceLabels List<label> {len(faces)}({labels});\n"
           f"flipMap List<bool> {len(faces)}{{0}};\n}}\n)\n")
    return tmp_path, points


def test_projection_puts_every_interface_point_on_the_sphere_and_moves_nothing_else(tmp_path):
    case, before = _mesh(tmp_path)
    mesh = case / "constant/polyMesh"
    faces = face_zone_faces(mesh)
    assert len(faces) == 8 * 24
    tilted = tilt_degrees(before, faces)
    assert np.median(tilted) > 0.5  # a 1 % scatter in radius tilts faces of 15 degrees by about a degree

    moved = project_interface_onto_sphere(case, RADIUS)
    after = read_points(mesh)
    assert moved["points"] == 9 * 24
    assert 0.9 < moved["largest_move_pct_of_radius"] <= 1.0
    assert np.linalg.norm(after[2:], axis=1) == pytest.approx(RADIUS, rel=1e-12)
    assert np.array_equal(after[:2], before[:2])  # points of no zone face stay bit for bit
    # faces of a latitude band, inscribed in the sphere, tilt only by their own small asymmetry
    assert tilt_degrees(after, faces).max() < 0.05 * tilted.max()

    again = project_interface_onto_sphere(case, RADIUS)
    assert again["largest_move_pct_of_radius"] < 1e-9
    assert np.array_equal(read_points(mesh), after)


def test_the_report_gives_the_spread_and_tilt_of_the_interface(tmp_path):
    case, _ = _mesh(tmp_path)
    snapped = sphere_interface_spread(case, RADIUS)
    project_interface_onto_sphere(case, RADIUS)
    placed = sphere_interface_spread(case, RADIUS)
    assert snapped["faces"] == placed["faces"] == 192
    assert placed["tilt_deg_max"] < 0.05 * snapped["tilt_deg_max"]
    # the centres of flat quads lie inside the sphere that holds their corners, by their sagitta (2 % for
    # these 15-degree quads, 0.01 % for the 0.25 m faces of an 8.5 m sphere on the coarse level)
    assert RADIUS * 0.97 < placed["face_radius_min_m"] <= placed["face_radius_max_m"] < RADIUS
    assert sphere_interface_spread(tmp_path / "nowhere", RADIUS) == {}


def test_a_zone_that_is_not_the_sphere_is_named(tmp_path):
    case, _ = _mesh(tmp_path, radius=1.5)
    with pytest.raises(HydroderivError, match="faceZone 'rotatingZone' is not the sphere of radius 2 m"):
        project_interface_onto_sphere(case, RADIUS)
    with pytest.raises(HydroderivError, match="has no faceZone 'sphere'"):
        project_interface_onto_sphere(case, RADIUS, zone="sphere")


def test_a_binary_mesh_is_refused_by_name(tmp_path):
    case, _ = _mesh(tmp_path)
    points = case / "constant/polyMesh/points"
    points.write_text(points.read_text().replace("format      ascii;", "format      binary;"))
    with pytest.raises(HydroderivError, match="points is written in binary"):
        project_interface_onto_sphere(case, RADIUS)
