"""Mesh quality read back from snappy's output (no OpenFOAM needed: the files are written here)."""

from hydroderiv.mesh.quality import layer_coverage, layers_along_x

LAYER_FIELD = """FoamFile
{
    version     2.0;
    format      ascii;
    class       volScalarField;
    object      nSurfaceLayers;
}
dimensions      [0 0 0 0 0 0 0];
internalField   uniform 0;
boundaryField
{
    farfield
    {
        type            calculated;
        value           uniform 0;
    }
    hull
    {
        type            calculated;
        value           nonuniform List<scalar> 4(8 8 5 0);
    }
    sail
    {
        type            calculated;
        value           nonuniform List<scalar> 4(4 4 4 2);
    }
}
"""


def test_layer_coverage_counts_each_patch_against_its_own_layer_count(tmp_path):
    (tmp_path / "0").mkdir()
    (tmp_path / "0/nSurfaceLayers").write_text(LAYER_FIELD)
    cover = layer_coverage(tmp_path, {"hull": 8, "sail": 4})
    assert cover["hull"] == {"faces": 4, "any_layer_pct": 75.0, "layers_wanted": 8, "all_layers_pct": 50.0,
                             "mean_layers": 5.25}
    # the sail asked for 4 layers: three faces have all of them, although none has the hull's 8
    assert cover["sail"]["all_layers_pct"] == 75.0
    assert cover["sail"]["any_layer_pct"] == 100.0


def test_layer_coverage_is_empty_without_snappys_layer_field(tmp_path):
    assert layer_coverage(tmp_path, {"hull": 8}) == {}


def _strip_of_faces(case, layers):
    """A patch ``hull`` of unit squares side by side along x (x in [k, k + 1], y = 0), with snappy's layer
    count ``layers[k]`` on face k."""
    mesh = case / "constant/polyMesh"
    mesh.mkdir(parents=True)
    header = "FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {};\n    object {};\n}}\n"
    n = len(layers)
    points = [(x, 0, z) for x in range(n + 1) for z in (0, 1)]
    faces = [(2 * k, 2 * k + 2, 2 * k + 3, 2 * k + 1) for k in range(n)]
    (mesh / "points").write_text(header.format("vectorField", "points") + f"{len(points)}\n(\n"
                                 + "".join(f"({x} {y} {z})\n" for x, y, z in points) + ")\n")
    (mesh / "faces").write_text(header.format("faceList", "faces") + f"{n}\n(\n"
                                + "".join(f"4({' '.join(map(str, f))})\n" for f in faces) + ")\n")
    (mesh / "boundary").write_text(header.format("polyBoundaryMesh", "boundary")
                                   + f"1\n(\n    hull\n    {{\n        type wall;\n        nFaces {n};\n        startFace 0;\n    }}\n)\n")
    (case / "0").mkdir()
    values = " ".join(str(v) for v in layers)
    (case / "0/nSurfaceLayers").write_text(header.format("volScalarField", "nSurfaceLayers")
                                           + "dimensions [0 0 0 0 0 0 0];\ninternalField uniform 0;\nboundaryField\n{\n"
                                           + f"    hull\n    {{\n        type calculated;\n        value nonuniform List<scalar> {n}({values});\n    }}\n}}\n")


def test_layers_along_x_show_where_along_the_body_snappy_kept_them(tmp_path):
    # aft half fully layered, fore half: one face without layers and one with two
    _strip_of_faces(tmp_path, [8, 8, 0, 2])
    aft, fore = layers_along_x(tmp_path, "hull", bins=2)
    assert (aft["x_from"], aft["x_to"], fore["x_to"]) == (0.5, 2.0, 3.5)  # face centres 0.5 ... 3.5
    assert aft == {**aft, "faces": 2, "any_layer_pct": 100.0, "mean_layers": 8.0, "face_size_mm": 1000.0}
    assert fore == {**fore, "faces": 2, "any_layer_pct": 50.0, "mean_layers": 1.0}
    assert layers_along_x(tmp_path / "elsewhere", "hull") == []  # no layer field: nothing to report
