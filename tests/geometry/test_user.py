"""A user's own STL: checked before anything runs, and every problem named in a clear error."""

import numpy as np
import pytest

from hydroderiv.errors import GeometryError
from hydroderiv.geometry import Body, load_user_body
from hydroderiv.geometry.stl import write_stl
from hydroderiv.geometry.surfaces import TriSurface


def _write(path, surface, names=("hull",), component=None):
    component = np.zeros(len(surface.faces), int) if component is None else component
    write_stl(path, surface, component, names)
    return path


@pytest.fixture(scope="module")
def bare_hull(suboff):
    return suboff("AFF-1").surface


def test_a_good_file_round_trips_with_its_reference_quantities(tmp_path, suboff):
    aff8 = suboff("AFF-8")
    aff8.write(tmp_path)
    # the same surface, given in nose-origin coordinates with the moment centre named there
    shifted = TriSurface(aff8.surface.vertices + [5.0, 0.0, 0.0], aff8.surface.faces)
    path = _write(tmp_path / "mine.stl", shifted, aff8.component_names, aff8.face_component)
    body = load_user_body(path, reference_length=4.261, moment_centre=(5.0, 0.0, 0.0))
    assert body.component_names == aff8.component_names
    assert body.reference.volume == pytest.approx(aff8.reference.volume, rel=1e-9)
    assert body.reference.wetted_area == pytest.approx(aff8.reference.wetted_area, rel=1e-9)
    np.testing.assert_allclose(body.surface.bounds, aff8.surface.bounds, atol=1e-8)
    # the largest section is at the sail: more than the hull's 0.508 m, less than hull + sail bounding box
    assert 0.508 < body.reference.max_diameter < 0.56
    again = Body.read(tmp_path)
    assert again.component_names == aff8.component_names and again.surface.is_watertight()
    assert again.reference == aff8.reference


def test_an_inside_out_file_is_turned_round(tmp_path, bare_hull):
    inside_out = TriSurface(bare_hull.vertices, bare_hull.faces[:, ::-1])
    body = load_user_body(_write(tmp_path / "flip.stl", inside_out), 4.261, (0, 0, 0))
    assert body.reference.volume == pytest.approx(0.6992, rel=0.002)


def test_open_surface_is_refused(tmp_path, bare_hull):
    holed = TriSurface(bare_hull.vertices, bare_hull.faces[10:])
    with pytest.raises(GeometryError, match="open"):
        load_user_body(_write(tmp_path / "open.stl", holed), 4.261, (0, 0, 0))


@pytest.mark.parametrize("scale, unit", [(1000.0, "millimetres"), (100.0, "centimetres"), (1 / 0.3048, "feet")])
def test_wrong_units_are_named(tmp_path, bare_hull, scale, unit):
    scaled = TriSurface(bare_hull.vertices * scale, bare_hull.faces)
    with pytest.raises(GeometryError, match=f"implausible units.*{unit}"):
        load_user_body(_write(tmp_path / "units.stl", scaled), 4.261, (0, 0, 0))


def test_reference_length_in_the_wrong_unit_is_named(tmp_path, bare_hull):
    with pytest.raises(GeometryError, match="reference length given in metres"):
        load_user_body(_write(tmp_path / "ok.stl", bare_hull), 4261.0, (0, 0, 0))


@pytest.mark.parametrize(
    "content, words",
    [
        (b"", "empty"),
        (b"   \n", "empty"),
        (b"solid x\nendsolid x\n", "no triangles"),
        (b"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n", "truncated"),
        (b"solid x\n facet normal 0 0 1\n outer loop\n vertex 0 zero 0\n", "non-numeric"),
        (b"hello world\n", "unexpected keyword"),
        (b"\x00\xff" * 100, "neither a valid binary STL"),
    ],
)
def test_malformed_files_are_named(tmp_path, content, words):
    path = tmp_path / "bad.stl"
    path.write_bytes(content)
    with pytest.raises(GeometryError, match=words):
        load_user_body(path, 4.261, (0, 0, 0))


def test_missing_file_is_named(tmp_path):
    with pytest.raises(GeometryError, match="no such STL file"):
        load_user_body(tmp_path / "nothing.stl", 4.261, (0, 0, 0))


def test_binary_stl_is_read(tmp_path, bare_hull):
    import trimesh

    path = tmp_path / "binary.stl"
    trimesh.Trimesh(bare_hull.vertices, bare_hull.faces, process=False).export(path, file_type="stl")
    assert path.read_bytes()[:5] != b"solid"
    body = load_user_body(path, 4.261, (0, 0, 0))
    assert body.component_names == ("hull",)
    assert body.reference.volume == pytest.approx(0.6992, rel=0.002)


def test_flat_body_is_degenerate(tmp_path):
    # a closed but flat "body": a tetrahedron squashed into a plane
    v = np.array([[0, 0, 0], [4.3, 0, 0], [0, 0.5, 0], [1.0, 0.2, 0.0]], float)
    f = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    with pytest.raises(GeometryError, match="degenerate"):
        load_user_body(_write(tmp_path / "flat.stl", TriSurface(v, f)), 4.261, (0, 0, 0))


def test_inconsistent_normals_are_named(tmp_path, bare_hull):
    faces = bare_hull.faces.copy()
    faces[::7] = faces[::7, ::-1]
    with pytest.raises(GeometryError, match="inconsistent"):
        load_user_body(_write(tmp_path / "mixed.stl", TriSurface(bare_hull.vertices, faces)), 4.261, (0, 0, 0))


def test_bad_solid_name_and_moment_centre_are_named(tmp_path, bare_hull):
    half = np.arange(len(bare_hull.faces)) % 2
    path = _write(tmp_path / "names.stl", bare_hull, ("hull", "my fin!"), half)
    with pytest.raises(GeometryError, match="solid name 'my fin!'"):
        load_user_body(path, 4.261, (0, 0, 0))
    good = _write(tmp_path / "good.stl", bare_hull)
    with pytest.raises(GeometryError, match="moment centre"):
        load_user_body(good, 4.261, (40.0, 0, 0))
    with pytest.raises(GeometryError, match="reference length must be a positive"):
        load_user_body(good, -1.0, (0, 0, 0))
