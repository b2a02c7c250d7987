import importlib.util
import shutil
from pathlib import Path

import pytest

from hydroderiv.geometry import suboff_body


@pytest.fixture(scope="session")
def suboff():
    """SUBOFF bodies at the default resolution, built once per test session."""
    cache = {}

    def get(config: str):
        if config not in cache:
            cache[config] = suboff_body(config)
        return cache[config]

    return get


_FOAM_HEADER = "FoamFile\n{{\n    version 2.0;\n    format ascii;\n    class {};\n    object {};\n}}\n"


@pytest.fixture
def strip_of_faces():
    """Builder of a hand-made ascii polyMesh under ``case/constant/polyMesh`` with one patch ``hull``: faces
    side by side along x, face k spanning x_edges[k] to x_edges[k + 1] at y = 0, one unit high in z, next
    to cell k (area vector (0, -width, 0)). Other files of the case (fields) are for the test to write."""

    def build(case, x_edges):
        mesh = case / "constant/polyMesh"
        mesh.mkdir(parents=True)
        n = len(x_edges) - 1
        points = [(x, 0, z) for x in x_edges for z in (0, 1)]
        faces = [(2 * k, 2 * k + 2, 2 * k + 3, 2 * k + 1) for k in range(n)]
        (mesh / "points").write_text(_FOAM_HEADER.format("vectorField", "points") + f"{len(points)}\n(\n"
                                     + "".join(f"({x} {y} {z})\n" for x, y, z in points) + ")\n")
        (mesh / "faces").write_text(_FOAM_HEADER.format("faceList", "faces") + f"{n}\n(\n"
                                    + "".join(f"4({' '.join(map(str, f))})\n" for f in faces) + ")\n")
        (mesh / "boundary").write_text(_FOAM_HEADER.format("polyBoundaryMesh", "boundary")
                                       + f"1\n(\n    hull\n    {{\n        type wall;\n        nFaces {n};\n        startFace 0;\n    }}\n)\n")
        (mesh / "owner").write_text(_FOAM_HEADER.format("labelList", "owner") + f"{n}\n(\n"
                                    + "".join(f"{k}\n" for k in range(n)) + ")\n")  # face k on cell k
        return mesh

    return build


@pytest.fixture(scope="session")
def openfoam():
    """Skip-free guard: OpenFOAM is part of the set-up, so its absence is an error, not a skip."""
    for application in ("blockMesh", "snappyHexMesh", "simpleFoam", "decomposePar", "mpirun"):
        assert shutil.which(application), f"{application} is not on PATH: run scripts/setup.sh"


@pytest.fixture(scope="session")
def coarse_bare_hull(tmp_path_factory, suboff, openfoam):
    """The coarse single mesh of the bare hull (AFF-1), built once for all OpenFOAM tests, with snappyHexMesh
    on 2 MPI ranks as studies build theirs."""
    from hydroderiv.mesh import build_mesh

    case = tmp_path_factory.mktemp("mesh") / "AFF-1-coarse"
    report = build_mesh(suboff("AFF-1"), "coarse", case, log=lambda message: None, n_procs=2)
    return case, report


@pytest.fixture(scope="session")
def load_script():
    """Loader of a script under scripts/ as a module (the scripts are not a package): load("compare_tables")."""

    def load(name: str):
        path = Path(__file__).resolve().parents[1] / "scripts" / f"{name}.py"
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module

    return load
