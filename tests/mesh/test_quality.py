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


def _layered_strip(case, strip_of_faces, layers):
    """A strip of unit squares along x (x in [k, k + 1]) with snappy's layer count ``layers[k]`` on face k."""
    strip_of_faces(case, list(range(len(layers) + 1)))
    header = "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class volScalarField;\n    object nSurfaceLayers;\n}\n"
    (case / "0").mkdir()
    values = " ".join(str(v) for v in layers)
    (case / "0/nSurfaceLayers").write_text(header + "dimensions [0 0 0 0 0 0 0];\ninternalField uniform 0;\nboundaryField\n{\n"
                                           + f"    hull\n    {{\n        type calculated;\n        value nonuniform List<scalar> {len(layers)}({values});\n    }}\n}}\n")


def test_layers_along_x_show_where_along_the_body_snappy_kept_them(tmp_path, strip_of_faces):
    # aft half fully layered, fore half: one face without layers and one with two
    _layered_strip(tmp_path, strip_of_faces, [8, 8, 0, 2])
    aft, fore = layers_along_x(tmp_path, "hull", bins=2)
    assert (aft["x_from"], aft["x_to"], fore["x_to"]) == (0.5, 2.0, 3.5)  # face centres 0.5 ... 3.5
    assert aft == {**aft, "faces": 2, "any_layer_pct": 100.0, "mean_layers": 8.0, "face_size_mm": 1000.0}
    assert fore == {**fore, "faces": 2, "any_layer_pct": 50.0, "mean_layers": 1.0}
    assert layers_along_x(tmp_path / "elsewhere", "hull") == []  # no layer field: nothing to report
