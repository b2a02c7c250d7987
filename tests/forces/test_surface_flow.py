"""The wall reports on hand-made meshes: reversed flow (face areas, the sign of the wall shear, the turning
stream), y+ along the body and the loads along it."""

import numpy as np
import pytest

from hydroderiv.errors import HydroderivError
from hydroderiv.forces import PrimeScales
from hydroderiv.forces.surface_flow import (describe_reversed_flow, describe_yplus_along_x, friction_yplus, loads_along_x,
                                            reversed_flow, yplus_along_x)
from hydroderiv.mesh.quality import patch_faces, patch_owners

HEADER = "FoamFile\n{{\n    version 2.0;\n    format {fmt};\n    class {cls};\n    object {obj};\n}}\n"

# a box x in [0, 2], y in [-1, 1], z in [0, 1]: faces 0-3 stand for the rest of the mesh; the walls are the
# side at y = -1 (face 4) and the side at y = +1 (face 5), 2 m^2 each, and the nose x = 2 (face 6), 2 m^2
POINTS = [(0, -1, 0), (2, -1, 0), (2, 1, 0), (0, 1, 0), (0, -1, 1), (2, -1, 1), (2, 1, 1), (0, 1, 1)]
FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 4, 7, 3), (0, 1, 5, 4), (0, 1, 5, 4), (3, 7, 6, 2), (1, 2, 6, 5)]


def _mesh(tmp_path, fmt="ascii"):
    mesh = tmp_path / "constant/polyMesh"
    mesh.mkdir(parents=True)
    (mesh / "points").write_text(HEADER.format(fmt=fmt, cls="vectorField", obj="points")
                                 + f"\n{len(POINTS)}\n(\n" + "".join(f"({x} {y} {z})\n" for x, y, z in POINTS) + ")\n")
    (mesh / "faces").write_text(HEADER.format(fmt="ascii", cls="faceList", obj="faces")
                                + f"\n{len(FACES)}\n(\n" + "".join(f"4({' '.join(map(str, f))})\n" for f in FACES) + ")\n")
    (mesh / "boundary").write_text(HEADER.format(fmt="ascii", cls="polyBoundaryMesh", obj="boundary") + """
2
(
    sides
    {
        type            wall;
        inGroups        1(wall);
        nFaces          2;
        startFace       4;
    }
    nose
    {
        type            wall;
        nFaces          1;
        startFace       6;
    }
)
""")
    return mesh


def _shear(tmp_path, sides, nose):
    def values(vectors):
        return f"nonuniform List<vector> {len(vectors)}(" + " ".join(f"({a} {b} {c})" for a, b, c in vectors) + ")"

    time_dir = tmp_path / "100"
    time_dir.mkdir()
    (time_dir / "wallShearStress").write_text(HEADER.format(fmt="ascii", cls="volVectorField", obj="wallShearStress") + f"""
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{{
    sides {{ type calculated; value {values(sides)}; }}
    nose {{ type calculated; value {values(nose)}; }}
}}
""")
    return time_dir


def test_face_areas_and_centres_come_from_the_patch_faces(tmp_path):
    faces = patch_faces(_mesh(tmp_path), ["sides", "nose"])
    centres, areas = faces["sides"]
    assert np.allclose(centres, [[1, -1, 0.5], [1, 1, 0.5]])
    assert np.allclose(np.linalg.norm(areas, axis=1), [2.0, 2.0])
    assert np.allclose(np.abs(areas[:, 1]), [2.0, 2.0])  # normal to y
    assert np.allclose(faces["nose"][0], [[2, 0, 0.5]])


def test_shear_against_the_stream_is_attached_flow_and_along_it_reversed(tmp_path):
    mesh = _mesh(tmp_path)
    # the stream runs aft (-x); attached flow at the wall runs aft too, so the wall's stress on the fluid
    # points forward (+x). One side attached, the other running forward; the nose attached.
    time_dir = _shear(tmp_path, sides=[(0.5, 0, 0), (-0.2, 0.1, 0)], nose=[(0, 0.3, 0)])
    report = reversed_flow(time_dir, patch_faces(mesh, ["sides", "nose"]), inflow=np.array([-3.0, 0.0, 0.0]))
    assert report["sides"] == {"area_m2": 4.0, "reversed_pct": 50.0}
    assert report["nose"]["reversed_pct"] == 0.0  # a shear across the stream is not reversed flow
    assert "sides 50.0 %" in describe_reversed_flow(report)
    assert "nose" not in describe_reversed_flow(report)


def test_in_a_turn_each_face_is_judged_against_its_own_stream(tmp_path):
    mesh = _mesh(tmp_path)
    # Omega = (0, 0, 2) rad/s: the stream U_inf - Omega x r is -3 + 2*1 = -1 m/s at y = +1 but
    # -3 - 2 = -5 m/s at y = -1, so both still run aft; at 4 rad/s the one at y = +1 runs forward (+1 m/s).
    time_dir = _shear(tmp_path, sides=[(0.5, 0, 0), (0.5, 0, 0)], nose=[(0.5, 0, 0)])
    inflow = np.array([-3.0, 0.0, 0.0])
    slow = reversed_flow(time_dir, patch_faces(mesh, ["sides"]), inflow, angular_velocity=np.array([0.0, 0.0, 2.0]))
    fast = reversed_flow(time_dir, patch_faces(mesh, ["sides"]), inflow, angular_velocity=np.array([0.0, 0.0, 4.0]))
    assert slow["sides"]["reversed_pct"] == 0.0
    assert fast["sides"]["reversed_pct"] == 50.0


def test_missing_field_unknown_patch_and_binary_mesh_are_named(tmp_path):
    mesh = _mesh(tmp_path)
    with pytest.raises(HydroderivError, match="wallShearStress is missing"):
        reversed_flow(tmp_path, patch_faces(mesh, ["sides"]), np.array([-1.0, 0, 0]))
    with pytest.raises(HydroderivError, match="no patch 'sail'"):
        patch_faces(mesh, ["sail"])
    binary = _mesh(tmp_path / "binary", fmt="binary")
    with pytest.raises(HydroderivError, match="binary"):
        patch_faces(binary, ["sides"])
    assert describe_reversed_flow({"error": "boom"}) == "reversed flow not reported: boom"
    assert describe_reversed_flow({"hull": {"area_m2": 6.0, "reversed_pct": 0.2}}) is None


def _yplus(case, values):
    time_dir = case / "200"
    time_dir.mkdir()
    (time_dir / "yPlus").write_text(HEADER.format(fmt="ascii", cls="volScalarField", obj="yPlus") + f"""
dimensions      [0 0 0 0 0 0 0];
internalField   uniform 0;
boundaryField
{{
    hull {{ type calculated; value nonuniform List<scalar> {len(values)}({' '.join(map(str, values))}); }}
}}
""")
    return time_dir


def test_yplus_along_x_weights_by_area_and_finds_the_slice_beyond_the_log_layer(tmp_path, strip_of_faces):
    # aft slice: faces 3 m and 1 m wide (x 0..3, 3..4) at y+ 400 and 40; fore slice: 1 m and 3 m at 50 and 70
    mesh = strip_of_faces(tmp_path, [0, 3, 4, 5, 8])
    time_dir = _yplus(tmp_path, [400, 40, 50, 70])
    aft, fore = yplus_along_x(time_dir, patch_faces(mesh, ["hull"]), "hull", bins=2)
    assert (aft["x_from"], aft["x_to"], fore["x_to"]) == (1.5, 4.0, 6.5)  # face centres 1.5, 3.5, 4.5, 6.5
    assert aft == {**aft, "faces": 2, "mean": 310.0, "max": 400.0, "above_log_layer_pct": 75.0}
    assert fore == {**fore, "faces": 2, "mean": 65.0, "max": 70.0, "above_log_layer_pct": 0.0}
    line = describe_yplus_along_x({"hull": [aft, fore]})
    assert line == "hull y+ along x, aft to fore: 310 65 (% of area above 300: 75 0)"
    assert describe_yplus_along_x({}) is None
    resolved = [{**aft, "mean": 0.53, "above_log_layer_pct": 0.0}, {**fore, "mean": 1.2, "above_log_layer_pct": 0.0}]
    assert describe_yplus_along_x({"hull": resolved}) == "hull y+ along x, aft to fore: 0.53 1.2 (% of area above 300: 0 0)"
    with pytest.raises(HydroderivError, match="yPlus is missing"):
        yplus_along_x(tmp_path, patch_faces(mesh, ["hull"]), "hull")


def _wall_law_fields(time_dir, wall_law, k_cells, shear):
    """nut with ``wall_law`` on the hull, k in the cells next to it and the wall shear stress on it."""
    (time_dir / "nut").write_text(HEADER.format(fmt="ascii", cls="volScalarField", obj="nut") + f"""
dimensions      [0 2 -1 0 0 0 0];
internalField   uniform 0;
boundaryField
{{
    hull {{ type {wall_law}; Cmu 0.09; value uniform 0; }}
}}
""")
    (time_dir / "k").write_text(HEADER.format(fmt="ascii", cls="volScalarField", obj="k") + f"""
dimensions      [0 2 -2 0 0 0 0];
internalField   nonuniform List<scalar> {len(k_cells)}({' '.join(map(str, k_cells))});
boundaryField
{{
    hull {{ type kqRWallFunction; value uniform 0; }}
}}
""")
    vectors = " ".join(f"({a} {b} {c})" for a, b, c in shear)
    (time_dir / "wallShearStress").write_text(HEADER.format(fmt="ascii", cls="volVectorField", obj="wallShearStress") + f"""
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{{
    hull {{ type calculated; value nonuniform List<vector> {len(shear)}({vectors}); }}
}}
""")


def test_yplus_from_the_wall_shear_recovers_the_distance_from_a_k_based_wall_law(tmp_path, strip_of_faces):
    mesh = strip_of_faces(tmp_path, [0, 1, 2])
    time_dir = _yplus(tmp_path, [0.1, 60.0])
    # a resolved sublayer (k small) reads 0.1 from k; the log layer is in equilibrium, u_tau^2 = C_mu^0.5 k
    u_tau = 0.12
    k_cells = [1e-6, u_tau**2 / 0.3]
    _wall_law_fields(time_dir, "nutkWallFunction", k_cells, [(-0.0144, 0, 0), (u_tau**2, 0, 0)])
    owners = patch_owners(mesh, ["hull"])["hull"]
    friction = friction_yplus(time_dir, "hull", np.array([0.1, 60.0]), owners)
    # y_P / nu = 0.1 / (0.09^0.25 * 1e-3) = 182.6; times u_tau = 0.12 gives 21.9
    assert friction == pytest.approx([0.1 * 0.12 / (0.09**0.25 * 1e-3), 60.0])
    aft, fore = yplus_along_x(time_dir, patch_faces(mesh, ["hull"]), "hull", bins=2, owners=owners)
    assert (aft["mean"], aft["friction_mean"], fore["friction_mean"]) == (0.1, 21.9, 60.0)
    line = describe_yplus_along_x({"hull": [aft, fore]})
    assert line.endswith("; from the wall shear stress: 22 60")
    # without the cells next to the faces only OpenFOAM's own y+ is given
    assert "friction_mean" not in yplus_along_x(time_dir, patch_faces(mesh, ["hull"]), "hull", bins=2)[0]


def test_other_wall_laws_already_report_the_friction_yplus(tmp_path, strip_of_faces):
    mesh = strip_of_faces(tmp_path, [0, 1, 2])
    time_dir = _yplus(tmp_path, [1.5, 40.0])
    owners = patch_owners(mesh, ["hull"])["hull"]
    assert friction_yplus(time_dir, "hull", np.array([1.5, 40.0]), owners) is None  # no wall shear, no nut
    _wall_law_fields(time_dir, "nutUSpaldingWallFunction", [0.0, 0.0], [(0.01, 0, 0), (0.01, 0, 0)])
    assert friction_yplus(time_dir, "hull", np.array([1.5, 40.0]), owners) == pytest.approx([1.5, 40.0])
    _wall_law_fields(time_dir, "nutkWallFunction", [0.0, 0.04 / 0.3], [(0.01, 0, 0), (0.04, 0, 0)])
    # a cell without turbulence energy gives no distance: OpenFOAM's value stands there
    assert friction_yplus(time_dir, "hull", np.array([1.5, 40.0]), owners) == pytest.approx([1.5, 40.0])


def _pressure_and_shear(case, pressure, shear):
    time_dir = case / "300"
    time_dir.mkdir()
    (time_dir / "p").write_text(HEADER.format(fmt="ascii", cls="volScalarField", obj="p") + f"""
dimensions      [0 2 -2 0 0 0 0];
internalField   {pressure};
boundaryField
{{
    hull {{ type zeroGradient; }}
}}
""")
    (time_dir / "wallShearStress").write_text(HEADER.format(fmt="ascii", cls="volVectorField", obj="wallShearStress") + f"""
dimensions      [0 2 -2 0 0 0 0];
internalField   uniform (0 0 0);
boundaryField
{{
    hull {{ type calculated; value uniform ({shear}); }}
}}
""")
    return time_dir


def test_loads_along_x_add_the_pressure_of_the_next_cell_and_the_wall_shear_per_slice(tmp_path, strip_of_faces):
    # four 1 m^2 faces along x with the fluid on their +y side (area vectors (0, -1, 0)): the fore half
    # at a suction, the aft half at an overpressure, as on a fin whose aft half pulls against its fore half
    mesh = strip_of_faces(tmp_path, [0, 1, 2, 3, 4])
    time_dir = _pressure_and_shear(tmp_path, "nonuniform List<scalar> 4(3 2 -1 -1)", "0.5 0.2 0.1")
    faces, owners = patch_faces(mesh, ["hull"]), patch_owners(mesh, ["hull"])
    assert owners["hull"].tolist() == [0, 1, 2, 3]
    scales = PrimeScales(rho=2.0, speed=1.0, length=1.0)  # 0.5 rho U^2 L^2 = 1 N
    aft, fore = loads_along_x(time_dir, faces, owners, scales, bins=2)["hull"]
    # each face: rho (p S_f - |S_f| tau_w) = 2 (-0.5, -p - 0.2, -0.1): the overpressure pushes towards -y,
    # the shear stress on the fluid is the opposite of the fluid's pull on the wall
    assert (aft["x_from"], aft["x_to"], fore["x_to"]) == (0.5, 2.0, 3.5)
    assert aft == {**aft, "faces": 2, "Y": pytest.approx(-10.8), "Z": pytest.approx(-0.4)}
    assert fore == {**fore, "faces": 2, "Y": pytest.approx(3.2), "Z": pytest.approx(-0.4)}
    # twice the speed: a quarter of the coefficients
    faster = loads_along_x(time_dir, faces, owners, PrimeScales(2.0, 2.0, 1.0), bins=2)["hull"]
    assert [s["Y"] for s in faster] == pytest.approx([-2.7, 0.8])


def test_loads_along_x_take_a_uniform_pressure_and_name_what_is_missing(tmp_path, strip_of_faces):
    mesh = strip_of_faces(tmp_path, [0, 1, 2])
    faces, owners = patch_faces(mesh, ["hull"]), patch_owners(mesh, ["hull"])
    with pytest.raises(HydroderivError, match="p is missing: the run wrote no pressure"):
        loads_along_x(tmp_path, faces, owners, PrimeScales(2.0, 1.0, 1.0))
    time_dir = _pressure_and_shear(tmp_path, "uniform 1", "0 0 0")
    (whole,) = loads_along_x(time_dir, faces, owners, PrimeScales(2.0, 1.0, 1.0), bins=1)["hull"]
    assert whole == {**whole, "faces": 2, "Y": pytest.approx(-4.0), "Z": 0.0}
    with pytest.raises(HydroderivError, match="1 owner cells for 2 faces"):
        loads_along_x(time_dir, faces, {"hull": owners["hull"][:1]}, PrimeScales(2.0, 1.0, 1.0))
    shear = time_dir / "wallShearStress"
    shear.write_text(shear.read_text().replace("uniform (0 0 0); }", "nonuniform List<vector> 3((0 0 0) (0 0 0) (0 0 0)); }"))
    with pytest.raises(HydroderivError, match="3 values on hull, but the mesh has 2 faces"):
        loads_along_x(time_dir, faces, owners, PrimeScales(2.0, 1.0, 1.0))
