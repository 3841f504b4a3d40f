"""Learn to grasp: a hand controller learnt on ``VirtualProsthetics/Grasp-v0``.

    pip install "clients/python[learn]"     # Gymnasium, cma (CMA-ES), matplotlib
    python clients/python/examples/learn_grasp.py --url ws://127.0.0.1:8000 --hand edged

The policy closes every digit to a share of its way from open to closed, the opposing
digit starting a little before the others, over a time: three numbers, learnt by CMA-ES
(the ``cma`` package) from the environment's reward, several episodes side by side in scenes of their own
(Gymnasium's vector environment: the server steps each scene in its own process). It
starts from a hand that closes under half way (it lifts nothing) and prints each
generation's success; at the end it saves the learning curve as a PNG and shows the learnt grasp in the
viewer, at real speed.

Why CMA-ES and not Stable-Baselines3's PPO: PPO needs PyTorch, whose wheels on PyPI bring
gigabytes of CUDA libraries to a CPU machine; a policy of three numbers is what evolution
strategies learn well, from returns alone, on two cores.
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import cma
import gymnasium
import matplotlib
import numpy as np

import virtual_prosthetics.gym  # noqa: F401 (registers the environments)
from virtual_prosthetics.tasks.controller import PHASES, smooth

matplotlib.use("Agg")  # a file, no display
from matplotlib import pyplot  # noqa: E402  (after choosing the backend)

ENV = "VirtualProsthetics/Grasp-v0"
START = np.array([0.45, 0.1, 0.67])  # closes under half way: lifts nothing
LOW, HIGH = np.array([0.0, 0.0, 0.2]), np.array([1.0, 0.8, 1.5])


class Policy:
    """The controller of three numbers ``theta``: how far the digits close (a share of
    each closing motor's way, as the grip map gives it), how many seconds before the
    others the opposing digit starts, and how many seconds closing takes (an eased ramp:
    a hand that closes at once flings what it takes). The other digits start when the
    hand has come down (the task's timeline). It knows the hand by one probe
    environment's grip map and action map."""

    def __init__(self, probe: Any) -> None:
        inner = probe.unwrapped
        self.grip, self.actions, self.layout = inner.hands.grip, inner.actions, inner.layout

    def __call__(self, theta: np.ndarray, observation: np.ndarray) -> np.ndarray:
        share, lead, span = np.clip(theta, LOW, HIGH)
        parts = self.layout.split(observation)
        t = float(parts["time"][0])
        shares = {i: share * smooth(t, PHASES.closing - (lead if i == self.grip.opposing else 0.0), span)
                  for i in range(len(self.grip.digits))}
        wanted = self.grip.angles(shares)
        return self.actions.action_of([a if w is None else w for a, w in zip(parts["angles"], wanted)])


def episodes(envs: Any, act: Policy, thetas: list[np.ndarray], seed: int) -> tuple[np.ndarray, np.ndarray]:
    """One episode in each environment of ``envs``, each with its ``theta``: their
    returns and whether each succeeded (the task's verdict at its end)."""
    observations, _ = envs.reset(seed=seed)
    totals = np.zeros(len(thetas))
    done, success = np.zeros(len(thetas), bool), np.zeros(len(thetas), bool)
    while not done.all():
        actions = np.array([act(theta, observation) for theta, observation in zip(thetas, observations)])
        observations, rewards, terminated, truncated, infos = envs.step(actions)
        totals += np.where(done, 0.0, rewards)
        ended = (terminated | truncated) & ~done
        success |= ended & infos["success"].astype(bool)
        done |= terminated | truncated
    return totals, success


def learn(args: argparse.Namespace) -> tuple[np.ndarray, list[dict[str, float]]]:
    """CMA-ES over the policy's numbers; the best found and each generation's figures."""
    make = dict(url=args.url, hand=args.hand, object=args.object, weight=args.weight)
    probe = gymnasium.make(ENV, **make)
    act = Policy(probe)
    probe.close()
    envs = gymnasium.make_vec(ENV, num_envs=args.population, vectorization_mode="async", **make)
    strategy = cma.CMAEvolutionStrategy(START, 0.2, {"popsize": args.population, "seed": args.seed,
                                                    "bounds": [LOW.tolist(), HIGH.tolist()], "verbose": -9})
    curve = []
    try:
        before = episodes(envs, act, [START] * args.population, args.seed)
        curve.append({"generation": 0, "return": float(before[0].mean()), "success": float(before[1].mean())})
        print(f"before: success {curve[0]['success']:.0%}, return {curve[0]['return']:.0f}", flush=True)
        for generation in range(1, args.generations + 1):
            thetas = strategy.ask()
            returns, success = episodes(envs, act, thetas, args.seed + generation)
            strategy.tell(thetas, (-returns).tolist())  # CMA-ES minimises
            curve.append({"generation": generation, "return": float(returns.mean()),
                          "success": float(success.mean())})
            print(f"generation {generation}: success {success.mean():.0%}, return {returns.mean():.0f} "
                  f"(best {returns.max():.0f})", flush=True)
        best = np.clip(strategy.result.xfavorite, LOW, HIGH)
        after = episodes(envs, act, [best] * args.population, args.seed + 1000)
        curve.append({"generation": args.generations + 1, "return": float(after[0].mean()),
                      "success": float(after[1].mean())})
        print(f"after: success {after[1].mean():.0%}, return {after[0].mean():.0f}; theta {np.round(best, 3)}")
    finally:
        envs.close()
    return best, curve


def plot(curve: list[dict[str, float]], path: str) -> None:
    """The learning curve: mean return and success per generation."""
    figure, (returns, success) = pyplot.subplots(2, 1, sharex=True, figsize=(6, 5))
    generations = [row["generation"] for row in curve]
    returns.plot(generations, [row["return"] for row in curve], marker="o")
    returns.set_ylabel("mean return")
    success.plot(generations, [100 * row["success"] for row in curve], marker="o", color="seagreen")
    success.set_ylabel("success (%)")
    success.set_xlabel("generation (0: before; last: the learnt policy, new seeds)")
    figure.suptitle(f"{ENV}: CMA-ES")
    figure.tight_layout()
    figure.savefig(path)


def show(args: argparse.Namespace, theta: np.ndarray) -> None:
    """The learnt grasp once more, in the viewer (its address is printed), at real speed."""
    env = gymnasium.make(ENV, url=args.url, hand=args.hand, object=args.object, weight=args.weight,
                         render_mode="human")
    act = Policy(env)
    observation, _ = env.reset(seed=args.seed)
    ended = False
    while not ended:
        started = time.monotonic()
        observation, _, terminated, truncated, info = env.step(act(theta, observation))
        ended = terminated or truncated
        time.sleep(max(0.0, 1 / 60 - (time.monotonic() - started)))
    print(f"shown: {'held' if info['success'] else 'not held'}")
    env.close()


def main() -> None:
    parse = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parse.add_argument("--url", default="ws://127.0.0.1:8000")
    parse.add_argument("--hand", default="edged")
    parse.add_argument("--object", default="sphere")
    parse.add_argument("--weight", default="heavy")
    parse.add_argument("--generations", type=int, default=8)
    parse.add_argument("--population", type=int, default=6, help="episodes side by side")
    parse.add_argument("--seed", type=int, default=1)
    parse.add_argument("--out", default="learn_grasp.png")
    parse.add_argument("--no-show", action="store_true", help="skip the grasp in the viewer")
    args = parse.parse_args()
    started = time.monotonic()
    theta, curve = learn(args)
    plot(curve, args.out)
    print(f"learnt in {time.monotonic() - started:.0f} s; curve: {args.out}")
    if not args.no_show:
        show(args, theta)


if __name__ == "__main__":
    main()
