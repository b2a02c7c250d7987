"""A user's own body from an STL file, checked before anything else runs."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import GeometryError
from .body import Body, ReferenceQuantities
from .stl import read_stl
from .surfaces import TriSurface, cross_section_areas

# Length units a CAD export commonly uses, as metres per unit, to name the likely mistake.
_UNITS = {"millimetres": 1e-3, "centimetres": 1e-2, "inches": 0.0254, "feet": 0.3048}
_PATCH_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


def check_closed_surface(surface: TriSurface, source: str) -> TriSurface:
    """Raise :class:`GeometryError` unless ``surface`` is a closed, consistently oriented, solid body.

    Returns the surface with outward normals (an inside-out but otherwise sound file is turned round).
    """
    counts = surface.edge_use_counts()
    open_edges = int(np.sum(counts == 1))
    non_manifold = int(np.sum(counts > 2))
    if open_edges:
        raise GeometryError(
            f"{source}: the surface is open: {open_edges} edges belong to only one triangle "
            "(holes or gaps); a body must be a closed, watertight surface"
        )
    if non_manifold:
        raise GeometryError(f"{source}: {non_manifold} edges are shared by more than two triangles (non-manifold surface)")
    if not surface.is_consistently_oriented():
        raise GeometryError(f"{source}: triangle normals are inconsistent (neighbouring faces point opposite ways)")
    if surface.volume < 0:
        surface = TriSurface(surface.vertices, surface.faces[:, ::-1].copy())
    extent = np.ptp(surface.vertices, axis=0)
    if extent.min() <= 1e-3 * extent.max():
        raise GeometryError(f"{source}: the body is degenerate: flat, extents {extent.round(6).tolist()} m")
    if surface.volume <= 1e-4 * float(np.prod(extent)):
        raise GeometryError(f"{source}: the body is degenerate: it encloses almost no volume ({surface.volume:.3g} m^3)")
    return surface


def check_units(length_in_file: float, reference_length: float, source: str) -> None:
    """Raise if the file's length along x is implausible for the stated reference length (in metres)."""
    ratio = length_in_file / reference_length
    if 0.5 <= ratio <= 2.0:
        return
    guess = min(_UNITS, key=lambda unit: abs(np.log(ratio * _UNITS[unit])))
    hint = ""
    if abs(np.log(ratio * _UNITS[guess])) < np.log(2.0):
        hint = f"; the file looks like it is in {guess}: scale it by {_UNITS[guess]:g} to metres"
    elif ratio < 0.5:
        hint = "; is the reference length given in metres?"
    raise GeometryError(
        f"{source}: implausible units: the body is {length_in_file:.6g} long along x but the reference length is "
        f"{reference_length:g} m (ratio {ratio:.3g}); STL coordinates must be in metres{hint}"
    )


def _max_equivalent_diameter(surface: TriSurface) -> float:
    """Diameter of the circle with the area of the largest cross-section normal to x."""
    lo, hi = surface.bounds[:, 0]
    areas = cross_section_areas(surface, np.linspace(lo, hi, 202)[1:-1])
    return float(2.0 * np.sqrt(areas.max() / np.pi))


def load_user_body(
    path: str | Path,
    reference_length: float,
    moment_centre: tuple[float, float, float],
    name: str | None = None,
) -> Body:
    """Read a closed STL (metres; x forward, y starboard, z down) and check it before anything else runs.

    ``moment_centre`` is given in the file's coordinates; the returned body is translated so that it is
    the origin. Each ``solid`` of an ASCII file becomes a named component (its forces are reported apart).
    """
    path = Path(path)
    source = str(path)
    if not np.isfinite(reference_length) or reference_length <= 0:
        raise GeometryError(f"{source}: the reference length must be a positive number of metres, got {reference_length}")
    centre = np.asarray(moment_centre, dtype=float)
    if centre.shape != (3,) or not np.all(np.isfinite(centre)):
        raise GeometryError(f"{source}: the moment centre must be three finite coordinates, got {moment_centre}")
    surface, face_component, names = read_stl(path)
    if len(names) == 1:
        names = ["hull"]
    for solid in names:
        if not _PATCH_NAME.match(solid):
            raise GeometryError(
                f"{source}: solid name {solid!r} cannot name a component; use letters, digits and '_', "
                "starting with a letter"
            )
    if len(set(names)) != len(names):
        raise GeometryError(f"{source}: two solids share a name; each component needs its own")
    check_units(float(np.ptp(surface.vertices[:, 0])), reference_length, source)
    surface = check_closed_surface(surface, source)
    lo, hi = surface.bounds
    if not np.all((lo - 0.5 * reference_length <= centre) & (centre <= hi + 0.5 * reference_length)):
        raise GeometryError(f"{source}: the moment centre {centre.tolist()} lies far outside the body {lo.tolist()}..{hi.tolist()}")
    surface = TriSurface(surface.vertices - centre, surface.faces)
    reference = ReferenceQuantities(
        length=float(reference_length),
        moment_centre=tuple(float(c) for c in centre),
        moment_centre_frame=f"coordinates of {path.name}",
        volume=surface.volume,
        wetted_area=surface.area,
        max_diameter=_max_equivalent_diameter(surface),
    )
    return Body(name or path.stem, surface, tuple(names), face_component, reference)
