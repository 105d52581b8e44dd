"""What an environment of the lab is made of, apart from Gymnasium: how one scene is built, and
the task's vectorized parts (episode sampling, observation, reward) that the single environment
(SuperDexEnv) and the batched vector environment (SuperDexVectorEnv) share, so that the two give
bitwise the same trajectories for the same seeds.

Every array function here works on rows: row k is one scene of a batch (one row for SuperDexEnv).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

import superdex.physics as sdp
import superdex.robotics as sdr

np_real = np.float64 if sdp.uses_double_precision() else np.float32


@dataclass
class BuiltScene:
    """One scene of an environment, as built by `SuperDexEnv.build_scene`.

    articulation: the robot's articulated actor (its actions and joint observations);
    contact_actor: the actor whose total contact force (N, world) is observed, or None;
    keep: objects that must live as long as the scene (the robotics context, prefab instances).
    """

    scene: object
    articulation: object
    contact_actor: object = None
    keep: list = field(default_factory=list)


def make_batch(spec: sdr.SceneBatchSpec, built: list[BuiltScene]) -> sdr.SceneBatch:
    """The C++ batch over the built scenes (captures each one's state as its initial state)."""
    return sdr.SceneBatch(spec, [b.scene for b in built], [b.articulation for b in built],
                          [b.contact_actor for b in built])


def ensure_engine(num_worker_threads: int = 0) -> None:
    """Starts the engine with `num_worker_threads` if it is not running; a running engine is used as
    it is (its thread count was chosen by whoever started it)."""
    if not sdp.is_initialized():
        sdp.initialize(num_worker_threads=num_worker_threads)

