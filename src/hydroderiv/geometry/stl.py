"""STL reading and writing with named solids (one solid per body component)."""

from __future__ import annotations

import io
import struct
from pathlib import Path

import numpy as np

from .._io import atomic_write_bytes
from ..errors import GeometryError
from .surfaces import TriSurface


def write_stl(path: str | Path, surface: TriSurface, face_component: np.ndarray, names: tuple[str, ...]) -> None:
    """Write an ASCII STL with one ``solid <name>`` block per component (OpenFOAM reads them as regions)."""
    normals = surface.face_normals_area
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = normals / np.where(lengths > 0, lengths, 1.0)
    out = io.StringIO()
    for k, name in enumerate(names):
        mask = face_component == k
        out.write(f"solid {name}\n")
        for n, tri in zip(normals[mask], surface.triangles[mask]):
            out.write(f"  facet normal {n[0]:.6e} {n[1]:.6e} {n[2]:.6e}\n    outer loop\n")
            for v in tri:
                out.write(f"      vertex {v[0]:.9e} {v[1]:.9e} {v[2]:.9e}\n")
            out.write("    endloop\n  endfacet\n")
        out.write(f"endsolid {name}\n")
    atomic_write_bytes(path, out.getvalue().encode())


def _read_binary(data: bytes, path: Path) -> tuple[np.ndarray, np.ndarray, list[str]]:
    (count,) = struct.unpack_from("<I", data, 80)
    records = np.frombuffer(data, dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]), count=count, offset=84)
    return records["v"].astype(float), np.zeros(count, dtype=np.int64), [path.stem]


def _read_ascii(text: str, path: Path) -> tuple[np.ndarray, np.ndarray, list[str]]:
    names: list[str] = []
    vertices: list[tuple[float, float, float]] = []
    component: list[int] = []
    current = -1
    for lineno, line in enumerate(text.splitlines(), start=1):
        words = line.split()
        if not words:
            continue
        key = words[0].lower()
        if key == "solid":
            names.append(" ".join(words[1:]) or f"solid{len(names)}")
            current = len(names) - 1
        elif key == "vertex":
            if current < 0:
                raise GeometryError(f"{path}: line {lineno}: 'vertex' outside any 'solid' block")
            try:
                vertices.append(tuple(float(w) for w in words[1:4]))
            except ValueError:
                raise GeometryError(f"{path}: line {lineno}: vertex with non-numeric coordinates: {line.strip()!r}")
            if len(words) != 4:
                raise GeometryError(f"{path}: line {lineno}: a vertex needs exactly three coordinates")
            if len(vertices) % 3 == 1:
                component.append(current)
        elif key not in {"facet", "outer", "endloop", "endfacet", "endsolid"}:
            raise GeometryError(f"{path}: line {lineno}: unexpected keyword {words[0]!r}; not an STL file?")
    if len(vertices) % 3:
        raise GeometryError(f"{path}: truncated file, {len(vertices)} vertices is not a whole number of triangles")
    return np.asarray(vertices, dtype=float).reshape(-1, 3, 3), np.asarray(component, dtype=np.int64), names


def read_stl(path: str | Path) -> tuple[TriSurface, np.ndarray, list[str]]:
    """Read an ASCII (multi-solid) or binary STL into a surface with shared vertices.

    Returns the surface, the solid index of every face and the solid names. Raises
    :class:`GeometryError` naming the problem for a missing, empty, truncated or malformed file.
    """
    path = Path(path)
    if not path.is_file():
        raise GeometryError(f"{path}: no such STL file")
    data = path.read_bytes()
    if not data.strip():
        raise GeometryError(f"{path}: the STL file is empty")
    is_binary = len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]
    if is_binary:
        triangles, component, names = _read_binary(data, path)
    else:
        try:
            text = data.decode("ascii")
        except UnicodeDecodeError:
            raise GeometryError(f"{path}: neither a valid binary STL (size does not match its triangle count) nor ASCII")
        triangles, component, names = _read_ascii(text, path)
    if len(triangles) == 0:
        raise GeometryError(f"{path}: the STL file holds no triangles")
    if not np.all(np.isfinite(triangles)):
        raise GeometryError(f"{path}: the STL file has NaN or infinite coordinates")
    flat = triangles.reshape(-1, 3)
    # Merge vertices that coincide to within a tiny fraction of the body size (STL repeats each vertex).
    tol = 1e-9 * max(float(np.ptp(flat, axis=0).max()), 1e-30)
    _, first, inverse = np.unique(np.round(flat / tol), axis=0, return_index=True, return_inverse=True)
    surface = TriSurface(flat[first], inverse.reshape(-1, 3))
    # Drop triangles that collapse to a line or point once vertices are merged.
    f = surface.faces
    keep = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
    return TriSurface(surface.vertices, f[keep]), component[keep], names
