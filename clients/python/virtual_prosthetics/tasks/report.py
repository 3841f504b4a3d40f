"""``python -m virtual_prosthetics.tasks report --hands edged,round,FILE --tasks grasp,hold,
relocate,box-and-blocks --seeds 1-5 --parallel N --out DIR``: every task with every hand
at every seed, ``N`` runs at once, each in a scene of its own (the server runs each scene
in a process of its own: all its cores, a cluster's workers); a progress bar with the
time left on stderr; every trial in ``trials.csv`` and ``trials.json``, every run's
results in ``runs.json``, and ``report.html``: plots to compare hands by."""

from __future__ import annotations

import argparse
import csv
import json
import os
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Iterator, Sequence

from tqdm import tqdm

from ..runtime import connect
from ..session import Session
from . import TASKS, progress
from .hands import hand_source
from .report_page import page
from .trial import TaskHand


@dataclass(frozen=True)
class Run:
    """One task with one hand at one seed."""

    hand: str
    task: str
    seed: int


def seeds(text: str) -> list[int]:
    """``1-5`` or ``1,3,7`` (or both: ``1-3,9``)."""
    out: list[int] = []
    for part in text.split(","):
        first, _, last = part.partition("-")
        try:
            out += list(range(int(first), int(last or first) + 1))
        except ValueError:
            raise argparse.ArgumentTypeError(f"seeds are numbers and ranges (1-5,9); got {part!r}") from None
    if not out:
        raise argparse.ArgumentTypeError(f"no seeds in {text!r}")
    return out


def parser() -> argparse.ArgumentParser:
    parse = argparse.ArgumentParser(prog="python -m virtual_prosthetics.tasks report",
                                    description=__doc__.split("\n\n")[0])
    parse.add_argument("--hands", default="edged", help="comma-separated: edged|round|anthro, "
                       "robot files, module:function (default: edged)")
    parse.add_argument("--tasks", default="grasp", help=f"comma-separated: {','.join(sorted(TASKS))}")
    parse.add_argument("--seeds", type=seeds, default=[1], help="1-5, or 1,3,7 (default: 1)")
    parse.add_argument("--trials", type=int, default=5, help="trials of each object (default: 5)")
    parse.add_argument("--grips", help="grasp: comma-separated patterns (default: all)")
    parse.add_argument("--parallel", type=int, default=os.cpu_count() or 1,
                       help="runs at once, each in its own scene (default: this machine's cores)")
    parse.add_argument("--out", type=Path, required=True, help="the folder to write into")
    parse.add_argument("--url", default="ws://127.0.0.1:8000")
    parse.add_argument("--token", help="the server's token, when it asks for one")
    parse.add_argument("--scene", default="report", help="scenes are named NAME-1, NAME-2, …")
    return parse


def main(argv: Sequence[str]) -> int:
    args = parser().parse_args(argv)
    tasks = args.tasks.split(",")
    unknown = sorted(set(tasks) - set(TASKS))
    if unknown:
        raise SystemExit(f"unknown task {', '.join(unknown)}; the tasks are {', '.join(sorted(TASKS))}")
    if args.trials < 1 or args.parallel < 1:
        parser().error("--trials and --parallel must be at least 1")
    runs = [Run(hand, task, seed) for hand in args.hands.split(",") for task in tasks for seed in args.seeds]
    results = run_all(runs, args)
    write(args.out, results, http_of(args.url))
    print(f"{len(results)} runs, {len(trial_rows(results))} trials: {args.out / 'report.html'}", file=sys.stderr)
    return 0


def run_all(runs: list[Run], args: argparse.Namespace) -> list[dict[str, Any]]:
    """Every run, ``args.parallel`` at once, each thread in a scene of its own; a bar of
    runs done with the time left."""
    local = threading.local()
    sessions: list[Session] = []
    names = iter(range(1, len(runs) + 1))
    lock = threading.Lock()

    def session() -> Session:
        if not hasattr(local, "session"):
            with lock:
                name = f"{args.scene}-{next(names)}"
            local.session = connect(args.url, scene=name, token=args.token)
            sessions.append(local.session)
        return local.session

    def one(run: Run) -> dict[str, Any]:
        with progress.silenced():
            here = session()
            options = argparse.Namespace(trials=args.trials, seed=run.seed, side_by_side=10,
                                         grips=args.grips, controller=None)
            result = TASKS[run.task](here, TaskHand(hand_source(run.hand, here)), options)
        bar.update(1)
        return {"hand": run.hand, "task": run.task, "seed": run.seed, **result}

    bar = tqdm(total=len(runs), desc="report", unit=" runs", file=sys.stderr, dynamic_ncols=True)
    try:
        with ThreadPoolExecutor(args.parallel) as pool:
            return list(pool.map(one, runs))
    finally:
        bar.close()
        for each in sessions:
            each.close()


def trial_rows(results: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One row per trial of every run: the run, the object, the trial's draws and measures."""
    rows = []
    for run in results:
        head = {"hand": run["hand"], "task": run["task"], "seed": run["seed"]}
        for line in _lines(run):
            fixed = {k: v for k, v in line.items() if not isinstance(v, (list, dict))}
            for index, trial in enumerate(line.get("each", [fixed])):
                rows.append({**head, **{k: fixed[k] for k in ("grip", "object", "weight") if k in fixed},
                             "trial": index, **trial})
    return rows


def _lines(run: dict[str, Any]) -> Iterator[dict[str, Any]]:
    if "results" in run:
        yield from run["results"]
    elif run["task"] == "box-and-blocks":
        yield {"blocks": run["blocks"], "blocksAcross": run["blocksAcross"], "blocksOver": run["blocksOver"]}
    else:
        yield {"object": run.get("object"), "each": run.get("each", [])}


def write(out: Path, results: list[dict[str, Any]], server: str) -> None:
    """``runs.json``, ``trials.json``, ``trials.csv`` and ``report.html`` into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    rows = trial_rows(results)
    (out / "runs.json").write_text(json.dumps(results, indent=1))
    (out / "trials.json").write_text(json.dumps(rows, indent=1))
    columns = list(dict.fromkeys(key for row in rows for key in row))
    with (out / "trials.csv").open("w", newline="") as file:
        writer = csv.DictWriter(file, columns)
        writer.writeheader()
        writer.writerows(rows)
    (out / "report.html").write_text(page(results, rows, server))


def http_of(url: str) -> str:
    """The server's HTTP address from its WebSocket one."""
    return url.replace("wss://", "https://", 1).replace("ws://", "http://", 1).split("/ws")[0].rstrip("/")
