"""Writing an OpenFOAM polyMesh from hexahedra given as eight point labels each, some of them collapsed.

A generated mesh (see mesh/revolution.py) has no mesher to write its faces, so they are derived here: every
cell contributes six quadrilaterals, shared ones become internal faces and the rest boundary faces, each
oriented by geometry (outwards from its owner) rather than by the cells' point order. A cell may repeat a
label (a hexahedron collapsed onto an axis): its faces with two distinct points vanish, those with three
are triangles, and the cell is a prism.
"""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import numpy as np

from .._io import atomic_write_text

# The six faces of a hexahedron in OpenFOAM's point order (cellModel hex), as positions in its 8 labels.
_HEX_FACES = np.array([[0, 4, 7, 3], [1, 2, 6, 5], [0, 1, 5, 4], [3, 7, 6, 2], [0, 3, 2, 1], [4, 5, 6, 7]])

_HEADER = """FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};{note}
    location    "constant/polyMesh";
    object      {obj};
}}

"""


def _header(cls: str, obj: str, note: str = "") -> str:
    return _HEADER.format(cls=cls, obj=obj, note=f'\n    note        "{note}";' if note else "")


def _face_normals(points: np.ndarray, quads: np.ndarray) -> np.ndarray:
    p = points[quads]
    return 0.5 * np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])


def hex_faces(points: np.ndarray, cells: np.ndarray) -> dict[str, np.ndarray]:
    """Faces of the hexahedra ``cells`` (n x 8 point labels): internal ones and boundary ones.

    Faces are n x 4 labels; a triangle repeats one label in place (see :func:`face_lists`). Returns
    ``internal`` (quads, owner, neighbour), sorted upper-triangular as OpenFOAM wants, and ``boundary``
    (quads, owner). Every face points out of its owner. Raises ValueError when a face is shared by more
    than two cells (the cells overlap).
    """
    n_cells = len(cells)
    quads = cells[:, _HEX_FACES].reshape(-1, 4)
    cell_of = np.repeat(np.arange(n_cells), 6)
    repeated = quads == np.roll(quads, 1, axis=1)
    real = repeated.sum(axis=1) <= 1  # collapsed to an edge or a point: no face
    quads, repeated, cell_of = quads[real], repeated[real], cell_of[real]
    # orient each face outwards from its own cell: compare its area vector with the direction to its centre
    centres = points[cells].mean(axis=1)
    face_centres = np.where(repeated[:, :, None], 0.0, points[quads]).sum(axis=1) / (4 - repeated.sum(axis=1))[:, None]
    outward = np.einsum("ij,ij->i", _face_normals(points, quads), face_centres - centres[cell_of])
    quads[outward < 0] = quads[outward < 0][:, ::-1]
    key = np.sort(np.where(repeated, -1, quads), axis=1)  # a triangle's key whichever label it repeats
    order = np.lexsort(key.T[::-1])
    key, quads, cell_of = key[order], quads[order], cell_of[order]
    same_as_next = np.all(key[1:] == key[:-1], axis=1)
    if np.any(same_as_next[1:] & same_as_next[:-1]):
        raise ValueError("a face is shared by more than two cells: the generated cells overlap")
    first = np.flatnonzero(same_as_next)  # pairs (first, first + 1)
    paired = np.zeros(len(key), dtype=bool)
    paired[first] = paired[first + 1] = True
    a, b = cell_of[first], cell_of[first + 1]
    owner, neighbour = np.minimum(a, b), np.maximum(a, b)
    internal = np.where((a < b)[:, None], quads[first], quads[first + 1])
    sort = np.lexsort((neighbour, owner))
    return {
        "internal": (internal[sort], owner[sort], neighbour[sort]),
        "boundary": (quads[~paired], cell_of[~paired]),
    }


def face_lists(quads: np.ndarray) -> list[str]:
    """OpenFOAM's text for faces given as 4 labels, a triangle's repeated label dropped."""
    out = []
    for face in quads.tolist():
        distinct = [v for n, v in enumerate(face) if v != face[n - 1]]
        out.append(f"{len(distinct)}({' '.join(map(str, distinct))})")
    return out


def _labels(values: np.ndarray) -> str:
    return "\n".join(map(str, values.tolist()))


def _write_list(path: Path, cls: str, obj: str, body: str, count: int, note: str = "") -> None:
    atomic_write_text(path, _header(cls, obj, note) + f"{count}\n(\n{body}\n)\n")


def write_polymesh(
    mesh_dir: str | Path,
    points: np.ndarray,
    cells: np.ndarray,
    patch_of_boundary_face: Callable[[np.ndarray], np.ndarray],
    patches: list[tuple[str, dict]],
    cell_zone: tuple[str, np.ndarray] | None = None,
) -> dict:
    """Write ``constant/polyMesh`` for the hexahedra ``cells`` on ``points``.

    ``patch_of_boundary_face`` maps the boundary quads (n x 4 point labels) to indices into ``patches``, a
    list of (name, dict of boundary entries such as type and inGroups). ``cell_zone`` (name, cell mask) adds
    a cellZone and a faceZone of the same name on its border. Returns the counts.
    """
    mesh_dir = Path(mesh_dir)
    faces = hex_faces(points, cells)
    internal, owner, neighbour = faces["internal"]
    b_quads, b_owner = faces["boundary"]
    patch = np.asarray(patch_of_boundary_face(b_quads))
    order = np.lexsort((b_owner, patch))
    b_quads, b_owner, patch = b_quads[order], b_owner[order], patch[order]
    all_quads = np.vstack([internal, b_quads])
    all_owner = np.concatenate([owner, b_owner])
    n_internal, n_faces, n_cells = len(internal), len(all_quads), len(cells)
    note = f"nPoints:{len(points)}  nCells:{n_cells}  nFaces:{n_faces}  nInternalFaces:{n_internal}"

    text = "\n".join(f"({x:.10g} {y:.10g} {z:.10g})" for x, y, z in points.tolist())
    _write_list(mesh_dir / "points", "vectorField", "points", text, len(points))
    text = "\n".join(face_lists(all_quads))
    _write_list(mesh_dir / "faces", "faceList", "faces", text, n_faces)
    _write_list(mesh_dir / "owner", "labelList", "owner", _labels(all_owner), n_faces, note)
    _write_list(mesh_dir / "neighbour", "labelList", "neighbour", _labels(neighbour), n_internal, note)

    entries, start = [], n_internal
    for index, (name, spec) in enumerate(patches):
        n = int(np.count_nonzero(patch == index))
        extra = "".join(f"        {k:<16}{v};\n" for k, v in spec.items())
        entries.append(f"    {name}\n    {{\n{extra}        nFaces          {n};\n        startFace       {start};\n    }}")
        start += n
    atomic_write_text(mesh_dir / "boundary",
                      _header("polyBoundaryMesh", "boundary") + f"{len(patches)}\n(\n" + "\n".join(entries) + "\n)\n")

    counts = {"points": len(points), "cells": n_cells, "faces": n_faces, "internal_faces": n_internal,
              "patch_faces": {name: int(np.count_nonzero(patch == i)) for i, (name, _) in enumerate(patches)}}
    if cell_zone is not None:
        name, inside = cell_zone
        cells_in = np.flatnonzero(inside)
        border = np.flatnonzero(inside[owner] != inside[neighbour])
        flip = ~inside[owner[border]]  # the face points into the zone: flipped with respect to it
        atomic_write_text(mesh_dir / "cellZones", _header("regIOobject", "cellZones") + (
            f"1\n(\n{name}\n{{\n    type cellZone;\n    cellLabels List<label> {len(cells_in)}\n(\n"
            f"{_labels(cells_in)}\n)\n;\n}}\n)\n"))
        atomic_write_text(mesh_dir / "faceZones", _header("regIOobject", "faceZones") + (
            f"1\n(\n{name}\n{{\n    type faceZone;\nfaceLabels      List<label> {len(border)}\n(\n"
            f"{_labels(border)}\n)\n;\nflipMap         List<bool> {len(border)}\n(\n"
            f"{_labels(flip.astype(int))}\n)\n;\n}}\n)\n"))
        counts["zone_cells"] = len(cells_in)
        counts["zone_faces"] = len(border)
    return counts
