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
