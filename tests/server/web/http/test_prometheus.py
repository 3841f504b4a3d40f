"""The Prometheus text form of /api/metrics."""

from __future__ import annotations

from server.web.http.prometheus import SCENE_METRICS, exposition


def figures(**overrides):
    return {field: 1.5 for field in SCENE_METRICS} | {"state": "running"} | overrides


def test_every_scene_figure_is_a_labelled_sample_with_help_and_type():
    text = exposition({"scenesRemoved": 2, "scenes": {"b": figures(ticks=10), "a": figures()}})
    lines = text.splitlines()
    assert "vp_scenes_removed_total 2" in lines
    assert '# TYPE vp_ticks_total counter' in lines and '# TYPE vp_tick_ms_p95 gauge' in lines
    samples = [line for line in lines if line.startswith("vp_ticks_total{")]
    assert samples == ['vp_ticks_total{scene="a"} 1.5', 'vp_ticks_total{scene="b"} 10.0']
    names = {line.split("{")[0] for line in lines if not line.startswith("#") and "{" in line}
    assert names == {name for name, _, _ in SCENE_METRICS.values()} | {"vp_scene_state"}
    assert text.endswith("\n")


def test_label_values_are_escaped():
    text = exposition({"scenesRemoved": 0, "scenes": {'odd"name\\x': figures()}})
    assert 'vp_clients{scene="odd\\"name\\\\x"} 1.5' in text.splitlines()


def test_a_scene_that_failed_before_reporting_has_its_state_and_no_figures():
    failed = {"tickRate": 60, "state": "failed", "clients": 0, "queuedBytes": 0}  # as /api/metrics
    text = exposition({"scenesRemoved": 0, "scenes": {"gone": failed,
                                                      "ok": figures()}})
    lines = text.splitlines()
    assert 'vp_scene_state{scene="gone",state="failed"} 1' in lines
    assert 'vp_scene_state{scene="ok",state="running"} 1' in lines
    assert 'vp_clients{scene="gone"} 0.0' in lines
    assert not any(line.startswith('vp_ticks_total{scene="gone"') for line in lines)
    assert 'vp_ticks_total{scene="ok"} 1.5' in lines
