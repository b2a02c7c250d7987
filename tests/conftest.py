import shutil

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
