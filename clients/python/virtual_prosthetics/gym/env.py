"""A hand-function task as a Gymnasium environment, in a scene of a server.

The task moves the wrist (down to the object, up, and along the task's path); the agent
drives the hand's motors. One step is ``ticks_per_step`` of the scene's ticks (1/60 s
each), taken with the scene paused: an episode sees the same world however loaded the
server is, and runs as fast as the server computes it. Any viewer of the scene
(``render_mode="human"`` prints its address) watches the episodes."""

from __future__ import annotations

import math
import secrets
from dataclasses import replace
from typing import Any, Callable, Mapping

import gymnasium
import numpy as np

from ..http_api import request, scene_path
from ..runtime import connect
from ..tasks.controller import PHASES, prepare
from ..tasks.grasp import FRICTION_SPREAD, MASS_SPREAD, PATTERNS, PHYSICS
from ..tasks.hands import hand_source
from ..tasks.observation import apply
from ..tasks.relocate import turn_between
from ..tasks.progress import CAPTION_TICKS
from ..tasks.scale import Scale
from ..tasks.trial import TaskHand, Trial, lay_out
from .actions import action_map
from .episodes import EPISODES, OBJECTS, Grasped
from .observations import ObservationLayout, Watcher

WEIGHTS = ("light", "heavy")


class HandTaskEnv(gymnasium.Env):  # type: ignore[misc]
    """``episode`` (Grasp, Hold, Relocate: :mod:`.episodes`) with ``hand`` (a 1.0 hand's
    name, a robot file, or ``module:function``, as the tasks' ``--hand``) on ``object``
    (sphere, cube, cylinder, plate, tip, card: the grip pattern of that object), of the
    ``weight`` the task gives it; each reset draws its mass and friction as the tasks do.
    ``scene``: the scene to run in (default: a new one, ``gym-…``)."""

    metadata = {"render_modes": ["human", "rgb_array"], "render_fps": 60}
    picture_size = (320, 240)  # rgb_array's width and height (pixels)

    def __init__(self, episode: str = "Grasp", url: str = "ws://127.0.0.1:8000", hand: str = "edged",
                 object: str = "sphere", weight: str = "light", control: str = "angles",
                 token: str | None = None, scene: str | None = None,
                 grip_map: Mapping[str, Any] | None = None, ticks_per_step: int = 1,
                 render_mode: str | None = None, timeout: float | None = None) -> None:
        self.task = EPISODES[episode]
        self.pattern = _pattern(self.task.name, self.task.patterns, object)
        if weight not in WEIGHTS:
            raise ValueError(f"weight {weight!r}: expected one of {', '.join(WEIGHTS)}")
        if not (isinstance(ticks_per_step, int) and ticks_per_step >= 1):  # (the server: ≤ 60)
            raise ValueError(f"ticks_per_step {ticks_per_step!r}: a whole number of ticks, at least 1")
        if render_mode not in (None, *self.metadata["render_modes"]):
            raise ValueError(f"render_mode {render_mode!r}: expected None or "
                             f"{', '.join(self.metadata['render_modes'])}")
        self.render_mode = render_mode
        self.mass = self.pattern.item.light if weight == "light" else self.pattern.item.heavy
        self.session = connect(url, scene=scene or f"gym-{secrets.token_hex(4)}", token=token,
                               timeout=timeout)
        try:
            self._open(hand, grip_map, control, ticks_per_step)
        except BaseException:  # nothing left open: the connection closes, the scene resumes
            self.session.close()
            raise

    def _open(self, hand: str, grip_map: Mapping[str, Any] | None, control: str,
              ticks_per_step: int) -> None:
        """The scene paused and dynamic, the first trial laid out and kept, the spaces."""
        self.session.pause()  # held until close (not a with block: a lost env must not hang)
        self.session.set_physics("dynamic", **PHYSICS)
        self.hands = TaskHand(hand_source(hand, self.session), dict(grip_map) if grip_map else None)
        self.ticks_per_step = ticks_per_step
        self.period = ticks_per_step / self.session.tick_rate
        self.first = self._lay_out()
        self.trial: Trial | None = None  # the episode's, once reset
        grip = self.hands.grip
        assert grip is not None
        self.actions = action_map(self.first.hand, grip, control)
        self.layout = ObservationLayout(grip.motors, len(grip.digits))
        self.watcher = Watcher(self.layout, self.period)
        self.action_space = self.actions.space()
        self.observation_space = self.layout.space()
        self.metadata = {**self.metadata, "render_fps": round(1 / self.period)}
        self.t = 0.0
        self._sent: dict[int, float] = {}
        self.grasped: Grasped | None = None  # where the object and the wrist were at the hold
        self._shown = False
        self.episodes = 0
        self.score = 0.0  # the episode's return so far (the caption's)

    @property
    def viewer_url(self) -> str:
        """Where a browser watches this environment's scene."""
        return self.session.viewer_url()

    def _lay_out(self) -> Trial:
        """The trial every episode starts from, kept on the server (``saveState``)."""
        self.scale = Scale.of(self.session)
        trial = lay_out(self.session, self.hands, self.pattern.item, [(1.0, 1.0)], self.mass,
                        self.pattern.grip)[0]
        prepare(trial.hand, self.pattern.grip)
        length = trial.layout.length  # the camera: ahead of the hand, a little above and aside
        self.session.set_camera_target(trial.home[0], trial.table_top + 0.4 * length, trial.home[2])
        self.session.set_camera_position(trial.home[0] + 1.2 * length, trial.table_top + 1.4 * length,
                                         trial.home[2] - 2.4 * length)
        self.session.sync()
        self._start = self.session.save_state()
        return trial

    def reset(self, *, seed: int | None = None,
              options: dict[str, Any] | None = None) -> tuple[np.ndarray, dict[str, Any]]:
        """A new episode: the scene restored to the laid-out trial in the scene's process
        (the same seed and actions give the same episode), the object's mass and friction
        drawn from the environment's generator (seeded by ``seed``) as the tasks draw them."""
        super().reset(seed=seed)
        mass = self.mass * float(self.np_random.uniform(1 - MASS_SPREAD, 1 + MASS_SPREAD))
        friction = float(self.np_random.uniform(1 - FRICTION_SPREAD, 1 + FRICTION_SPREAD))
        with self.session.connection.gathering():  # one message and one answer
            self.session.restore_state(self._start, wait=False)
            self.first.obj.set_mass(mass)
            self.first.obj.set_friction(friction)
            motion = self._reading(self.session.read_many)
        self.trial = replace(self.first, mass=mass, friction=friction, heights=[], offsets=[],
                             forces=[], touched=[], poses=[])
        self.arm = self.task.arm(self.scale)  # a path keeps what it aimed at: a new one
        self.watcher.reset()
        self.t, self._sent, self.grasped = 0.0, {}, None
        self.episodes, self.score = self.episodes + 1, 0.0
        self._show()
        return self._observe(motion), self._info(self._judge()[:3])

    def step(self, action: np.ndarray) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        """Drive the motors by ``action`` for one step while the task moves the wrist: one
        message to the scene and one answer a tick (the last with the motors' speeds and
        torques)."""
        assert self.trial is not None
        targets = self.actions.targets(action)
        for tick in range(self.ticks_per_step):
            with self.session.connection.gathering():
                self.arm(self.trial, self.t)
                if tick == 0:
                    apply(self.trial, targets, self._sent)
                    self._caption()
                if tick == self.ticks_per_step - 1:
                    motion = self._reading(self.session.step_reading)
                else:
                    self.session.step()
            self.t += self.period / self.ticks_per_step
            self.trial.watch_contact()
            if self.t >= PHASES.holding:
                self.trial.observe()
            if self.grasped is None and self.t >= PHASES.holding and not self.task.dropped(self.trial):
                self.grasped = (tuple(self.trial.object_position()), tuple(self.trial.hand_position()))
        distance, turn, dropped, success = self._judge()
        truncated = self.t >= self.task.seconds - 1e-9
        # scored from the lift on (episodes.py): before it there is nothing to hold yet
        reward = self.task.reward(distance, turn, dropped) if self.t >= PHASES.lifting else 0.0
        self.score += reward
        return (self._observe(motion), reward, dropped, truncated,
                self._info((distance, turn, dropped), success))

    def _reading(self, read: Callable[[list[tuple[str, str]]], list[Any]]
                 ) -> tuple[list[float], list[float]]:
        """The hand's motors' speeds and torques, as ``read`` (a tick and a read, or a read)
        gives them."""
        hand = self.first.hand.id
        speeds, torques = read([(hand, "getSpeeds"), (hand, "getTorques")])
        return [float(v) for v in speeds], [float(v) for v in torques]

    def _observe(self, motion: tuple[list[float], list[float]] | None = None) -> np.ndarray:
        assert self.trial is not None
        return self.watcher.observe(self.trial, self.t, self.task.goal(self.trial, self.t, self.grasped),
                                    motion)

    def _judge(self) -> tuple[float, float, bool, bool]:
        """The object's distance from its goal (m), its turn from its start (rad), whether
        it is dropped, whether the task is solved so far."""
        trial = self.trial
        assert trial is not None
        where = trial.object_position()
        distance = self.scale.metres(math.dist(where, self.task.goal(trial, self.t, self.grasped)))
        turn = turn_between(trial.object_quaternion(), trial.start_quaternion)
        return distance, turn, self.task.dropped(trial), self.task.success(trial)

    def _info(self, judged: tuple[float, float, bool], success: bool = False) -> dict[str, Any]:
        distance, turn, dropped = judged
        return {"success": success, "is_success": success, "distance": distance, "turn": turn,
                "dropped": dropped, "time": self.t, "massKg": self.trial.mass if self.trial else None}

    def _caption(self) -> None:
        """Watched (``human``): the episode, its time and return in the viewers' corner,
        a quarter of a second at a time (sent with the step)."""
        tick = round(self.t / self.period) * self.ticks_per_step
        if self.render_mode != "human" or tick % CAPTION_TICKS >= self.ticks_per_step:
            return
        self.session.set_caption(f"{self.task.name}-v0 {self.hands.source.name} · episode "
                                 f"{self.episodes} · {self.t:.2f} of {self.task.seconds:.1f} s "
                                 f"· return {self.score:.1f}")

    def _show(self) -> None:
        if self.render_mode == "human" and not self._shown:
            print(f"watch at {self.viewer_url}", flush=True)
            self._shown = True

    def render(self) -> np.ndarray | None:
        """``human``: the scene's viewers draw it (its address is printed once);
        ``rgb_array``: the scene from its camera, drawn by the server (its parts in their
        colours, lit but not textured)."""
        self._show()
        if self.render_mode != "rgb_array":
            return None
        width, height = self.picture_size
        path = f"{scene_path(self.session, 'picture')}?width={width}&height={height}&format=rgb"
        data = request(self.session, path, "render")
        return np.frombuffer(data, dtype=np.uint8).reshape(height, width, 3)

    def close(self) -> None:
        """Leave the scene (what the environment made goes with it)."""
        self.session.close()


def _pattern(episode: str, offered: tuple[str, ...], obj: str) -> Any:
    """The grip pattern of ``obj`` (a short object name), if ``episode`` offers it."""
    name = OBJECTS.get(obj)
    if name not in offered:
        choices = [short for short, pattern in OBJECTS.items() if pattern in offered]
        raise ValueError(f"object {obj!r}: {episode} takes {', '.join(choices)}")
    return next(p for p in PATTERNS if p.name == name)
