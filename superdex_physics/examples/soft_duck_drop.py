"""Soft duck drop: the soft duck-lamp prop falls onto the ground, squashes a little and comes to rest.

The duck lamp (assets/prefabs/duck_lamp) is a tetrahedral finite-element body of soft silicone
(Neo-Hookean, E = 100 kPa). It is loaded with sdp.prefab.add_to_scene from the full finite-element
twin of the seed's prefab (the seed's duck is a reduced soft body, which cannot be released), 3 cm
higher and centred on the origin. The prefab pins the duck's flat belly
(its "fixedRegion") so that it stays put under the seed's arm; this example loads a copy of the
prefab without that region (nodes pinned at creation stay pinned), so the whole body falls. The elastic body and its frictional contact with the ground are solved
together in every implicit step.

The summary follows the fall: the lowest and mean node heights, the fastest node, and the ground's
contact force, which ends equal to the duck's weight.

Run it with

    uv run python superdex_physics/examples/soft_duck_drop.py [--seconds 0.4] [--height 0.03]

The soft body is the slow part (tens of ms per step on a laptop core). Add --debugger to watch it
in the scene debugger; without a display, also set SUPERDEX_DEBUGGER_RECORD=duck.jsonl to record
the run to a file (superdex.physics.debugger).
"""

import argparse
import json
import tempfile
from pathlib import Path

import numpy as np

import superdex.physics as sdp

GRAVITY = 9.81  # m/s^2
# the full finite-element twin of the seed's (reduced, pinned) duck: dropped, the duck is free
DUCK_LAMP_ASSET = "prefabs/duck_lamp/duck_lamp_recumbent_full.mochi_prefab"
PREFAB_OFFSET_X = -0.3  # m: where the prefab places the duck (under the seed's arm)


def add_duck(scene: sdp.Scene, height: float) -> sdp.Actor:
    """Loads the duck-lamp prefab with its belly `height` above the ground, centred on the origin,
    without the nodes the prefab pins."""
    root = Path(sdp.paths.get_assets_root()).resolve()
    prefab_path = Path(sdp.paths.resolve_asset(DUCK_LAMP_ASSET))
    prefab = json.loads(prefab_path.read_text())
    # the prefab pins its belly (fixedRegion) to stand in the seed's scene; dropped, it is free
    for soft in prefab["actors"]["soft"]:
        soft.pop("fixedRegion", None)
        soft.pop("fixedNodes", None)
        # the copy lives elsewhere: its mesh by its path under the assets root
        soft["shape"] = (prefab_path.parent / soft["shape"]).resolve().relative_to(root).as_posix()
    with tempfile.TemporaryDirectory() as folder:
        free_prefab = Path(folder) / prefab_path.name
        free_prefab.write_text(json.dumps(prefab))
        instance = sdp.prefab.add_to_scene(
            prefab_path=str(free_prefab),
            root_path=str(root),
            scene=scene,
            params=sdp.prefab.PrefabParams(name="duck_lamp", translation=[-PREFAB_OFFSET_X, 0.0, height]),
        )
    duck = instance.actors[0]
    duck.register_query(sdp.QueryType.NODE_POSITIONS)
    return duck


def node_positions_world(actor: sdp.Actor) -> np.ndarray:
    """(n, 3) world positions of the duck's nodes: its local node positions (the NODE_POSITIONS
    query) placed by its frame."""
    local = np.asarray(actor.get_node_positions_local(), dtype=np.float64).reshape(-1, 3)
    X_WL = actor.get_root_transform()
    x, y, z, w = np.asarray(X_WL.rotation, dtype=np.float64)
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    return local @ R.T + np.asarray(X_WL.translation, dtype=np.float64)


def run(seconds: float = 0.4, dt: float = 0.004, height: float = 0.03, debugger: bool = False,
        report_every: float = 0.04, on_step=None) -> dict:
    """Drops the duck from `height` and simulates `seconds`. Returns its mass, its node positions at
    release and at the end, the node velocities of the last step, the ground's contact force, and a
    history (every `report_every` s) of time, lowest and mean node height, fastest node and ground
    force. on_step(scene, duck) is called after every step when given."""
    sdp.initialize(num_worker_threads=0)
    try:
        scene = sdp.create_scene("Soft duck drop")
        scene.set_gravity([0, 0, -GRAVITY])
        ground = scene.create_rigid_actor(name="ground", shape=sdp.create_plane_shape(normal=[0, 0, 1], distance=0),
                                          is_static=True, contact=sdp.ContactParams(coulomb_friction_coefficient=0.8))
        duck = add_duck(scene, height)
        for actor in (ground, duck):
            actor.register_query(sdp.QueryType.TOTAL_CONTACT_FORCE)
        scene.step(0.0)  # runs no physics: fills the queries with the state at release
        released = node_positions_world(duck)
        previous = released.copy()
        velocities = np.zeros_like(released)
        history = []
        every = max(1, int(round(report_every / dt)))
        if debugger:
            sdp.debugger.attach()
        steps = int(round(seconds / dt))
        for k in range(1, steps + 1):
            scene.step(dt)
            nodes = node_positions_world(duck)
            velocities = (nodes - previous) / dt  # the implicit step's end velocity: x+ = x + dt v+
            previous = nodes
            if on_step is not None:
                on_step(scene, duck)
            if k % every == 0 or k == steps:
                history.append((scene.get_total_simulation_time(), nodes[:, 2].min(), nodes[:, 2].mean(),
                                np.linalg.norm(velocities, axis=1).max(), 0.0 - float(ground.get_contact_force_world()[2])))
        return {
            "mass": duck.get_mass(),
            "released_nodes": released,
            "final_nodes": previous,
            "final_node_velocities": velocities,
            "ground_force": np.array(ground.get_contact_force_world(), dtype=np.float64),
            "duck_contact_force": np.array(duck.get_contact_force_world(), dtype=np.float64),
            "history": np.array(history),
        }
    finally:
        if debugger:
            sdp.debugger.detach()
        sdp.shutdown()


def print_summary(result: dict) -> None:
    print(f"duck lamp: {len(result['final_nodes'])} nodes, {result['mass']:.4f} kg, "
          f"released with its belly at z = {result['released_nodes'][:, 2].min():.3f} m")
    print(f"{'t [s]':>6} {'lowest z [mm]':>14} {'mean z [mm]':>12} {'fastest node [m/s]':>19} {'ground force [N]':>17}")
    for t, lowest, mean, fastest, force in result["history"]:
        print(f"{t:6.3f} {lowest * 1e3:14.3f} {mean * 1e3:12.3f} {fastest:19.4f} {force:17.4f}")
    print(f"weight {result['mass'] * GRAVITY:.4f} N; ground force at the end {-result['ground_force'][2]:.4f} N")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=0.4, help="simulated time (s)")
    parser.add_argument("--dt", type=float, default=0.004, help="time step (s)")
    parser.add_argument("--height", type=float, default=0.03, help="drop height of the belly (m)")
    parser.add_argument("--debugger", action="store_true", help="attach the scene debugger (or record, see above)")
    args = parser.parse_args()
    print_summary(run(args.seconds, args.dt, args.height, args.debugger))


if __name__ == "__main__":
    main()
