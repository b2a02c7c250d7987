"""The free-stream turbulence: one eddy viscosity, whichever variables a model transports."""

import pytest

from hydroderiv.case.fluid import C_MU, SA_CV1, TURBULENCE_MODELS, Fluid, FreestreamTurbulence


@pytest.mark.parametrize("model", sorted(TURBULENCE_MODELS))
def test_every_model_gets_the_free_stream_eddy_viscosity_ratio(model):
    free, nu, speed = FreestreamTurbulence(), Fluid().nu, 3.344
    values = {field: free.value(field, speed, nu) for field in TURBULENCE_MODELS[model]}
    if "R" in values:  # a Reynolds-stress model: the same k as half the stress's trace, isotropic, no shear
        xx, xy, xz, yy, yz, zz = values.pop("R")
        assert xx == yy == zz > 0 and xy == xz == yz == 0
        values["k"] = (xx + yy + zz) / 2
    assert all(v > 0 for v in values.values())
    if "omega" in values:
        eddy_viscosity = values["k"] / values["omega"]
    elif "epsilon" in values:
        eddy_viscosity = C_MU * values["k"] ** 2 / values["epsilon"]
    else:
        chi = values["nuTilda"] / nu
        eddy_viscosity = values["nuTilda"] * chi**3 / (chi**3 + SA_CV1**3)
    assert eddy_viscosity == pytest.approx(free.viscosity_ratio * nu, rel=1e-9)
    if "k" in values:  # k from the intensity: 1.5 (I U)^2
        assert values["k"] == pytest.approx(1.5 * (free.intensity * speed) ** 2)


def test_a_field_no_model_transports_is_named_in_the_error():
    with pytest.raises(ValueError, match="'nuTilde'"):
        FreestreamTurbulence().value("nuTilde", 3.344, Fluid().nu)
