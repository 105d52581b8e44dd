"""The "rgb_array" view of the lab's environments: a schematic side view (world X right, Z up)
of the robot's link origins, the observed contact actor and the task's targets, drawn with
matplotlib's headless Agg backend. No GPU or display is needed; the scene debugger ("human") is
the faithful 3D view."""

from __future__ import annotations

import numpy as np

import superdex.physics as sdp

WIDTH, HEIGHT, DPI = 320, 240, 80


def render_side_view(built, targets) -> np.ndarray:
    """An (HEIGHT, WIDTH, 3) uint8 image of the scene `built` (a BuiltScene) and target points (k x 3, m)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    arm = built.articulation
    links = sdp.DynamicArrayTransformRT(len(arm.get_nested_link_actors()))
    arm.get_articulated_link_transforms(links)
    p_WL = np.array([np.array(links[i].translation, dtype=np.float64) for i in range(len(links))])
    fig = Figure(figsize=(WIDTH / DPI, HEIGHT / DPI), dpi=DPI)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes([0, 0, 1, 1])
    ax.plot(p_WL[:, 0], p_WL[:, 2], "o-", color="tab:blue", lw=2, ms=3)
    targets = np.asarray(targets, dtype=np.float64).reshape(-1, 3)
    if len(targets):
        ax.plot(targets[:, 0], targets[:, 2], "x", color="tab:red", ms=8)
    if built.contact_actor is not None:
        p = np.array(built.scene.get_actor(built.contact_actor.get_handle() if hasattr(built.contact_actor, "get_handle")
                                           else built.contact_actor).get_root_transform().translation)
        ax.plot([p[0]], [p[2]], "s", color="tab:orange", ms=5)
    ax.axhline(0.0, color="0.5", lw=1)
    center = p_WL.mean(axis=0)
    span = max(0.5, float(np.ptp(p_WL[:, [0, 2]])) * 1.4)
    ax.set_xlim(center[0] - span / 2 * WIDTH / HEIGHT, center[0] + span / 2 * WIDTH / HEIGHT)
    ax.set_ylim(center[2] - span / 2, center[2] + span / 2)
    ax.set_axis_off()
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()
