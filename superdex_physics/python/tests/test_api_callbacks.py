"""Step callbacks: the StepInfo they receive, their order by priority then registration,
cancellation by handle (also from inside a callback), and exceptions propagating out of step()."""

import pytest

import superdex.physics as sdp


def ball(scene, y=1.0):
    return scene.create_rigid_actor(name="ball", shape=sdp.create_sphere_shape([0, 0, 0], 0.1),
                                    world_from_local=sdp.TransformRT(translation=[0, y, 0]))


def test_callbacks_receive_the_scene_and_time_step(scene):
    seen = []
    scene.register_pre_step_callback("pre", lambda info: seen.append(("pre", info.scene, info.time_step_sec)))
    scene.register_post_step_callback("post", lambda info: seen.append(("post", info.scene, info.time_step_sec)))
    scene.step(0.25)
    scene.step(0.125)
    assert seen == [("pre", scene, 0.25), ("post", scene, 0.25), ("pre", scene, 0.125), ("post", scene, 0.125)]


def test_pre_callbacks_see_the_state_before_the_step_and_post_after(engine):
    scene = sdp.create_scene("fall")  # default gravity: -9.8 along y
    b = ball(scene)
    ys = {}
    scene.register_pre_step_callback("pre", lambda info: ys.setdefault("pre", b.get_root_transform().translation[1]))
    scene.register_post_step_callback("post", lambda info: ys.setdefault("post", b.get_root_transform().translation[1]))
    dt = 0.01
    scene.step(dt)
    assert ys["pre"] == pytest.approx(1.0)
    # backward Euler: v1 = -g dt, y1 = y0 + v1 dt
    assert ys["post"] == pytest.approx(1.0 - 9.8 * dt * dt, rel=1e-6)


def test_order_is_priority_then_registration(scene):
    order = []
    for name, priority in [("c", 200), ("a", 100), ("b", 100), ("first", -5)]:
        scene.register_pre_step_callback(name, lambda info, n=name: order.append(n), priority)
    scene.register_post_step_callback("late", lambda info: order.append("post"), priority=-1000)
    scene.step(0.01)
    assert order == ["first", "a", "b", "c", "post"]
    assert sdp.Scene.DEFAULT_CALLBACK_PRIORITY == 100  # a default priority sits with "a" and "b"


def test_cancel_by_handle(scene):
    calls = []
    h1 = scene.register_pre_step_callback("one", lambda info: calls.append(1))
    h2 = scene.register_post_step_callback("two", lambda info: calls.append(2))
    assert isinstance(h1, sdp.CallbackHandle) and h1.is_valid() and h1 != h2
    scene.step(0.01)
    scene.cancel_callback(h1)
    scene.step(0.01)
    scene.cancel_callback(h1)  # cancelling twice, or an invalid handle, has no effect
    scene.cancel_callback(sdp.CallbackHandle())
    scene.cancel_callback(h2)
    scene.step(0.01)
    assert calls == [1, 2, 2]


def test_a_callback_may_cancel_itself_and_register_others(scene):
    calls = []
    handles = {}

    def once(info):
        calls.append("once")
        scene.cancel_callback(handles["once"])
        handles["later"] = scene.register_pre_step_callback("later", lambda info: calls.append("later"))

    handles["once"] = scene.register_pre_step_callback("once", once)
    scene.step(0.01)
    scene.step(0.01)
    scene.step(0.01)
    # the list of a running step is the one it started with: "later" runs from the next step on
    assert calls == ["once", "later", "later"]


def test_exception_in_a_callback_propagates_out_of_step(scene):
    class Boom(Exception):
        pass

    def bad(info):
        raise Boom("from the callback")

    h = scene.register_post_step_callback("bad", bad)
    with pytest.raises(Boom, match="from the callback"):
        scene.step(0.01)
    scene.cancel_callback(h)
    scene.step(0.01)  # the scene goes on once the callback is gone


def test_non_callable_is_refused_naming_the_call(scene):
    with pytest.raises(sdp.Error, match="register_pre_step_callback"):
        scene.register_pre_step_callback("x", 42)


def test_zero_time_step_runs_callbacks_without_moving(engine):
    scene = sdp.create_scene("zero")
    b = ball(scene)
    infos = []
    scene.register_post_step_callback("p", lambda info: infos.append(info.time_step_sec))
    scene.step(0.0)
    assert infos == [0.0]
    assert b.get_root_transform().translation == sdp.Real3(0, 1, 0)
    assert scene.get_total_simulation_time() == 0.0
    with pytest.raises(sdp.Error, match="time_step"):
        scene.step(-0.01)


def test_callbacks_go_with_their_scene(engine):
    calls = []
    s = sdp.create_scene("gone")
    s.register_pre_step_callback("c", lambda info: calls.append(1))
    s.step(0.01)
    sdp.destroy_scene(s)
    assert calls == [1]
    with pytest.raises(sdp.Error):
        s.step(0.01)
