"""Mesh quality read back from snappy's output (no OpenFOAM needed: the files are written here)."""

from hydroderiv.mesh.quality import layer_coverage

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
