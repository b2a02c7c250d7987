"""Mesh quality: the checkMesh gate and prism-layer coverage; the ascii polyMesh readers and face geometry."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import HydroderivError


class MeshQualityError(HydroderivError):
    """checkMesh found the mesh unusable; the message names the failed checks and the log."""


# checkMesh problems that flag a few poor cells rather than a broken mesh: reported, not fatal. A snapped
# mesh around appendages routinely has a handful of faces just over checkMesh's skewness limit of 4 or
# concave layer cells; snappyHexMesh's own quality controls have already bounded them.
SOFT_PROBLEMS = ("skew", "aspect ratio", "concave", "non-orthogonal", "determinant")


def parse_check_mesh(text: str) -> dict:
    """Cell count, pass/fail and the named problems ('***' lines) from a checkMesh log.

    ``ok`` is False when checkMesh reports any problem outside :data:`SOFT_PROBLEMS` (negative volumes,
    wrong face orientation, open cells, ...); soft ones are listed under ``warnings``.
    """
    cells = re.search(r"^\s*cells:\s+(\d+)", text, re.M)
    failed = re.search(r"Failed (\d+) mesh checks", text)
    skew = re.search(r"Max skewness = ([\d.eE+-]+)", text)
    nonortho = re.search(r"Mesh non-orthogonality Max: ([\d.eE+-]+) average: ([\d.eE+-]+)", text)
    problems = [line.strip(" *") for line in re.findall(r"^\s*\*\*\*.*$", text, re.M)]
    hard = [p for p in problems if not any(word in p.lower() for word in SOFT_PROBLEMS)]
    return {
        "ok": ("Mesh OK." in text or failed is not None) and not hard and cells is not None,
        "failed": int(failed.group(1)) if failed else 0,
        "cells": int(cells.group(1)) if cells else None,
        "problems": hard,
        "warnings": [p for p in problems if p not in hard],
        "max_skewness": float(skew.group(1)) if skew else None,
        "max_non_orthogonality": float(nonortho.group(1)) if nonortho else None,
        "mean_non_orthogonality": float(nonortho.group(2)) if nonortho else None,
    }


def _boundary_list(path: Path, patch: str) -> np.ndarray:
    """The values of a scalar field on one patch (uniform or nonuniform List<scalar>)."""
    text = path.read_text()
    start = re.search(rf"^\s*{re.escape(patch)}\s*$\s*\{{", text[text.index("boundaryField") :], re.M)
    if start is None:
        return np.empty(0)
    block = text[text.index("boundaryField") + start.end() :]
    nonuniform = re.match(r"[^}]*?value\s+nonuniform\s+List<scalar>\s*(\d+)\s*\((.*?)\)", block, re.S)
    if nonuniform:
        return np.array(nonuniform.group(2).split(), dtype=float)
    uniform = re.match(r"[^}]*?value\s+uniform\s+([^;]+);", block, re.S)
    return np.array([float(uniform.group(1))]) if uniform else np.empty(0)


def _layer_counts(case: Path, patch: str) -> np.ndarray:
    """snappy's layer count on each face of one patch; empty without its layer field or that patch."""
    field = Path(case) / "0" / "nSurfaceLayers"
    return _boundary_list(field, patch) if field.is_file() else np.empty(0)


def layer_coverage(case: Path, layers_wanted: dict[str, int]) -> dict:
    """Per patch: faces, % with any prism layer, % with all of that patch's layers, mean layers.

    ``layers_wanted`` maps each patch to the layer count asked of it (thin parts may ask fewer than the
    hull). Read from snappy's layer field.
    """
    out = {}
    for patch, wanted in layers_wanted.items():
        n = _layer_counts(case, patch)
        if len(n):
            out[patch] = {
                "faces": int(len(n)),
                "any_layer_pct": round(100.0 * float((n > 0).mean()), 1),
                "layers_wanted": wanted,
                "all_layers_pct": round(100.0 * float((n >= wanted).mean()), 1),
                "mean_layers": round(float(n.mean()), 2),
            }
    return out


def slices_along_x(x: np.ndarray, bins: int) -> tuple[np.ndarray, np.ndarray]:
    """Edges of ``bins`` equal slices from the smallest to the largest x, and the slice of each x (0 aftmost)."""
    edges = np.linspace(x.min(), x.max(), bins + 1)
    return edges, np.clip(np.searchsorted(edges, x, side="right") - 1, 0, bins - 1)


def layers_along_x(case: Path, patch: str, bins: int = 8) -> list[dict]:
    """Prism layers on one patch in ``bins`` equal slices of its length along x, aft to fore.

    The patch-wide share hides where the layers are missing: on the coarse AFF-8 hull snappy keeps the full
    stack on the parallel midbody and loses most of it on the nose, the tail cone and the appendage roots.
    Each slice: its x range (m), faces, mean face size (mm), % of faces with any layer and mean layers.
    Empty without snappy's layer field.
    """
    counts = _layer_counts(case, patch)
    if not len(counts):
        return []
    centres, areas = patch_faces(Path(case) / "constant" / "polyMesh", [patch])[patch]
    size = np.sqrt(np.linalg.norm(areas, axis=1))
    edges, slot = slices_along_x(centres[:, 0], bins)
    out = []
    for k in range(bins):
        n = counts[slot == k]
        if len(n):
            out.append({"x_from": round(float(edges[k]), 3), "x_to": round(float(edges[k + 1]), 3), "faces": int(len(n)),
                        "face_size_mm": round(1000.0 * float(size[slot == k].mean()), 1),
                        "any_layer_pct": round(100.0 * float((n > 0).mean()), 1), "mean_layers": round(float(n.mean()), 2)})
    return out


def _ascii_file(path: Path) -> tuple[str, str]:
    """(header, body) of an ascii OpenFOAM file: its FoamFile dictionary, and everything after it."""
    text = path.read_text()
    header_end = text.index("}", text.index("FoamFile")) + 1
    require_ascii(text[:header_end], path)
    return text[:header_end], text[header_end:]


def poly_list(path: Path) -> str:
    """The text of an ascii polyMesh list file (faces, owner, ...) from its opening parenthesis on."""
    body = _ascii_file(path)[1]
    return body[body.index("("):]


def require_ascii(header: str, path: Path) -> None:
    """Raise if an OpenFOAM file's header says it is not ascii (the mesh readers here parse text only)."""
    match = re.search(r"format\s+(\w+)\s*;", header)
    if match and match.group(1) != "ascii":
        raise HydroderivError(f"{path} is written in {match.group(1)}; only ascii meshes can be read here")


def read_points_file(mesh_dir: Path) -> tuple[str, np.ndarray]:
    """The FoamFile header and the points, (n, 3) in metres, of an ascii polyMesh: the header is what
    writing the points back needs."""
    header, body = _ascii_file(Path(mesh_dir) / "points")
    count = re.search(r"(\d+)\s*\(", body)
    values = body[count.end() :].translate(str.maketrans("()", "  ")).split()
    return header, np.array(values[: 3 * int(count.group(1))], dtype=float).reshape(-1, 3)


def read_points(mesh_dir: Path) -> np.ndarray:
    """The points of an ascii polyMesh, (n, 3) in metres."""
    return read_points_file(mesh_dir)[1]


def face_geometry(points: np.ndarray, face: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(centre, area vector) of one polygonal face, as OpenFOAM defines them for warped faces too.

    The face is fanned into triangles about its mean point; the area vector is their sum and the centre is
    their area-weighted centroid.
    """
    corners = points[face]
    middle = corners.mean(axis=0)
    following = np.roll(corners, -1, axis=0)
    triangles = 0.5 * np.cross(corners - middle, following - middle)
    weights = np.linalg.norm(triangles, axis=1)
    centre = (weights[:, None] * (corners + following + middle)).sum(axis=0) / (3.0 * weights.sum())
    return centre, triangles.sum(axis=0)


def _patch_ranges(mesh_dir: Path, patches) -> dict[str, tuple[int, int]]:
    """(start face, face count) of each named patch, from the polyMesh's boundary file."""
    boundary = (mesh_dir / "boundary").read_text()
    ranges = {}
    for patch in patches:
        block = re.search(rf"^\s*{re.escape(patch)}\s*\{{([^}}]*)\}}", boundary, re.M)
        if block is None:
            raise HydroderivError(f"{mesh_dir / 'boundary'} has no patch {patch!r}")
        entries = dict(re.findall(r"(\w+)\s+([^;]+);", block.group(1)))
        ranges[patch] = (int(entries["startFace"]), int(entries["nFaces"]))
    return ranges


def patch_owners(mesh_dir: str | Path, patches: tuple[str, ...] | list[str]) -> dict[str, np.ndarray]:
    """The cell next to each face of each named patch of an ascii polyMesh (its owner), in face order.

    A field with a zero-gradient condition on the patch (the pressure on a wall) has these cells' values
    on its faces, which OpenFOAM does not write into the field file.
    """
    mesh_dir = Path(mesh_dir)
    ranges = _patch_ranges(mesh_dir, patches)
    owner = np.array(poly_list(mesh_dir / "owner")[1:].split(")")[0].split(), dtype=np.int64)
    return {patch: owner[start : start + n] for patch, (start, n) in ranges.items()}


def patch_faces(mesh_dir: str | Path, patches: tuple[str, ...] | list[str]) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """(face centres, face area vectors) of each named patch of an ascii polyMesh, in metres.

    Only the faces of those patches are parsed (they sit in one contiguous range of the faces file each),
    so this stays quick on meshes of millions of cells.
    """
    mesh_dir = Path(mesh_dir)
    ranges = _patch_ranges(mesh_dir, patches)
    points = read_points(mesh_dir)

    wanted = sorted((start, n, patch) for patch, (start, n) in ranges.items())
    faces: dict[str, list[list[int]]] = {patch: [] for patch in patches}
    with open(mesh_dir / "faces") as stream:
        header = ""
        for line in stream:  # header and count, up to the opening parenthesis of the list
            header += line
            if line.strip() == "(":
                break
        require_ascii(header, mesh_dir / "faces")
        index, k = 0, 0
        for line in stream:
            if k == len(wanted):
                break
            start, n, patch = wanted[k]
            if index >= start:
                labels = line[line.index("(") + 1 : line.rindex(")")].split()
                faces[patch].append([int(v) for v in labels])
                if len(faces[patch]) == n:
                    k += 1
            index += 1

    out = {}
    for patch in patches:
        centres, areas = [], []
        for face in faces[patch]:
            centre, area = face_geometry(points, np.asarray(face))
            centres.append(centre)
            areas.append(area)
        out[patch] = (np.array(centres).reshape(-1, 3), np.array(areas).reshape(-1, 3))
    return out
