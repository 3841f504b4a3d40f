"""The Gymnasium environments against the real server: Gymnasium's own checker passes
with a 1.0 hand and with a gripper of the tests' making, a seed and the same actions give
the same episode, and the task's verdicts come out as reward, ends and ``success``."""

from __future__ import annotations

import math

import gymnasium
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import virtual_prosthetics.gym as vp_gym
from virtual_prosthetics.tasks.controller import PHASES, shares

pytestmark = pytest.mark.long  # tests/conftest.py: dealt out first

GRIPPER = "tests.clients.python.tasks.gripper:three_digits"


@pytest.fixture
def make(server):
    made = []

    def making(env_id: str, **options):
        # a scene of its own each (gym-…): the checker makes a second from the spec
        env = gymnasium.make(env_id, url=server.ws, **options)
        made.append(env)
        return env
    yield making
    for env in made:
        env.close()


@pytest.mark.parametrize("env_id", sorted(vp_gym.IDS.values()))
def test_gymnasiums_checker_passes_with_a_built_in_hand(make, env_id):
    env = make(env_id, hand="round")
    check_env(env.unwrapped, skip_render_check=True)  # its own seeded-reset determinism too
    assert env.spec.max_episode_steps == round(env.unwrapped.task.seconds * 60)


def test_gymnasiums_checker_passes_with_the_tests_own_gripper_under_torque_control(make):
    env = make("VirtualProsthetics/Grasp-v0", hand=GRIPPER, object="cube", control="torques")
    check_env(env.unwrapped, skip_render_check=True)
    parts = env.unwrapped.layout.split(env.reset(seed=1)[0])
    assert parts["angles"].shape == (6,) and parts["digitForces"].shape == (3,)


def test_a_seed_and_the_same_actions_give_the_same_episode(make):
    env = make("VirtualProsthetics/Grasp-v0", hand="edged")
    actions = np.random.default_rng(1).uniform(-1, 1, (150, env.action_space.shape[0])).astype(np.float32)

    def episode(seed: int) -> np.ndarray:
        seen = [env.reset(seed=seed)[0]]
        seen += [env.step(action)[0] for action in actions]
        return np.array(seen)
    first = episode(5)
    assert np.array_equal(first, episode(5))  # bit for bit, contacts included
    assert not np.array_equal(first, episode(6))  # another ball's mass and friction
    assert np.abs(first[-1] - first[0]).max() > 0.1  # the fingers moved, the ball with them


def test_a_reset_and_a_step_are_one_message_each(make):
    """The scene is restored, the object drawn and the motors read in one text (and one
    answer); a step is one text too, and the episode goes on as after any reset."""
    env = make("VirtualProsthetics/Grasp-v0", hand="edged")
    env.reset(seed=1)
    socket = env.unwrapped.session.connection._ws
    sent: list[str] = []
    send = socket.send
    socket.send = lambda text: sent.append(text) or send(text)
    observation, info = env.reset(seed=2)
    assert len(sent) == 1 and "restoreState" in sent[0] and "getTorques" in sent[0]
    assert info["massKg"] != pytest.approx(env.unwrapped.mass)  # drawn for this seed
    env.step(env.action_space.sample())
    assert len(sent) == 2 and '"step"' in sent[1]
    assert env.observation_space.contains(observation)


def scripted(env) -> tuple[float, dict]:
    """Run an episode with the tasks' baseline as actions; its total reward, last info."""
    inner = env.unwrapped
    observation, info = env.reset(seed=3)
    total, ended = 0.0, False
    while not ended:
        grip = inner.hands.grip
        wanted = grip.angles(shares(grip, inner.pattern.grip, inner.t))
        angles = inner.layout.split(observation)["angles"]
        action = inner.actions.action_of([a if w is None else w for a, w in zip(angles, wanted)])
        observation, reward, terminated, truncated, info = env.step(action)
        total += reward
        ended = terminated or truncated
    return total, {**info, "terminated": terminated, "truncated": truncated}


def test_the_baseline_through_the_env_holds_and_succeeds_and_an_open_hand_drops(make):
    env = make("VirtualProsthetics/Grasp-v0", hand="edged")
    total, info = scripted(env)
    assert info["success"] and info["truncated"] and not info["terminated"], info
    assert info["distance"] < 0.02  # the ball went where the wrist went
    env.reset(seed=3)
    opened = np.full(env.action_space.shape, -1.0, dtype=np.float32)  # every motor at its low end
    steps, ended = 0, False
    while not ended:
        _, reward, terminated, truncated, info = env.step(opened)
        steps, ended = steps + 1, terminated or truncated
    assert terminated and info["dropped"] and not info["success"], info
    assert reward < -10  # dropped: MyoSuite's penalty on top of the distance
    assert steps == math.ceil(PHASES.holding * 60)  # judged from the hold on, as the task does


def test_what_an_environment_cannot_be_is_said(server):
    with pytest.raises(ValueError, match="Hold takes sphere"):
        gymnasium.make("VirtualProsthetics/Hold-v0", url=server.ws, object="cube")
    with pytest.raises(ValueError, match="weight 'medium'"):
        gymnasium.make("VirtualProsthetics/Grasp-v0", url=server.ws, weight="medium")
    with pytest.raises(ValueError, match="ticks_per_step 0"):
        gymnasium.make("VirtualProsthetics/Grasp-v0", url=server.ws, ticks_per_step=0)


def test_a_human_render_says_where_to_watch(make, capsys):
    env = make("VirtualProsthetics/Hold-v0", hand="edged", render_mode="human")
    env.reset(seed=0)
    env.render()
    assert capsys.readouterr().out.count(f"/view?scene={env.unwrapped.session.name}") == 1
    for _ in range(16):  # watched: the episode, its time and return in the viewers' corner
        env.step(env.action_space.sample())
    session = env.unwrapped.session
    session.sync()
    caption = session.read(lambda mirror: mirror.caption)
    assert caption.startswith("Hold-v0 edged · episode 1 · 0.25 of ") and " · return " in caption


def test_an_rgb_array_render_is_the_trial_from_the_scenes_camera(make):
    env = make("VirtualProsthetics/Grasp-v0", hand="edged", object="cube", render_mode="rgb_array")
    check_env(env.unwrapped)  # the render check included
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (240, 320, 3) and frame.dtype == np.uint8
    colours = {tuple(pixel) for pixel in frame.reshape(-1, 3)[::7]}
    assert (255, 255, 255) in colours  # the sky
    blue = (frame[:, :, 2].astype(int) - frame[:, :, 0] > 60).mean()  # the steel-blue cube
    grey = ((np.ptp(frame, axis=2) < 12) & (frame[:, :, 0] > 90) & (frame[:, :, 0] < 230)).mean()  # the hand
    assert blue > 0.002 and grey > 0.02


def test_a_vector_of_environments_on_a_cluster_spreads_its_scenes_over_the_workers(tmp_path):
    """Gymnasium's async vector of two environments through one gateway: each its scene,
    each scene on a worker of its own, stepping and resetting there."""
    from urllib.parse import parse_qs, urlparse

    from tests.server.cluster.conftest import Cluster, holder, running_bus
    with running_bus(tmp_path) as url:
        # cores to spare: on a machine the suite loads, a scene's start measured against
        # its two cores made a worker full, and both scenes went to the other
        cluster = Cluster(url, tmp_path, gateways=1, worker_extra=("--worker-cores", "64"))
        try:
            vector = gymnasium.make_vec("VirtualProsthetics/Grasp-v0", num_envs=2,
                                        vectorization_mode="async", url=cluster.gateways[0].ws)
            try:
                observations, _ = vector.reset(seed=[4, 4])
                scenes = [parse_qs(urlparse(u).query)["scene"][0] for u in vector.get_attr("viewer_url")]
                assert sorted(holder(url, scene) for scene in scenes) == ["wa", "wb"]
                actions = np.zeros((20, *vector.action_space.shape), dtype=np.float32)
                for action in actions:
                    stepped = vector.step(action)[0]
                assert np.array_equal(stepped[0], stepped[1])  # the same seed each: the same world
                assert np.abs(stepped[0] - observations[0]).max() > 0.01  # (the wrist moved)
                assert np.array_equal(vector.reset(seed=[4, 4])[0], observations)  # restored there
            finally:
                vector.close()
        finally:
            cluster.close()
