"""Model files checked and simulated from Python."""

import math
import os

import numpy as np
import pytest

import mbexpr

A1 = """A1 {k}
DIFF/1, IC = 0, FUNCTION = DIF(2)
DIFF/2, IC = 5, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, {k}, 1.5, 50, 0.01)
END
"""


def test_check_model_lists_problems_with_lines_and_columns(tmp_path, examples):
    assert mbexpr.check_model(examples / "simulate" / "a1_ball.adm") == []
    broken = tmp_path / "broken.adm"
    broken.write_text("broken\nDIFF/1, IC = 0, FUNCTION = STEP(TIME, 0, 0, 1)\nEND\n")
    (found,) = mbexpr.check_model(broken)
    assert (found.line, found.column) == (2, 28)
    assert "STEP takes 5 arguments" in found.message
    with pytest.raises(mbexpr.Error, match="cannot read"):
        mbexpr.check_model(tmp_path / "missing.adm")


def test_a_path_to_no_file_raises_file_not_found_naming_it(tmp_path):
    # Each was read as model text: a parse error about the path's own words.
    for missing in ["missing.adm", "ball.ACF", "run.cmd", "model.dat", "scene.toml",
                    "models/a1", "runs/k=1e4/model.adm", str(tmp_path / "a1.adm"),
                    tmp_path / "a1"]:
        with pytest.raises(FileNotFoundError) as caught:
            mbexpr.simulate(missing, end=1.0, steps=1)
        assert caught.value.filename == os.fspath(missing), missing
        assert os.fspath(missing) in str(caught.value)
    # Model text stays text: a title that ends in .adm and holds a slash,
    # and a one-line dataset (only a title, so no state) with its `=`.
    text = "from models/a1.adm\nDIFF/1, IC = 0, FUNCTION = 1\nEND\n"
    assert mbexpr.simulate(text, end=1.0, steps=1)["DIF(1)"][-1] == pytest.approx(1.0)
    with pytest.raises(mbexpr.Error, match="no state"):
        mbexpr.simulate("DIFF/1, IC = 0, FUNCTION = 1", end=1.0, steps=1)


def test_a_free_flight_is_the_closed_form():
    # Between the walls the ball moves at 5 m/s: x = 5 t until t = 0.2.
    result = mbexpr.simulate(A1.format(k=1e5), end=0.15, steps=15, rtol=1e-10)
    assert list(result.columns) == ["time", "DIF(1)", "DIF(2)"]
    assert np.allclose(result["DIF(1)"], 5 * result.time, rtol=0, atol=1e-12)
    assert result.events == []
    assert result.statistics["steps"] > 0


def test_the_ball_rebounds_conserving_what_damping_leaves(examples):
    result = mbexpr.simulate(examples / "simulate" / "a1_ball.adm", end=1.0, steps=100, rtol=1e-8)
    # No deeper than the undamped wall lets a ball of 12.5 J in:
    # k p^2.5 / 2.5 = 12.5 gives p = 0.0398.
    deepest = (12.5 * 2.5 / 1e5) ** (1 / 2.5)
    assert 1 < result["DIF(1)"].max() <= 1 + deepest and result["DIF(1)"].min() >= -1 - deepest
    first = result.events[0]
    assert first.function == "BISTOP" and math.isclose(first.time, 0.2, rel_tol=1e-9)
    assert (first.line, first.column) == (8, 28)
    speed = abs(result["DIF(2)"][-1])
    assert 0 < speed < 5
    dop = mbexpr.simulate(examples / "simulate" / "a1_ball.adm", end=1.0, steps=100, rtol=1e-8, method="dop853")
    assert np.allclose(dop["DIF(1)"], result["DIF(1)"], atol=1e-5)


def test_refusals_name_their_place():
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.simulate("joint\nPART/1, GROUND\nUCON/1, FUNCTION = USER(1)\nEND\n", end=1, steps=1)
    assert caught.value.line == 3 and "constraint" in str(caught.value)
    with pytest.raises(mbexpr.Error, match="end time"):
        mbexpr.simulate(A1.format(k=1e5), end=-1.0, steps=10)
    with pytest.raises(mbexpr.Error, match="give the end time"):
        mbexpr.simulate(A1.format(k=1e5))
    with pytest.raises(mbexpr.Error):
        mbexpr.simulate(A1.format(k=1e5), end=1.0, steps=10, method="euler")


A4 = """A4
DIFF/1, IC = 0, FUNCTION = DIF(2)
DIFF/2, IC = 0, FUNCTION = BISTOP(DIF(1), DIF(2), -1, 1, 1e8, 1.5, 1e6, 1e-5) - 9.81
END
"""


def test_the_default_method_is_auto():
    # The dropped ball falls freely (DOP853) and turns stiff where it lands
    # in its damped stop at t = sqrt(2/9.81) = 0.4515 s: auto takes Radau5.
    result = mbexpr.simulate(A4, end=1.0, steps=10)
    ((time, from_method, to_method),) = result.statistics["method_changes"]
    assert (from_method, to_method) == ("dop853", "radau")
    assert 0.4515 <= time < 0.5
    for method in ("radau5", "dop853"):
        fixed = mbexpr.simulate(A4, end=1.0, steps=10, method=method)
        assert fixed.statistics["method_changes"] == []
        assert np.allclose(fixed["DIF(1)"], result["DIF(1)"], rtol=0, atol=1e-4)
    study = mbexpr.sweep(A4, [{}], end=1.0, steps=10)
    assert study["final DIF(1)"][0] == result["DIF(1)"][-1]


def test_every_problem_of_a_model_comes_with_its_place():
    broken = "two\nDIFF/1, IC = 0, FUNCTION = STEP(TIME, 0, 0, 1)\nDIFF/2, IC = 0, FUNCTION = DIF(3) + VARVAL(9)\nEND\n"
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.simulate(broken, end=1.0, steps=10)
    places = [(found.line, found.column) for found in caught.value.errors]
    assert places == [(2, 28), (3, 32), (3, 44)]
    assert (caught.value.line, caught.value.column) == (2, 28)
    assert len(str(caught.value).splitlines()) == 3


def test_a_scene_file_is_simulated(examples):
    result = mbexpr.simulate(examples / "scenes" / "ball_simulation.toml", rtol=1e-8)
    assert "ball.x" in result.columns and len(result.time) == 201
    text = (examples / "scenes" / "ball_simulation.toml").read_text()
    again = mbexpr.simulate(text, rtol=1e-8)
    assert np.array_equal(again["ball.x"], result["ball.x"])
