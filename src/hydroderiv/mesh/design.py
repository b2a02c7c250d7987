"""The numbers of the single mesh: domain, rotating sphere, refinement levels and prism layers.

One mesh serves every condition. The domain is a cube centred at the moment centre B with a sphere of
radius 2L (the rotating zone of the hybrid frames, as in the seed paper's Fig. 4) snapped inside it.
Levels coarse/medium/fine differ only in the base cell size, by a constant ratio, so that they form a
systematic family for a grid-convergence study; all refinement levels are relative to the base cell.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Mapping

from ..errors import ConfigurationError

REFINEMENT_RATIO = math.sqrt(2.0)  # base cell size ratio between successive levels

# Shift of the background grid, in base cells. A cube centred exactly on B puts grid planes through the
# hull axis at every refinement level, so the nose tip becomes a vertex shared by four cells; layered, those
# cells made simpleFoam blow up at the nose (760 m/s there after 50 iterations on the medium AFF-8 mesh).
# A third of a base cell is 1/3 or 2/3 of a cell at every refinement level (1/3 = 0.0101... in binary), so the
# axis never comes closer than a third of a cell to a grid plane. The y shift is a mesh option
# (MeshDesign.grid_shift_y, whose default is GRID_SHIFT[1]): at 0, y = 0 is a grid plane at every level
# and the mesh mirrors about the vertical centre plane, while the z shift still keeps the axis off every
# grid line.
GRID_SHIFT = (1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0)
LEVELS = ("coarse", "medium", "fine")


@dataclass(frozen=True)
class LayerDesign:
    """Prism layers sized for wall functions from a flat-plate skin-friction estimate."""

    first_thickness: float  # m
    expansion: float
    count: int
    yplus_target: float  # at the first cell centre, at the design speed

    @property
    def total_thickness(self) -> float:
        e = self.expansion
        return self.first_thickness * (e**self.count - 1.0) / (e - 1.0)

    @property
    def final_thickness(self) -> float:
        return self.first_thickness * self.expansion ** (self.count - 1)


def friction_velocity(speed: float, length: float, nu: float) -> float:
    """u_tau from the ITTC-1957 line Cf = 0.075 / (log10 Re - 2)^2, an average over the hull."""
    reynolds = speed * length / nu
    cf = 0.075 / (math.log10(reynolds) - 2.0) ** 2
    return speed * math.sqrt(cf / 2.0)


def first_cell_yplus(first_thickness: float, speed: float, length: float, nu: float) -> float:
    """y+ at the centre of the first prism cell (what OpenFOAM's yPlus reports)."""
    return friction_velocity(speed, length, nu) * 0.5 * first_thickness / nu


@dataclass(frozen=True)
class MeshDesign:
    """Everything that sets the mesh of one body at one level."""

    level: str
    length: float  # reference length L, m
    body_radius: float  # largest distance of the body from the x axis, m
    body_x_min: float  # aft end of the body, m
    body_x_max: float  # nose, m
    design_speed: float = 3.344  # m/s: 6.5 knots, the speed of Roddy's captive tests
    nu: float = 0.001053 / 998.55  # water at 18 C (Roddy 1990)
    domain_half_width_L: float = 4.0
    sphere_radius_L: float = 2.0
    coarse_base_cell_L: float = 0.235  # base (blockMesh) cell of the coarse level, in L
    hull_surface_level: int = 5
    # Sail and appendages are thin lifting parts: surface cells two levels finer than the hull's (8 mm on
    # the coarse mesh, about 45 along the sail's chord and 5 across a stern appendage). With one level the
    # sail's flow separated from mid-chord: it gave side force at zero drift (AFF-8 medium, 1.6e-4) and
    # about half its lift at drift (runs of 2026-11-22, recorded in the issue-4 notes).
    appendage_extra_level: int = 2
    # extra levels on the sail and appendages where the surface turns by more than resolveFeatureAngle within
    # a cell: their rounded leading edges (radius ~1.1 t^2/c, about one surface cell) and tip caps
    thin_curvature_levels: int = 0
    # at most this many prism layers on the sail and appendages: the hull's full stack (about 20 mm) is more
    # than half the sail's half-thickness, and snappy then shrinks or drops the layers near the thin edges.
    # Four layers (5 mm) with their own minimum thickness survive on 75 % of the sail's faces.
    thin_max_layers: int = 4
    # Shift of the background grid in y, in base cells (see GRID_SHIFT). 0 makes the mesh
    # mirror-symmetric about y = 0, so that a symmetric body feels no side force at zero incidence from
    # lopsided snapping; a thin part whose mid-plane then lies on a grid plane may snap badly at its root.
    grid_shift_y: float = GRID_SHIFT[1]
    sphere_surface_level: int = 2
    sphere_inside_level: int = 1
    # Move the snapped interface of the rotating sphere exactly onto the sphere (see mesh/interface.py):
    # MRF's flux correction then vanishes there and uniform flow stays uniform through it. Meshes built
    # before this option existed have the interface as snapped (False).
    interface_on_sphere: bool = True
    yplus_target: float = 50.0
    # Prism-layer thicknesses relative to the local surface cell (snappy's relativeSizes) instead of absolute.
    # Absolute, the hull's stack (about 20 mm) is sized for the hull's own surface cells (31 mm coarse) and is
    # two thirds of a cell or more where the hull's cells are finer, next to the sail and the appendage
    # roots; snappy drops it there for mesh quality (the coarse AFF-8 hull: 77.7 % of its faces with any
    # layer). Relative, each part's stack is scaled so that it has its absolute design on that part's
    # nominal cells, and shrinks with the cells elsewhere (its first cell's y+ with it).
    relative_layer_sizes: bool = False
    # Extra refinement levels in a cylinder about the aft part of the body (the tail cone and the appendage
    # roots). There the hull's layers collapse on the curved surface, and the first cells of the hull's own
    # level put y+ at 100-500 (medium AFF-8, 2026-12-02), where the stern's boundary layer feeds the
    # appendages and sets the rotary loads. Finer cells there snap closer and put the first cell lower. One
    # level on the coarse AFF-8 mesh took the tail cone's y+ from 190-520 to 40-160 and left the hull's N'r
    # unchanged (studies/aff8-coarse-stern-refined.toml), so it is off by default.
    stern_extra_level: int = 0
    stern_region_length_L: float = 0.3  # from the aft end of the body forward, in L
    stern_region_radius_L: float = 0.08  # about the x axis, in L: SUBOFF's appendage tips are at 0.06 L
    layer_expansion: float = 1.3
    final_layer_fraction: float = 0.3  # final layer thickness over the surface cell size
    max_layers: int = 8
    min_layers: int = 3

    def __post_init__(self):
        if self.level not in LEVELS:
            raise ConfigurationError(f"unknown mesh level {self.level!r}; choose one of {', '.join(LEVELS)}")

    @property
    def half_width(self) -> float:
        return self.domain_half_width_L * self.length

    @property
    def sphere_radius(self) -> float:
        return self.sphere_radius_L * self.length

    @property
    def base_cells(self) -> int:
        """Base cells along each side of the cube."""
        target = self.coarse_base_cell_L * self.length / REFINEMENT_RATIO ** LEVELS.index(self.level)
        return max(4, round(2.0 * self.half_width / target))

    @property
    def base_cell(self) -> float:
        return 2.0 * self.half_width / self.base_cells

    def cell_at(self, level: int) -> float:
        return self.base_cell / 2**level

    @property
    def hull_cell(self) -> float:
        return self.cell_at(self.hull_surface_level)

    def layers(self) -> LayerDesign:
        """The hull's prism layers: the first cell sized for y+, growing to a fraction of the surface cell."""
        u_tau = friction_velocity(self.design_speed, self.length, self.nu)
        first = 2.0 * self.yplus_target * self.nu / u_tau
        wanted_final = self.final_layer_fraction * self.hull_cell
        e = self.layer_expansion
        count = 1 + math.ceil(math.log(max(wanted_final / first, 1.0)) / math.log(e))
        count = max(self.min_layers, min(self.max_layers, count))
        return LayerDesign(first, e, count, self.yplus_target)

    def layers_of(self, component: str) -> LayerDesign:
        """The prism layers of one body part: the hull's, with at most ``thin_max_layers`` on a thin part."""
        hull = self.layers()
        if not is_thin_part(component):
            return hull
        return dataclasses.replace(hull, count=min(hull.count, self.thin_max_layers))

    def surface_level_of(self, component: str) -> int:
        """The surface refinement level of one body part: the hull's, or the thin parts' finer one."""
        return self.hull_surface_level + (self.appendage_extra_level if is_thin_part(component) else 0)

    def surface_cell_of(self, component: str) -> float:
        """The nominal surface cell of one body part, m."""
        return self.cell_at(self.surface_level_of(component))

    def min_layer_thickness(self, component: str) -> float:
        """Below this total thickness snappy drops a part's layers: a quarter of that part's own stack.

        One absolute value for every patch would be a quarter of the hull's stack, which on a thin part with
        fewer layers may be most of its whole stack, so its layers would be dropped wherever they shrink.
        """
        return 0.25 * self.layers_of(component).total_thickness

    def location_in_mesh(self) -> tuple[float, float, float]:
        """A point in the fluid, outside the sphere and off every cell face (snappy needs one)."""
        r = 0.5 * (self.sphere_radius + self.half_width)
        return (r + 0.0123, 0.0137, 0.0171)


# What the body and the speed decide; every other MeshDesign field is a meshing option a user may set.
_FROM_THE_BODY = ("level", "length", "body_radius", "body_x_min", "body_x_max", "design_speed")


# Values MeshDesign fields had before the field existed: a mesh report that lacks one of these was built to
# this value (other missing fields are not compared, see mesh/snappy.py).
BEFORE_THE_FIELD = {"interface_on_sphere": False, "relative_layer_sizes": False, "stern_extra_level": 0}

_TRUE, _FALSE = ("true", "yes", "on", "1"), ("false", "no", "off", "0")


def mesh_options(options: Mapping[str, object], source: str = "mesh options") -> dict[str, int | float | bool]:
    """Check meshing options (a study's [mesh] table, ``--mesh KEY=VALUE``) and convert their values.

    Raises :class:`ConfigurationError` naming an unknown option or a value of the wrong kind.
    ``mesher = "revolution"`` asks for the body-fitted mesh of a body of revolution instead of snappyHexMesh
    (mesh/revolution.py), with that mesher's own options.
    """
    if "mesher" in options:
        mesher = str(options["mesher"]).strip().lower()
        rest = {k: v for k, v in options.items() if k != "mesher"}
        if mesher == "revolution":
            from .revolution import revolution_options

            return {"mesher": "revolution", **revolution_options(rest, source)}
        if mesher != "snappy":
            raise ConfigurationError(f"{source}: unknown mesher {options['mesher']!r}; choose snappy or revolution")
        options = rest
    kinds = {f.name: {"int": int, "bool": bool}.get(f.type, float) for f in dataclasses.fields(MeshDesign)
             if f.name not in _FROM_THE_BODY}
    return checked_options(options, kinds, source)


def checked_options(options: Mapping[str, object], kinds: Mapping[str, type], source: str) -> dict:
    """``options`` converted to ``kinds`` (option name -> int, float or bool), or a ConfigurationError naming
    the unknown option or the value of the wrong kind."""
    checked = {}
    for name, value in options.items():
        if name not in kinds:
            raise ConfigurationError(f"{source}: unknown mesh option {name!r}; options are {', '.join(sorted(kinds))}")
        if kinds[name] is bool:
            word = str(value).strip().lower()
            if word not in _TRUE + _FALSE:
                raise ConfigurationError(f"{source}: mesh option {name} = {value!r} must be true or false")
            checked[name] = word in _TRUE
            continue
        try:
            number = float(value)
        except (TypeError, ValueError):
            raise ConfigurationError(f"{source}: mesh option {name} = {value!r} is not a number")
        if kinds[name] is int and number != int(number):
            raise ConfigurationError(f"{source}: mesh option {name} = {value!r} must be a whole number")
        checked[name] = kinds[name](number)
    return checked


def is_thin_part(component: str) -> bool:
    """The sail and the appendages are thin lifting parts; everything about them differs from the hull's."""
    return component != "hull"
