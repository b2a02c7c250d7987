"""Warm starts: a solved internal field moves into a new case byte for byte, under the new boundary conditions."""

import struct

import numpy as np
import pytest
from foamlib import FoamFieldFile

from hydroderiv._foam import write_foam_dict
from hydroderiv.case.warm_start import take_internal_field
from hydroderiv.errors import ConfigurationError

HEADER = (
    'FoamFile\n{{\n    version     2.0;\n    format      {format};\n    class       volVectorField;\n'
    '    arch        "LSB;label=32;scalar=64";\n    location    "188";\n    object      U;\n}}\n\n'
    "dimensions      [0 1 -1 0 0 0 0];\n\n\n"
)


def _solved_binary(path, values: np.ndarray) -> None:
    """A field file as simpleFoam writes it with writeFormat binary; its boundary data is binary too."""
    blob = values.astype("<f8").tobytes()
    body = (
        HEADER.format(format="binary").encode()
        + f"internalField   nonuniform List<vector> \n{len(values)}\n(".encode() + blob + b")\n;\n\n"
        + b"boundaryField\n{\n    farfield\n    {\n        type            freestreamVelocity;\n"
        + b"        freestreamValue uniform (-3 0.2 0);\n        value           nonuniform List<vector> \n2\n("
        + struct.pack("<6d", 1, 2, 3, 4, 5, 6) + b")\n;\n    }\n}\n"
    )
    path.write_bytes(body)


def _new_case_field(path, inflow) -> None:
    write_foam_dict(
        path,
        {
            "dimensions": "[0 1 -1 0 0 0 0]",
            "internalField": inflow,
            "boundaryField": {"farfield": {"type": "freestreamVelocity", "freestreamValue": inflow}},
        },
        foam_class="volVectorField",
    )


def test_a_binary_solution_becomes_the_internal_field_and_the_new_inflow_stays(tmp_path):
    rng = np.random.default_rng(1)
    # values whose bytes contain the keyword the splice looks for must not cut the field short
    solved = rng.normal(size=(5, 3))
    solved[2] = np.frombuffer(b"\nboundaryField\n{" + b"\x00" * 8, dtype="<f8")
    (tmp_path / "188").mkdir()
    (tmp_path / "0").mkdir()
    _solved_binary(tmp_path / "188/U", solved)
    _new_case_field(tmp_path / "0/U", [-3.3, -0.23, 0.0])

    take_internal_field(tmp_path / "0/U", tmp_path / "188/U", n_cells=5)

    field = FoamFieldFile(tmp_path / "0/U")
    np.testing.assert_array_equal(np.asarray(field.internal_field), solved)
    farfield = field.boundary_field["farfield"]
    assert np.allclose(farfield["freestreamValue"], [-3.3, -0.23, 0.0])
    assert "value" not in farfield  # the solved case's boundary values are gone
    assert b'location    "0"' in (tmp_path / "0/U").read_bytes()


def test_an_ascii_solution_is_taken_as_well(tmp_path):
    solved = np.arange(12.0).reshape(4, 3)
    (tmp_path / "0").mkdir()
    write_foam_dict(
        tmp_path / "source",
        {"dimensions": "[0 1 -1 0 0 0 0]", "internalField": solved,
         "boundaryField": {"farfield": {"type": "zeroGradient"}}},
        foam_class="volVectorField",
    )
    _new_case_field(tmp_path / "0/U", [-1.0, 0.0, 0.0])
    take_internal_field(tmp_path / "0/U", tmp_path / "source", n_cells=4)
    field = FoamFieldFile(tmp_path / "0/U")
    np.testing.assert_array_equal(np.asarray(field.internal_field), solved)
    assert field.boundary_field["farfield"]["type"] == "freestreamVelocity"


def test_a_solution_from_another_mesh_is_refused_by_name(tmp_path):
    (tmp_path / "0").mkdir()
    _solved_binary(tmp_path / "U.solved", np.zeros((5, 3)))
    _new_case_field(tmp_path / "0/U", [-1.0, 0.0, 0.0])
    before = (tmp_path / "0/U").read_bytes()
    with pytest.raises(ConfigurationError, match=r"U.solved.* 5 cell values, the mesh has 7 cells"):
        take_internal_field(tmp_path / "0/U", tmp_path / "U.solved", n_cells=7)
    assert (tmp_path / "0/U").read_bytes() == before
