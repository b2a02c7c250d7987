"""Triangulated surfaces: construction (revolve, loft) and the watertight union of components."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import manifold3d
import numpy as np

from ..errors import GeometryError


@dataclass(frozen=True)
class TriSurface:
    """A triangulated surface: ``vertices`` (n, 3) float and ``faces`` (m, 3) int, outward normals."""

    vertices: np.ndarray
    faces: np.ndarray

    @property
    def triangles(self) -> np.ndarray:
        return self.vertices[self.faces]

    @property
    def face_normals_area(self) -> np.ndarray:
        """Cross products of the triangle edges: direction of the normal, length twice the area."""
        t = self.triangles
        return np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])

    @property
    def area(self) -> float:
        return float(0.5 * np.linalg.norm(self.face_normals_area, axis=1).sum())

    def _signed_tetrahedron_volumes(self) -> np.ndarray:
        """Signed volume of the tetrahedron each face spans with the origin (positive for outward normals)."""
        t = self.triangles
        return np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])) / 6.0

    @property
    def volume(self) -> float:
        """Enclosed volume by the divergence theorem (positive for outward normals)."""
        return float(self._signed_tetrahedron_volumes().sum())

    @property
    def centroid(self) -> np.ndarray:
        """Centre of the enclosed volume (the centre of buoyancy of a closed hull): the volume-weighted mean
        of the centroids of the tetrahedra each face spans with the origin."""
        volumes = self._signed_tetrahedron_volumes()
        return (volumes[:, None] * self.triangles.sum(axis=1) / 4.0).sum(axis=0) / volumes.sum()

    @property
    def second_moments(self) -> np.ndarray:
        """The enclosed volume's second moments about the origin, S_ij = \\int x_i x_j dV (3x3): a uniform
        solid's inertia tensor per unit density is trace(S) I - S. Summed over the tetrahedra each face spans
        with the origin, whose S is det[a b c] / 120 (a a^T + b b^T + c c^T + (a + b + c)(a + b + c)^T)."""
        t = self.triangles
        det = np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2]))
        corners = np.einsum("fki,fkj->fij", t, t)
        summed = t.sum(axis=1)
        return ((corners + np.einsum("fi,fj->fij", summed, summed)) * det[:, None, None]).sum(axis=0) / 120.0

    @property
    def bounds(self) -> np.ndarray:
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    def transformed(self, mapping: Callable[[np.ndarray], np.ndarray]) -> TriSurface:
        """Apply a point mapping; faces are flipped if the mapping reverses orientation."""
        moved = TriSurface(np.asarray(mapping(self.vertices), dtype=float), self.faces)
        if np.sign(moved.volume) != np.sign(self.volume):
            moved = TriSurface(moved.vertices, moved.faces[:, ::-1].copy())
        return moved

    def subset(self, face_mask: np.ndarray) -> TriSurface:
        """The faces selected by ``face_mask``, with only the vertices they use."""
        faces = self.faces[face_mask]
        used, inverse = np.unique(faces, return_inverse=True)
        return TriSurface(self.vertices[used], inverse.reshape(-1, 3))

    def edge_use_counts(self) -> np.ndarray:
        """How many faces use each undirected edge (2 everywhere on a closed 2-manifold)."""
        edges = np.sort(self.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        _, counts = np.unique(edges, axis=0, return_counts=True)
        return counts

    def is_consistently_oriented(self) -> bool:
        """True if every directed edge appears once: neighbouring faces agree on the normal direction."""
        directed = self.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2)
        _, counts = np.unique(directed, axis=0, return_counts=True)
        return bool(np.all(counts == 1))

    def is_watertight(self) -> bool:
        return bool(len(self.faces) > 0 and np.all(self.edge_use_counts() == 2))


def _orient_outward(surface: TriSurface) -> TriSurface:
    if surface.volume < 0:
        return TriSurface(surface.vertices, surface.faces[:, ::-1].copy())
    return surface


def revolve(x: np.ndarray, r: np.ndarray, n_around: int) -> TriSurface:
    """Closed surface of revolution about the x axis through stations (x, r); r must be 0 at both ends.

    Coordinates of the result: (x, radial 'up', thickness), i.e. the report frame of the SUBOFF equations.
    """
    if r[0] != 0 or r[-1] != 0 or np.any(r[1:-1] <= 0):
        raise GeometryError("a body of revolution needs zero radius at both tips and positive radius between")
    theta = np.linspace(0.0, 2.0 * np.pi, n_around, endpoint=False)
    # Scale the polygon so that its area equals the circle's: the discrete body then keeps the true
    # displaced volume instead of the inscribed polygon's smaller one.
    polygon_factor = np.sqrt(2.0 * np.pi / (n_around * np.sin(2.0 * np.pi / n_around)))
    inner_x, inner_r = x[1:-1], r[1:-1] * polygon_factor
    ring = np.stack(
        [
            np.repeat(inner_x, n_around),
            np.outer(inner_r, np.cos(theta)).ravel(),
            np.outer(inner_r, np.sin(theta)).ravel(),
        ],
        axis=1,
    )
    vertices = np.vstack([[x[0], 0.0, 0.0], ring, [x[-1], 0.0, 0.0]])
    n_rings = len(inner_x)
    j = np.arange(n_around)
    jn = (j + 1) % n_around
    faces = [np.column_stack([np.zeros(n_around, int), 1 + jn, 1 + j])]
    for i in range(n_rings - 1):
        a, b = 1 + i * n_around + j, 1 + i * n_around + jn
        c, d = b + n_around, a + n_around
        faces += [np.column_stack([a, b, c]), np.column_stack([a, c, d])]
    last = len(vertices) - 1
    base = 1 + (n_rings - 1) * n_around
    faces.append(np.column_stack([np.full(n_around, last), base + j, base + jn]))
    return _orient_outward(TriSurface(vertices, np.vstack(faces)))


def loft(rings: list[np.ndarray]) -> TriSurface:
    """Closed surface through a sequence of closed rings (each (n, 3), same n), capped by flat fans.

    The caps fan out from each end ring's centroid, so the end rings must be star-shaped about it
    (true for the aerofoil and sail sections used here).
    """
    rings = [np.asarray(r, dtype=float) for r in rings]
    n = len(rings[0])
    if len(rings) < 2 or any(len(r) != n for r in rings):
        raise GeometryError("a loft needs at least two rings with the same number of points")
    vertices = np.vstack([*rings, rings[0].mean(axis=0), rings[-1].mean(axis=0)])
    j = np.arange(n)
    jn = (j + 1) % n
    faces = []
    for i in range(len(rings) - 1):
        a, b = i * n + j, i * n + jn
        c, d = b + n, a + n
        faces += [np.column_stack([a, b, c]), np.column_stack([a, c, d])]
    first_centre, last_centre = len(vertices) - 2, len(vertices) - 1
    tail = (len(rings) - 1) * n
    faces.append(np.column_stack([np.full(n, first_centre), jn, j]))
    faces.append(np.column_stack([np.full(n, last_centre), tail + j, tail + jn]))
    return _orient_outward(TriSurface(vertices, np.vstack(faces)))


def _as_manifold(surface: TriSurface):
    return manifold3d.Manifold(
        manifold3d.Mesh64(
            vert_properties=np.ascontiguousarray(surface.vertices, dtype=np.float64),
            tri_verts=np.ascontiguousarray(surface.faces, dtype=np.uint64),
        )
    )


def _sections(surface: TriSurface, x: np.ndarray) -> list:
    """Manifold's sections of a closed surface by the planes x = const, in the coordinates (y, z)."""
    # Manifold slices normal to z, so turn the x axis onto z: (x, y, z) -> (y, z, x).
    solid = _as_manifold(surface).transform(np.array([[0.0, 1.0, 0, 0], [0, 0, 1.0, 0], [1.0, 0, 0, 0]]))
    return [solid.slice(float(h)) for h in np.atleast_1d(x)]


def cross_section_areas(surface: TriSurface, x: np.ndarray) -> np.ndarray:
    """Areas of the sections of a closed surface by the planes x = const (exact polygon areas)."""
    return np.array([section.area() for section in _sections(surface, x)])


def cross_section_contours(surface: TriSurface, x: np.ndarray) -> list[list[np.ndarray]]:
    """The closed contours of each section of a closed surface by the planes x = const: per station a list
    of (n, 2) arrays of (y, z); an outer contour turns from +y towards +z (positive signed area in the
    (y, z) plane), a hole the other way."""
    return [[np.asarray(contour, dtype=float) for contour in section.to_polygons()] for section in _sections(surface, x)]


def union_components(parts: dict[str, TriSurface]) -> tuple[TriSurface, np.ndarray]:
    """Boolean union of closed component surfaces into one watertight surface.

    Returns the united surface and, per face, the index (into ``list(parts)``) of the component it came
    from. Junctions are exact intersection curves, so components are closed onto each other (no gaps)
    and nothing of one component remains inside another.
    """
    names = list(parts)
    solids = []
    for name in names:
        solid = _as_manifold(parts[name])
        if solid.status() != manifold3d.Error.NoError or solid.is_empty():
            raise GeometryError(f"component {name!r} is not a closed oriented surface ({solid.status()})")
        solids.append(solid.as_original())
    ids = {solid.original_id(): k for k, solid in enumerate(solids)}
    united = manifold3d.Manifold.batch_boolean(solids, manifold3d.OpType.Add) if len(solids) > 1 else solids[0]
    out = united.to_mesh64()
    faces = np.asarray(out.tri_verts, dtype=np.int64)
    vertices = np.asarray(out.vert_properties, dtype=float)[:, :3]
    component = np.empty(len(faces), dtype=np.int64)
    run_index = np.asarray(out.run_index, dtype=np.int64) // 3
    for start, stop, original in zip(run_index[:-1], run_index[1:], out.run_original_id):
        component[start:stop] = ids[int(original)]
    # Merge coincident vertices that the mesh output may duplicate at run boundaries.
    merged, inverse = np.unique(np.round(vertices, 12), axis=0, return_inverse=True)
    surface = TriSurface(merged, inverse.reshape(-1)[faces])
    return surface, component
