"""scripts/compare_tables.py: a rerun's loads and derivatives against the table it checks."""

import json
from pathlib import Path


def _table(path: Path, side_force: float, iterations: int, yv: float) -> Path:
    record = {"name": "U3_b+4", "iterations": iterations,
              "coefficients": {"X": -1.2e-3, "Y": side_force, "Z": 0.0, "K": 0.0, "M": 0.0, "N": 1e-3}}
    path.write_text(json.dumps({"Yv": yv, "conditions": [record]}))
    return path


def test_changes_are_relative_to_the_reference_and_small_loads_are_left_out(tmp_path, capsys, load_script):
    new = _table(tmp_path / "new.json", side_force=2.02e-3, iterations=321, yv=-0.0255)
    reference = _table(tmp_path / "reference.json", side_force=2.0e-3, iterations=271, yv=-0.0250)
    assert load_script("compare_tables").main([str(new), str(reference)]) == 0
    out = capsys.readouterr().out
    assert "321/271" in out
    assert "Y' +1.00" in out and "X' +0.00" in out
    assert "Z'" not in out.split("\n")[1]  # a zero load has no relative change
    assert "largest load change: 1.00 %" in out
    assert "-2.00 %" in out  # Y'v 2 % larger in magnitude, signed as the value moved


def test_tables_without_shared_conditions_are_refused(tmp_path, capsys, load_script):
    new = _table(tmp_path / "new.json", 2e-3, 300, -0.025)
    reference = tmp_path / "reference.json"
    reference.write_text(json.dumps({"conditions": [{"name": "other", "coefficients": {}}]}))
    assert load_script("compare_tables").main([str(new), str(reference)]) == 1
    assert "no condition" in capsys.readouterr().err
