"""Errors as Python exceptions, the progress callable, the GIL and Ctrl-C."""

import _thread
import threading
import time

import numpy
import pytest

import terratin

MILLION = 1_000_000


@pytest.fixture(scope="module")
def million_points():
    return numpy.random.default_rng(11).random((MILLION, 3))


def test_error_hierarchy():
    assert issubclass(terratin.Error, RuntimeError)
    for subclass in (
        terratin.InvalidInputError,
        terratin.IoError,
        terratin.CrsError,
        terratin.Cancelled,
    ):
        assert issubclass(subclass, terratin.Error)
    with pytest.raises(terratin.Error):
        terratin.triangulate(numpy.zeros((3, 3)))


def test_progress_is_called_with_fractions_and_messages():
    calls = []

    def progress(fraction, message):
        calls.append((fraction, message))
        return True

    terratin.triangulate(numpy.random.default_rng(1).random((20000, 3)), progress=progress)
    assert calls
    assert all(0.0 <= f <= 1.0 and isinstance(m, str) for f, m in calls)


def test_progress_returning_none_continues():
    vertices, _ = terratin.triangulate(
        numpy.random.default_rng(1).random((2000, 3)), progress=lambda f, m: None
    )
    assert len(vertices) == 2000


@pytest.mark.parametrize("function", ["triangulate", "simplify"])
def test_progress_returning_false_raises_cancelled(function):
    rng = numpy.random.default_rng(2)
    with pytest.raises(terratin.Cancelled):
        if function == "triangulate":
            terratin.triangulate(rng.random((20000, 3)), progress=lambda f, m: False)
        else:
            terratin.simplify(
                rng.random((200, 200)), (0, 1, 0, 0, 0, -1), max_error=0.01,
                progress=lambda f, m: False,
            )


def test_exception_in_progress_propagates():
    class Stop(Exception):
        pass

    def progress(fraction, message):
        raise Stop("from the callable")

    with pytest.raises(Stop, match="from the callable"):
        terratin.triangulate(numpy.random.default_rng(3).random((20000, 3)), progress=progress)


def test_other_python_threads_run_while_the_library_works(million_points):
    count = 0
    stop = threading.Event()

    def counter():
        nonlocal count
        while not stop.is_set():
            count += 1

    thread = threading.Thread(target=counter)
    thread.start()
    try:
        before = count
        terratin.triangulate(million_points, threads=1)
        during = count - before
    finally:
        stop.set()
        thread.join()
    # With the GIL held by the call, the counter could not move at all meanwhile.
    assert during > 10000


def test_ctrl_c_cancels_the_library(million_points):
    started = threading.Event()

    def progress(fraction, message):
        started.set()
        return True

    def interrupt():
        started.wait()
        _thread.interrupt_main()

    threading.Thread(target=interrupt, daemon=True).start()
    finished = False
    with pytest.raises(KeyboardInterrupt):
        try:
            terratin.triangulate(million_points, method="sequential", threads=1, progress=progress)
            finished = True
        finally:
            if finished:
                time.sleep(5)  # a late interrupt lands here, not in another test
    assert not finished, "the triangulation ran to its end despite Ctrl-C"


def test_ctrl_c_cancels_the_library_without_a_progress_callable(million_points):
    timer = threading.Timer(0.2, _thread.interrupt_main)
    timer.start()
    finished = False
    with pytest.raises(KeyboardInterrupt):
        try:
            terratin.triangulate(million_points, method="sequential", threads=1)
            finished = True
        finally:
            timer.join()
            if finished:
                time.sleep(5)
    assert not finished, "the triangulation ran to its end despite Ctrl-C"
