"""Folding frames for slow connections keeps the latest state of everything."""

from server.core.frames import merge_frames


def test_merge_keeps_latest_values_and_all_keys():
    older = {"op": "frame", "seq": 1, "time": 0.1, "angles": {"a": 1, "b": 2},
             "updates": {"n": {"name": "x", "flipped": True}}, "camera": {"position": [1, 1, 1]}}
    newer = {"op": "frame", "seq": 2, "time": 0.2, "angles": {"b": 3},
             "poses": {"r": [0, 0, 0, 0, 0, 0, 1]}, "updates": {"n": {"name": "y"}}}
    merged = merge_frames(older, newer)
    assert merged == {"op": "frame", "seq": 2, "time": 0.2, "angles": {"a": 1, "b": 3},
                      "poses": {"r": [0, 0, 0, 0, 0, 0, 1]},
                      "updates": {"n": {"name": "y", "flipped": True}},
                      "camera": {"position": [1, 1, 1]}}
    assert older["angles"] == {"a": 1, "b": 2}  # inputs untouched


def test_merge_keeps_every_contact_change_and_the_latest_readings():
    older = {"op": "frame", "seq": 1, "time": 0.1,
             "contacts": {"begin": [["a", "b"], ["c", "d"]], "end": [["e", "f"]]},
             "sensors": {"s": {"distance": 1}, "t": {"distance": 2}}}
    newer = {"op": "frame", "seq": 2, "time": 0.2,
             "contacts": {"begin": [["e", "f"], ["g", "h"]], "end": [["a", "b"]]},
             "sensors": {"s": {"distance": 3}}}
    merged = merge_frames(older, newer)
    # a-b began and ended, e-f ended and began again: to the slow client, nothing changed
    assert merged["contacts"] == {"begin": [["c", "d"], ["g", "h"]], "end": []}
    assert merged["sensors"] == {"s": {"distance": 3}, "t": {"distance": 2}}
    assert merge_frames(older, {"op": "frame", "seq": 2, "time": 0.2})["contacts"] == \
        older["contacts"]
