"""scripts/continue_condition.py: the schemes a continued copy runs on with another non-orthogonal
correction limit."""

from pathlib import Path

import pytest
from foamlib import FoamFile

from hydroderiv.case.numerics import write_numerics
from hydroderiv.errors import HydroderivError


@pytest.fixture
def schemes(tmp_path) -> Path:
    (tmp_path / "system").mkdir()
    write_numerics(tmp_path)
    return tmp_path / "system/fvSchemes"


@pytest.mark.parametrize("limit, written", [(1.0, "corrected"), (0.5, "limited corrected 0.5")])
def test_the_laplacian_and_sngrad_schemes_get_the_new_limit_and_nothing_else_changes(schemes, limit, written,
                                                                                    load_script):
    text = schemes.read_text()
    changed = load_script("continue_condition").with_non_orthogonal_correction(text, limit)
    schemes.write_text(changed)
    entries = FoamFile(schemes)
    words = lambda entry: " ".join(str(w) for w in entry) if not isinstance(entry, str) else entry
    assert words(entries["laplacianSchemes"]["default"]) == f"Gauss linear {written}"
    assert words(entries["snGradSchemes"]["default"]) == written
    # every other line as the set-up wrote it
    assert [a for a, b in zip(text.splitlines(), changed.splitlines()) if a != b] == [
        line for line in text.splitlines() if "limited corrected 0.33" in line]


def test_a_limit_out_of_range_or_a_case_already_changed_is_named(schemes, load_script):
    module = load_script("continue_condition")
    with pytest.raises(HydroderivError, match=r"must be in \(0, 1\]"):
        module.with_non_orthogonal_correction(schemes.read_text(), 1.5)
    changed = module.with_non_orthogonal_correction(schemes.read_text(), 1.0)
    with pytest.raises(HydroderivError, match="already changed"):
        module.with_non_orthogonal_correction(changed, 0.5)


def test_a_bad_limit_is_named_before_an_earlier_copy_is_removed(tmp_path, load_script):
    source, copy = tmp_path / "condition", tmp_path / "copy"
    (source / "system").mkdir(parents=True)
    write_numerics(source)
    (source / "262").mkdir()
    (source / "262" / "U").write_text("")
    copy.mkdir()
    (copy / "log.simpleFoam").write_text("an earlier continuation")
    with pytest.raises(HydroderivError, match=r"must be in \(0, 1\]"):
        load_script("continue_condition").continue_condition(source, 400, copy, 2, non_orthogonal_correction=0.0)
    assert (copy / "log.simpleFoam").read_text() == "an earlier continuation"
