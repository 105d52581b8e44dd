"""superdex.lab: Gymnasium environments over SuperDex scenes, batched vector environments stepped
in C++ on the engine's worker threads, and distributed rollouts with Ray.

    SuperDexEnv          the Env base class over one scene (env.py)
    SeedTaskEnv          the seed's 2-DOF arm: circle tracking and force on the duck (seed_task.py)
    PandaReachEnv        the 7-DOF Panda reaching above a table (panda_reach.py)
    SuperDexVectorEnv    num_envs scenes in one C++ SceneBatch, a gymnasium.vector.VectorEnv (vector_env.py)
    python -m superdex.lab.rollout --help    rollouts on a Ray cluster (rollout.py)

Needs the lab's Python packages: gymnasium (and ray, tqdm, matplotlib for rollouts and plots).
"""

from superdex.lab.env import SuperDexEnv
from superdex.lab.panda_reach import PandaReachEnv
from superdex.lab.seed_task import SeedTaskEnv
from superdex.lab.task import BuiltScene
from superdex.lab.vector_env import SuperDexVectorEnv

ENVIRONMENTS = {"seed": SeedTaskEnv, "panda": PandaReachEnv}


def _register():
    """gymnasium.make("superdex/SeedTask-v0", prop="box") and gymnasium.make_vec(...,
    vectorization_mode="vector_entry_point") give these environments and the batched vector env."""
    import gymnasium

    for env_id, cls in (("superdex/SeedTask-v0", "SeedTaskEnv"), ("superdex/PandaReach-v0", "PandaReachEnv")):
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point=f"superdex.lab:{cls}",
                               vector_entry_point=f"superdex.lab.vector_env:make_{cls}_vector")


_register()

__all__ = ["SuperDexEnv", "SeedTaskEnv", "PandaReachEnv", "SuperDexVectorEnv", "BuiltScene", "ENVIRONMENTS"]
