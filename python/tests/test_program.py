"""Compiled expressions over numpy arrays: values and exact derivatives
against closed forms and finite differences, broadcasting, strided arrays,
errors with their place, pickling, the GIL released, fork after bulk work."""

import multiprocessing
import pickle
import threading
import time

import numpy as np
import pytest

import mbexpr

SPRING = "-k*x - c*v"


def test_spring_damper_value_gradient_hessian_are_the_closed_forms():
    program = mbexpr.compile(SPRING, ["x", "v", "k", "c"])
    rng = np.random.default_rng(1)
    x, v, k, c = (rng.uniform(-2, 2, 1000) for _ in range(4))
    value, gradient, hessian = program.hessian(x, v, k, c)
    assert np.array_equal(value, -k * x - c * v)
    assert np.allclose(gradient, np.stack([-k, -c, -x, -v], axis=-1), rtol=0, atol=0)
    expected = np.zeros((1000, 4, 4))
    expected[:, 0, 2] = expected[:, 2, 0] = -1
    expected[:, 1, 3] = expected[:, 3, 1] = -1
    assert np.array_equal(hessian, expected)


def test_derivatives_agree_with_central_differences_at_random_points():
    program = mbexpr.compile("BISTOP(x, v, -1, 1, 1e5, 2.2, 50, 0.1) + SIN(x*v)", ["x", "v"])
    rng = np.random.default_rng(2)
    x = rng.uniform(-1.09, 1.09, 2000)
    v = rng.uniform(-3, 3, 2000)
    _, gradient = program.gradient(x=x, v=v)
    h = 1e-7
    for i, (dx, dv) in enumerate([(h, 0.0), (0.0, h)]):
        difference = (program.value(x + dx, v + dv) - program.value(x - dx, v - dv)) / (2 * h)
        scale = np.abs(gradient[:, i]) + 1.0
        # Away from the kinks (|x| = 1, 1 - 0.1), where a difference straddles one.
        smooth = (np.abs(np.abs(x) - 1) > 1e-5) & (np.abs(np.abs(x) - 0.9) > 1e-5)
        assert np.all(np.abs(difference - gradient[:, i])[smooth] <= 1e-5 * scale[smooth])


def test_inputs_broadcast_by_position_or_name_and_strided_arrays_are_read():
    program = mbexpr.compile("x * 10 + y", ["x", "y"])
    x = np.arange(12.0).reshape(3, 4)
    assert np.array_equal(program.value(x, 1.0), x * 10 + 1)
    assert np.array_equal(program.value(y=np.arange(4.0), x=x[:, :1]), x[:, :1] * 10 + np.arange(4.0))
    strided = np.arange(20.0)[::2]
    assert np.array_equal(program.value(strided, strided[::-1]), strided * 10 + strided[::-1])
    transposed = x.T
    assert np.array_equal(program.value(transposed, 0), transposed * 10)
    assert program.value(2, 3).shape == ()
    _, gradient, hessian = program.hessian(x, 0.5, wrt=["y"])
    assert gradient.shape == (3, 4, 1) and hessian.shape == (3, 4, 1, 1)
    assert np.all(gradient == 1)


def test_threads_give_the_same_numbers():
    program = mbexpr.compile("IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1) * STEP(x, 0, 0, 2, 1)", ["x", "v"])
    x = np.linspace(-1, 3, 100_001)
    results = [program.gradient(x, -1.0, threads=threads) for threads in (1, 2, 0)]
    for value, gradient in results[1:]:
        assert np.array_equal(value, results[0][0])
        assert np.array_equal(gradient, results[0][1])


def test_errors_carry_line_and_column_and_are_value_errors():
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.compile("1 +\n  STEP(x, 0, 0, 1)", ["x"])
    assert isinstance(caught.value, ValueError)
    assert (caught.value.line, caught.value.column) == (2, 3)
    assert "STEP takes 5 arguments" in caught.value.message
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.compile("x + spped", ["x", "speed"])
    assert caught.value.column == 5 and "speed" in str(caught.value)
    program = mbexpr.compile("2 * LOG(x)", ["x"])
    with pytest.raises(mbexpr.Error) as caught:
        program.value(np.array([1.0, 2.0, 0.0, -1.0]))
    assert caught.value.point == 2 and caught.value.column == 5
    values, status = program.value(np.array([1.0, 0.0, np.e]), errors="status")
    assert status.tolist() == [0, 1, 0] and values.tolist() == [0.0, 0.0, 2.0]
    assert not np.isnan(values).any()
    with pytest.raises(mbexpr.Error):
        program.value(np.inf)
    with pytest.raises(TypeError):
        program.value(1.0, y=2.0)


def test_every_compile_error_comes_with_its_place():
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.compile("spped * x +\n  LOG(y) + z", ["x"])
    error = caught.value
    places = [(found.line, found.column) for found in error.errors]
    assert places == [(1, 1), (2, 7), (2, 12)]
    assert [found.message for found in error.errors] == [f"{name} has no value" for name in ("spped", "y", "z")]
    assert (error.line, error.column, error.message) == (1, 1, error.errors[0].message)
    assert str(error).splitlines() == [str(found) for found in error.errors]
    # The checker's problems, each once: the compiler runs only on what checks.
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.compile("STEP(x, 0, 0, 1) +\n SQRT(x, 2)", ["x"])
    assert [(found.line, found.column) for found in caught.value.errors] == [(1, 1), (2, 2)]
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.compile("x +", ["x"])
    assert len(caught.value.errors) == 1 and str(caught.value.errors[0]) == str(caught.value)


def test_programs_pickle_as_their_text():
    program = mbexpr.compile("BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.01)", ["x", "v"])
    again = pickle.loads(pickle.dumps(program))
    assert again.text == program.text and again.inputs == program.inputs
    assert again.value(1.005, 0.7) == program.value(1.005, 0.7)


def test_bulk_evaluation_releases_the_gil():
    program = mbexpr.compile("SQRT(x*x + 1) * ATAN(x) + EXP(-x*x)", ["x"])
    x = np.linspace(-3, 3, 3_000_000)
    counts = []
    stop = threading.Event()

    def spin():
        count = 0
        while not stop.is_set():
            count += 1
        counts.append(count)

    spinner = threading.Thread(target=spin)
    spinner.start()
    started = time.perf_counter()
    program.hessian(x, threads=1)
    elapsed = time.perf_counter() - started
    stop.set()
    spinner.join()
    # With the GIL held, the spinning thread would barely run.
    assert counts[0] > 10_000 * elapsed


def _child_evaluates(queue):
    program = mbexpr.compile("x * 2", ["x"])
    queue.put(float(program.value(np.arange(10_000.0)).sum()))


def test_a_child_forked_after_bulk_work_does_not_hang():
    mbexpr.compile("x + 1", ["x"]).value(np.arange(100_000.0), threads=2)
    context = multiprocessing.get_context("fork")
    queue = context.Queue()
    child = context.Process(target=_child_evaluates, args=(queue,))
    child.start()
    child.join(60)
    hung = child.is_alive()
    if hung:
        child.kill()
    assert not hung
    assert queue.get(timeout=5) == 2 * sum(range(10_000))


def test_utilities_over_arrays_with_iord():
    x = np.array([-1.05, 0.0, 1.05])
    vector = mbexpr.bistop(x, 0.7, -1, 1, 1e5, 1.5, 50, 0.1, iord=0)
    assert vector.shape == (3, 3) and vector[1, 0] == 0.0
    program = mbexpr.compile("BISTOP(x, v, -1, 1, 1e5, 1.5, 50, 0.1)", ["x", "v"])
    value, gradient, hessian = program.hessian(x, 0.7)
    assert np.array_equal(vector[:, 0], value)
    assert np.array_equal(mbexpr.bistop(x, 0.7, -1, 1, 1e5, 1.5, 50, 0.1, iord=1)[:, :2], gradient)
    assert np.array_equal(mbexpr.bistop(x, 0.7, -1, 1, 1e5, 1.5, 50, 0.1, iord=2)[:, :2], hessian[:, 0, :])
    assert np.array_equal(
        mbexpr.impact(x, -1.0, 1, 1e4, 1.5, 10, 0.1, iord=1)[:, :2],
        mbexpr.compile("IMPACT(x, v, 1, 1e4, 1.5, 10, 0.1)", ["x", "v"]).gradient(x, -1.0)[1],
    )
    s = np.linspace(-0.5, 1.5, 9)
    assert np.allclose(mbexpr.step(s, 0, 0, 1, 10), 10 * np.clip(s, 0, 1) ** 2 * (3 - 2 * np.clip(s, 0, 1)))
    assert mbexpr.step(s, 0, 0, 1, 10, iord=2).shape == (9,)
    with pytest.raises(mbexpr.Error) as caught:
        mbexpr.bistop(x, 0.7, 1, 1, 1e5, 1.5, 50, 0.1)
    assert "point 0" in str(caught.value)
    with pytest.raises(mbexpr.Error):
        mbexpr.step(0.5, 0, 0, 1, 1, iord=3)


def test_columns_of_unequal_length_and_repeated_inputs_are_refused():
    # The private bulk entry points check what the public ones broadcast.
    from mbexpr import _core

    one = np.ones(3)
    with pytest.raises(ValueError, match="argument 2 has 1 values"):
        _core.utility_bulk("step", [one * 0.5, np.zeros(1), one * 0, one, one], 0)
    with pytest.raises(mbexpr.Error, match="repeats input 1"):
        mbexpr.compile("x", ["x", "X"])


def test_a_program_without_inputs_evaluates_to_its_constant():
    program = mbexpr.compile("2 + 3", [])
    assert program.value() == 5.0
    value, gradient = program.gradient()
    assert value == 5.0 and gradient.shape == (0,)
