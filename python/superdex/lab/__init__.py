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

__all__ = ["SuperDexEnv", "SeedTaskEnv", "PandaReachEnv", "SuperDexVectorEnv", "BuiltScene", "ENVIRONMENTS"]
