"""Pre- and post-step callbacks: order by priority then registration, the StepInfo (scene and
time step) passed through, cancellation by handle, and an exception in a callback propagating
out of step() as itself (traceback included)."""

import traceback

import pytest

import superdex.physics as sdp


def test_callbacks_run_in_priority_order(scene):
    calls = []
    scenes = []
    # equal priorities run in registration order: "b" (registered first) before "a"
    scene.register_pre_step_callback("b", lambda info: calls.append(("pre b", info.time_step_sec)), priority=10)
    a = scene.register_pre_step_callback("a", lambda info: calls.append(("pre a", info.time_step_sec)), priority=10)
    scene.register_pre_step_callback(
        "first", lambda info: calls.append(("pre first", info.scene.get_total_simulation_time())), priority=1)
    scene.register_post_step_callback("post", lambda info: (calls.append(("post", info.scene.get_total_simulation_time())),
                                                            scenes.append(info.scene)))
    scene.step(0.25)
    assert calls == [("pre first", 0.0), ("pre b", 0.25), ("pre a", 0.25), ("post", 0.25)]
    assert scenes == [scene]
    assert isinstance(a, sdp.CallbackHandle) and a.is_valid()
    scene.cancel_callback(a)
    calls.clear()
    scene.step(0.25)
    assert [c[0] for c in calls] == ["pre first", "pre b", "post"]
    # cancelling a cancelled or invalid handle has no effect (SuperDex)
    scene.cancel_callback(a)
    scene.cancel_callback(sdp.CallbackHandle())
    calls.clear()
    scene.step(0.25)
    assert [c[0] for c in calls] == ["pre first", "pre b", "post"]


def test_exception_in_callback_propagates_with_traceback(scene):
    def broken(info):
        raise KeyError("sensor lost")

    handle = scene.register_pre_step_callback("broken", broken)
    with pytest.raises(KeyError, match="sensor lost") as info:
        scene.step(0.01)
    assert "broken" in "".join(traceback.format_tb(info.tb)), "the Python traceback is kept"
    # the failed step changed nothing and the scene stays usable
    assert scene.get_total_simulation_time() == 0
    scene.cancel_callback(handle)
    scene.step(0.01)
    assert scene.get_total_simulation_time() == pytest.approx(0.01)


def test_a_callback_may_change_the_callbacks_during_a_step(scene):
    # the callbacks registered when a step's pre- (post-) step phase began run in it; a change a
    # callback makes counts from the next phase on
    calls = []
    handles = {}

    def changer(info):
        s = info.scene
        calls.append("changer")
        s.cancel_callback(handles["changer"])
        s.cancel_callback(handles["cancelled"])
        s.cancel_callback(handles["replaced"])
        s.register_pre_step_callback("added", lambda info: calls.append("added"), priority=0)
        s.register_post_step_callback("replaced", lambda info: calls.append("replaced, new"))

    handles["changer"] = scene.register_pre_step_callback("changer", changer, priority=1)
    handles["cancelled"] = scene.register_pre_step_callback("cancelled", lambda info: calls.append("cancelled"), priority=2)
    handles["replaced"] = scene.register_post_step_callback("replaced", lambda info: calls.append("replaced, old"))
    scene.step(0.01)
    assert calls == ["changer", "cancelled", "replaced, new"]
    calls.clear()
    scene.step(0.01)
    assert calls == ["added", "replaced, new"]
