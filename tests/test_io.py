"""_io: atomic writes leave a complete file or none, with the permissions a plain write would give."""

import os
import stat

import pytest

from hydroderiv._io import atomic_write_bytes, atomic_write_text


@pytest.fixture
def umask_022():
    previous = os.umask(0o022)
    yield
    os.umask(previous)


def _mode(path):
    return stat.S_IMODE(path.stat().st_mode)


def test_a_new_file_gets_the_umask_permissions_not_the_temporary_files_owner_only_ones(tmp_path, umask_022):
    path = tmp_path / "derivatives.json"
    atomic_write_text(path, "{}\n")
    assert path.read_text() == "{}\n"
    assert _mode(path) == 0o644


def test_a_rewritten_file_keeps_its_own_permissions(tmp_path, umask_022):
    path = tmp_path / "result.json"
    path.write_text("old")
    path.chmod(0o640)
    atomic_write_text(path, "new")
    assert path.read_text() == "new"
    assert _mode(path) == 0o640


def test_a_failed_write_leaves_the_old_file_and_no_temporary_file(tmp_path):
    path = tmp_path / "result.json"
    path.write_text("finished result")

    with pytest.raises(TypeError):
        atomic_write_bytes(path, object())  # not bytes: the write itself fails
    assert path.read_text() == "finished result"
    assert [p.name for p in tmp_path.iterdir()] == ["result.json"]
