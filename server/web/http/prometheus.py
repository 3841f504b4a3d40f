"""``/api/metrics?format=prometheus``: the same figures in Prometheus's text exposition
format (version 0.0.4), one sample per scene, labelled with the scene's name."""

from __future__ import annotations

from typing import Any

CONTENT_TYPE = "text/plain; version=0.0.4; charset=utf-8"

# JSON field of a scene's metrics -> (metric name, type, help)
SCENE_METRICS: dict[str, tuple[str, str, str]] = {
    "ticks": ("vp_ticks_total", "counter", "Ticks run since the scene started"),
    "tickFailures": ("vp_tick_failures_total", "counter", "Ticks that failed"),
    "requests": ("vp_requests_total", "counter", "Requests answered since the scene started"),
    "tickMsP50": ("vp_tick_ms_p50", "gauge", "Median tick duration over the recent window (ms)"),
    "tickMsP95": ("vp_tick_ms_p95", "gauge", "95th percentile tick duration over the recent window (ms)"),
    "tickMsMax": ("vp_tick_ms_max", "gauge", "Longest tick over the recent window (ms)"),
    "ticksPerSecond": ("vp_ticks_per_second", "gauge", "Ticks per second over the recent window"),
    "requestsPerSecond": ("vp_requests_per_second", "gauge",
                          "Requests answered per second over the recent window"),
    "cpuPercent": ("vp_cpu_percent", "gauge", "CPU of the scene's process over the recent window (%)"),
    "cpuSeconds": ("vp_cpu_seconds_total", "counter", "CPU the scene's process has used (s)"),
    "clients": ("vp_clients", "gauge", "Connections to the scene"),
    "queuedBytes": ("vp_queued_bytes", "gauge", "Bytes waiting in the scene's connections' outboxes"),
    "viewerFrames": ("vp_viewer_frames_total", "counter",
                     "Tick messages handed to connections, one per connection"),
    "fanoutCpuSeconds": ("vp_fanout_cpu_seconds_total", "counter",
                         "CPU this server process spent handing the scene's ticks to connections (s)"),
}


def _label(value: str) -> str:
    return value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n")


def exposition(metrics: dict[str, Any]) -> str:
    """The text for ``metrics`` as ``/api/metrics`` gives it in JSON."""
    lines = ["# HELP vp_scenes_removed_total Scenes removed since the server started",
             "# TYPE vp_scenes_removed_total counter",
             f"vp_scenes_removed_total {metrics['scenesRemoved']}"]
    scenes = sorted(metrics["scenes"].items())
    lines += ["# HELP vp_scene_state The scene's state (starting, running, unresponsive, failed)",
              "# TYPE vp_scene_state gauge"]
    lines += [f'vp_scene_state{{scene="{_label(scene)}",state="{_label(figures["state"])}"}} 1'
              for scene, figures in scenes if "state" in figures]
    for field, (name, kind, text) in SCENE_METRICS.items():
        lines += [f"# HELP {name} {text}", f"# TYPE {name} {kind}"]
        # a scene that failed before it reported has no figures: no sample, only its state
        lines += [f'{name}{{scene="{_label(scene)}"}} {float(figures[field])!r}'
                  for scene, figures in scenes if field in figures]
    return "\n".join(lines) + "\n"
