"""Which wall reports of a finished record are made (again) from its saved solution."""

from hydroderiv.run.condition import lacking_wall_reports

SLICE = {"x_from": -2.3, "x_to": -1.8, "faces": 10, "mean": 50.0, "max": 60.0, "above_log_layer_pct": 0.0}
COMPLETE = {
    "reversed_flow": {"hull": {"area_m2": 6.0, "reversed_pct": 0.1}},
    "yplus_along_x": {"hull": [{**SLICE, "friction_mean": 52.0, "friction_max": 61.0}]},
    "loads_along_x": {"hull": [{"x_from": -2.3, "x_to": -1.8, "faces": 10, "Y": 1e-5, "Z": 0.0}]},
}


def test_a_complete_record_needs_nothing():
    assert lacking_wall_reports(COMPLETE) == []
    assert lacking_wall_reports({key: {} for key in COMPLETE}) == []  # a run without a body has empty reports


def test_absent_failed_and_older_reports_are_made_again():
    assert lacking_wall_reports({}) == list(COMPLETE)
    failed = {**COMPLETE, "loads_along_x": {"error": "p is missing"}}
    assert lacking_wall_reports(failed) == ["loads_along_x"]
    # y+ slices from before they gave the y+ from the wall shear stress
    older = {**COMPLETE, "yplus_along_x": {"hull": [SLICE]}}
    assert lacking_wall_reports(older) == ["yplus_along_x"]
