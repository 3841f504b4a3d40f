"""Gymnasium environments of the hand-function tasks (``pip install
"virtual-prosthetics[gym]"``)::

    import gymnasium as gym
    import virtual_prosthetics.gym  # registers the environments

    env = gym.make("VirtualProsthetics/Grasp-v0", url="ws://127.0.0.1:8000", hand="edged",
                   object="sphere")
    observation, info = env.reset(seed=7)

``VirtualProsthetics/Grasp-v0``, ``Hold-v0`` and ``Relocate-v0`` (:mod:`.episodes`: their
rewards, ends and success, MyoSuite's), with any hand the tasks take
(:class:`~.env.HandTaskEnv`). The observation is :mod:`.observations`', the action
:mod:`.actions`'. An episode is the task's own length; ``max_episode_steps`` cuts it
there too.
"""

from __future__ import annotations

try:
    import gymnasium
except ImportError as error:  # an optional extra: say how to get it
    raise ImportError('virtual_prosthetics.gym needs Gymnasium: pip install "virtual-prosthetics[gym]"') from error

from .env import HandTaskEnv
from .episodes import EPISODES

IDS = {name: f"VirtualProsthetics/{name}-v0" for name in EPISODES}


def _register() -> None:
    for name, env_id in IDS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(id=env_id, entry_point="virtual_prosthetics.gym.env:HandTaskEnv",
                               kwargs={"episode": name},
                               max_episode_steps=round(EPISODES[name].seconds * 60))


_register()

__all__ = ["HandTaskEnv", "IDS"]
