"""A tick's messages, and folding frames for slow connections keeps the latest state of
everything."""

from server.core.scene.frames import held_back, merge_frames, tick_messages


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


def test_merge_keeps_a_caption_and_the_one_that_cleared_it():
    older = {"op": "frame", "seq": 1, "time": 0.1, "caption": "grasp · trial 1"}
    newer = {"op": "frame", "seq": 2, "time": 0.2}
    assert merge_frames(older, newer)["caption"] == "grasp · trial 1"
    assert merge_frames(older, {**newer, "caption": ""})["caption"] == ""


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


def test_merge_keeps_what_the_limits_held_back_in_the_worse_tick():
    older = {"op": "frame", "seq": 1, "time": 0.1, "limited": {"contactTests": 40}}
    quiet = {"op": "frame", "seq": 2, "time": 0.2}
    assert merge_frames(older, quiet)["limited"] == {"contactTests": 40}
    busier = {"op": "frame", "seq": 2, "time": 0.2, "limited": {"contactTests": 7, "contactPairs": 3}}
    assert merge_frames(older, busier)["limited"] == {"contactTests": 40, "contactPairs": 3}
    assert "limited" not in merge_frames(quiet, quiet)


def test_a_ticks_messages_carry_new_nodes_before_its_frame_and_removed_ids_after():
    changes = {"added": [{"id": "a"}], "angles": {"m": 0.5}, "removed": ["b"],
               **held_back(contactTests=0, contactPairs=2)}
    assert tick_messages(4, 0.25, changes) == [
        {"op": "added", "seq": 4, "nodes": [{"id": "a"}]},
        {"op": "frame", "seq": 4, "time": 0.25, "angles": {"m": 0.5}, "limited": {"contactPairs": 2}},
        {"op": "removed", "seq": 4, "ids": ["b"]}]
    assert tick_messages(5, 0.3, {}) == [{"op": "frame", "seq": 5, "time": 0.3}]


def test_an_update_names_each_field_as_the_nodes_description_does(scene):
    from server.core.model.motor import MotorZ

    motor = MotorZ(scene, "m")
    scene.tick(1 / 60)
    motor.set_max_torque(5.0)
    motor.set_name("knuckle")
    updates = scene.tick(1 / 60)[-1]["updates"]["m"]
    assert updates == {"maxTorque": 5.0, "name": "knuckle"}
    assert set(updates) <= set(motor.describe())
