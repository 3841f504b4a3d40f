"""The Prometheus text form of /api/metrics."""

from __future__ import annotations

from server.web.prometheus import SCENE_METRICS, exposition


def figures(**overrides):
    return {field: 1.5 for field in SCENE_METRICS} | overrides


def test_every_scene_figure_is_a_labelled_sample_with_help_and_type():
    text = exposition({"scenesRemoved": 2, "scenes": {"b": figures(ticks=10), "a": figures()}})
    lines = text.splitlines()
    assert "vp_scenes_removed_total 2" in lines
    assert '# TYPE vp_ticks_total counter' in lines and '# TYPE vp_tick_ms_p95 gauge' in lines
    samples = [line for line in lines if line.startswith("vp_ticks_total{")]
    assert samples == ['vp_ticks_total{scene="a"} 1.5', 'vp_ticks_total{scene="b"} 10.0']
    names = {line.split("{")[0] for line in lines if not line.startswith("#") and "{" in line}
    assert names == {name for name, _, _ in SCENE_METRICS.values()}
    assert text.endswith("\n")


def test_label_values_are_escaped():
    text = exposition({"scenesRemoved": 0, "scenes": {'odd"name\\x': figures()}})
    assert 'vp_clients{scene="odd\\"name\\\\x"} 1.5' in text.splitlines()
