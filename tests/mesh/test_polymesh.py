"""Faces of generated hexahedra: pairing, orientation, and cells collapsed onto an axis."""

import numpy as np
import pytest

from hydroderiv.mesh.polymesh import face_lists, hex_faces


def face_flux(points, quads):
    """Each face's x . S / 3 and area vector S: the divergence theorem's share of the volume it bounds."""
    p = points[quads]
    area = 0.5 * np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])
    return np.einsum("ij,ij->i", p.mean(axis=1), area) / 3.0, area  # any point of a planar face will do


def cell_volumes(points, cells, faces):
    """Each cell's volume by the divergence theorem over its faces as oriented by hex_faces."""
    volumes = np.zeros(len(cells))
    internal, owner, neighbour = faces["internal"]
    boundary, b_owner = faces["boundary"]
    f_internal, _ = face_flux(points, internal)
    np.add.at(volumes, owner, f_internal)
    np.add.at(volumes, neighbour, -f_internal)
    np.add.at(volumes, b_owner, face_flux(points, boundary)[0])
    return volumes


def _block(nx, ny, nz):
    idx = np.arange((nx + 1) * (ny + 1) * (nz + 1)).reshape(nx + 1, ny + 1, nz + 1)
    x, y, z = np.meshgrid(np.arange(nx + 1), np.arange(ny + 1), np.arange(nz + 1), indexing="ij")
    points = np.column_stack([x.ravel(), y.ravel(), z.ravel()]).astype(float)
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    # a mirrored point order in half of the cells: orientation must come from geometry, not from the order
    cells = np.stack([idx[i, j, k], idx[i + 1, j, k], idx[i + 1, j + 1, k], idx[i, j + 1, k],
                      idx[i, j, k + 1], idx[i + 1, j, k + 1], idx[i + 1, j + 1, k + 1], idx[i, j + 1, k + 1]],
                     axis=-1).reshape(-1, 8)
    cells[::2] = cells[::2][:, [4, 5, 6, 7, 0, 1, 2, 3]]
    return points, cells


def test_a_block_of_hexahedra_has_its_shared_faces_once_and_every_face_pointing_out_of_its_owner():
    points, cells = _block(3, 2, 2)
    faces = hex_faces(points, cells)
    internal, owner, neighbour = faces["internal"]
    assert len(internal) == 2 * 2 * 2 + 3 * 1 * 2 + 3 * 2 * 1  # interior planes in x, y and z
    assert len(faces["boundary"][0]) == 2 * (2 * 2 + 3 * 2 + 3 * 2)
    assert np.all(owner < neighbour)
    assert np.all(np.diff(owner * len(cells) + neighbour) > 0)  # upper-triangular order
    assert cell_volumes(points, cells, faces) == pytest.approx(np.ones(len(cells)))


def test_hexahedra_collapsed_onto_an_axis_become_prisms_with_triangular_ends():
    # four cells around the x axis: the points on the axis are shared by all four angles
    n = 4
    angles = 2 * np.pi * np.arange(n) / n
    axis = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
    rim = [[x, np.cos(a), np.sin(a)] for x in (0.0, 1.0) for a in angles]
    points = np.array(axis + rim)
    rim_id = lambda x, k: 2 + x * n + k % n  # noqa: E731
    cells = np.array([[0, 1, 1, 0, rim_id(0, k), rim_id(1, k), rim_id(1, k + 1), rim_id(0, k + 1)]
                      for k in range(n)])
    faces = hex_faces(points, cells)
    internal, _, _ = faces["internal"]
    boundary, _ = faces["boundary"]
    assert len(internal) == n  # the radial planes between neighbours
    assert len(boundary) == 2 * n + n  # two triangular ends and the outer quad of each cell
    texts = face_lists(boundary)
    assert sum(t.startswith("3(") for t in texts) == 2 * n
    assert cell_volumes(points, cells, faces) == pytest.approx(np.full(n, 0.5))  # a quarter of the square prism


def test_overlapping_cells_are_refused():
    points, cells = _block(1, 1, 1)
    with pytest.raises(ValueError, match="overlap"):
        hex_faces(points, np.vstack([cells, cells, cells]))  # every face then has three cells
