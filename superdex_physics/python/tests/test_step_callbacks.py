"""Pre- and post-step callbacks: order by priority then name, dt passed through, cancellation,
and an exception in a callback propagating out of step() as itself (traceback included)."""

import traceback

import pytest

import superdex.physics as sdp


def test_callbacks_run_in_priority_order(scene):
    calls = []
    scene.register_pre_step_callback("b", lambda s, dt: calls.append(("pre b", dt)), priority=10)
    scene.register_pre_step_callback("a", lambda s, dt: calls.append(("pre a", dt)), priority=10)
    scene.register_pre_step_callback("first", lambda s, dt: calls.append(("pre first", s.get_total_simulation_time())), priority=1)
    scene.register_post_step_callback("post", lambda s, dt: calls.append(("post", s.get_total_simulation_time())))
    scene.step(0.25)
    assert calls == [("pre first", 0.0), ("pre a", 0.25), ("pre b", 0.25), ("post", 0.25)]
    scene.cancel_callback("a")
    calls.clear()
    scene.step(0.25)
    assert [c[0] for c in calls] == ["pre first", "pre b", "post"]
    with pytest.raises(sdp.Error, match="no callback named 'a'"):
        scene.cancel_callback("a")


def test_exception_in_callback_propagates_with_traceback(scene):
    def broken(s, dt):
        raise KeyError("sensor lost")

    scene.register_pre_step_callback("broken", broken)
    with pytest.raises(KeyError, match="sensor lost") as info:
        scene.step(0.01)
    assert "broken" in "".join(traceback.format_tb(info.tb)), "the Python traceback is kept"
    # the failed step changed nothing and the scene stays usable
    assert scene.get_total_simulation_time() == 0
    scene.cancel_callback("broken")
    scene.step(0.01)
    assert scene.get_total_simulation_time() == pytest.approx(0.01)


def test_a_callback_may_change_the_callbacks_during_a_step(scene):
    # the callbacks registered when a step's pre- (post-) step phase began run in it; a change a
    # callback makes counts from the next phase on
    calls = []

    def changer(s, dt):
        calls.append("changer")
        s.cancel_callback("changer")
        s.cancel_callback("cancelled")
        s.register_pre_step_callback("added", lambda s, dt: calls.append("added"), priority=0)
        s.register_post_step_callback("replaced", lambda s, dt: calls.append("replaced, new"))

    scene.register_pre_step_callback("changer", changer, priority=1)
    scene.register_pre_step_callback("cancelled", lambda s, dt: calls.append("cancelled"), priority=2)
    scene.register_post_step_callback("replaced", lambda s, dt: calls.append("replaced, old"))
    scene.step(0.01)
    assert calls == ["changer", "cancelled", "replaced, new"]
    calls.clear()
    scene.step(0.01)
    assert calls == ["added", "replaced, new"]
