"""Contacts: the tracker's bounded measuring, and the book's begin and end diffs."""

import random

import pytest

from server.core.physics.contacts import CROWD, ContactBook, ContactTracker, Overlaps, pair
from server.core.physics.bullet_parts import GROUND, BulletParts
from server.core.physics.engine import PhysicsWorld


def test_update_reports_each_change_once():
    book = ContactBook()
    assert book.update(Overlaps([("a", "b"), ("b", "c")])) == ([("a", "b"), ("b", "c")], [])
    assert book.update(Overlaps([("a", "b"), ("b", "c")])) == ([], [])
    assert book.update(Overlaps([("b", "c"), ("a", "ground")])) == ([("a", "ground")],
                                                                    [("a", "b")])
    assert book.current.of("b") == ["c"] and book.current.of("a") == ["ground"]
    assert book.current.of("x") == []
    assert book.wire() == [["a", "ground"], ["b", "c"]]


def test_overlaps_index_both_sides_sorted():
    overlaps = Overlaps([("m", "z"), ("a", "m"), ("ground", "m")])
    assert overlaps.of("m") == ["a", "ground", "z"] and overlaps.of("a") == ["m"]


def test_partners_of_a_few_ids_are_the_index_s_whether_it_was_made_or_not():
    pairs = [pair(f"p{random.Random(k).randrange(30)}", f"p{random.Random(-k).randrange(30)}")
             for k in range(200)]
    asked = ["p3", None, "p17", "nobody", "p3", "ground"]
    fresh, indexed = Overlaps(pairs), Overlaps(pairs)
    expected = [tuple(indexed.of(i)) if i is not None else () for i in asked]
    assert fresh.partners_of(asked) == expected == indexed.partners_of(asked)
    assert any(expected) and expected[0] == expected[4] and expected[3] == ()


IDENTITY = (0.0, 0.0, 0.0, 1.0)
CUBE = {"kind": "box", "size": [1, 1, 1]}


def place(world, tracker, key, position, geometry=CUBE):
    if key in world:
        world.move(key, (position, IDENTITY))
    else:
        world.add(key, geometry, (position, IDENTITY))
    tracker.placed([key])


def test_tracker_measures_moved_bodies_and_the_ground(world):
    tracker = ContactTracker(world.parts, tests_per_update=100, max_pairs=100)
    place(world, tracker, "a", (0, 0.4, 0))
    place(world, tracker, "b", (0.9, 0.4, 0))
    place(world, tracker, "c", (5, 3, 0))
    tracker.update()
    assert tracker.overlaps().pairs == {("a", "b"), ("a", GROUND), ("b", GROUND)}
    place(world, tracker, "b", (0.9, 3, 0))  # away from a and the ground
    tracker.update()
    assert tracker.overlaps().pairs == {("a", GROUND)} and tracker.deferred == 0
    tracker.removed("a")
    tracker.update()
    assert tracker.overlaps().pairs == frozenset()


def test_crowds_are_measured_a_budget_at_a_time(world):
    """160 boxes in one spot crashed PyBullet's contact query; now it is 12 720 pair tests."""
    tracker = ContactTracker(world.parts, tests_per_update=2000, max_pairs=100_000)
    for k in range(160):
        place(world, tracker, f"b{k:03}", (0, 5, 0))
    updates = 0
    while tracker.deferred:
        tracker.update()
        updates += 1
        assert tracker.tests <= 2000
    assert len(tracker.overlaps().pairs) == 160 * 159 // 2
    assert 6 <= updates <= 10


def test_settle_measures_one_body_at_once(world):
    tracker = ContactTracker(world.parts, tests_per_update=1, max_pairs=100)
    for k in range(5):
        place(world, tracker, f"b{k}", (0, 5, 0))
    tracker.settle("b3")
    assert tracker.overlaps().of("b3") == ["b0", "b1", "b2", "b4"]


def test_settling_a_part_no_crowd_holds_leaves_nothing_for_another_update(world):
    tracker = ContactTracker(world.parts, tests_per_update=100, max_pairs=100)
    place(world, tracker, "a", (0, 0.4, 0))
    place(world, tracker, "b", (0.9, 0.4, 0))
    while tracker.unsettled:
        tracker.update()
    tracker.settle("a")
    assert tracker.overlaps().of("a") == ["b", GROUND] and not tracker.unsettled


def test_pairs_beyond_the_cap_are_counted_not_kept(world):
    tracker = ContactTracker(world.parts, tests_per_update=1000, max_pairs=10)
    for k in range(6):
        place(world, tracker, f"b{k}", (0, 5, 0))
    tracker.update()
    assert len(tracker.overlaps().pairs) == 10 and tracker.unrecorded == 5


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_every_touching_pair_is_found_whatever_the_boxes_sizes(world, seed):
    """The tracker only measures pairs whose boxes overlap (sweep and prune): it must
    still find exactly the pairs that a test of every pair finds, a long slab included."""
    rng = random.Random(seed)
    tracker = ContactTracker(world.parts, tests_per_update=100_000, max_pairs=100_000)
    keys = [f"b{i}" for i in range(60)]
    for key in keys:
        size = [rng.uniform(0.1, 2) for _ in range(3)]
        place(world, tracker, key, [rng.uniform(-3, 3) for _ in range(3)],
              {"kind": "box", "size": size})
    place(world, tracker, "slab", (0, 1, 0), {"kind": "box", "size": [20, 0.1, 0.3]})
    tracker.update()
    everything = [*keys, "slab", GROUND]
    expected = {pair(a, b) for i, a in enumerate(everything) for b in everything[i + 1:]
                if a != GROUND and world.parts.touching(a, b)}
    assert tracker.overlaps().pairs == expected and len(expected) > 30


def test_a_pile_stays_out_of_bullets_pairing_and_a_part_that_leaves_it_goes_back(world):
    tracker = ContactTracker(world.parts, tests_per_update=2000, max_pairs=100_000)
    for k in range(40):
        place(world, tracker, f"b{k:02}", (0, 5, 0))
    while tracker.deferred:
        tracker.update()
    assert len(tracker.overlaps().pairs) == 40 * 39 // 2
    assert not world.parts.detect()  # Bullet pairs none of them: no pair cache of 780
    place(world, tracker, "b00", (10, 5, 0))  # alone now
    tracker.update()
    assert tracker.overlaps().of("b00") == [] and not world.parts.detect()
    place(world, tracker, "lone", (10.5, 5, 0))  # made next to it: both measured by Bullet
    tracker.update()
    tracker.update()
    assert set(world.parts.detect()) == {("b00", "lone")}
    assert tracker.overlaps().of("b00") == ["lone"]



SHAPES = [{"kind": "box", "size": [0.5, 0.3, 0.4]}, {"kind": "sphere", "radius": 0.25},
          {"kind": "convex", "points": [[0, 0, 0], [0.5, 0, 0], [0, 0.4, 0], [0, 0, 0.3],
                                        [0.3, 0.3, 0.3]]}]


class DoubtingParts(BulletParts):
    """A world's parts whose every pair that begins is measured again, points new or old."""

    detects_afresh = False


def wander(world, rounds=150, doubting=False):
    """Parts of every kind wandering a few millimetres a step among each other; after each
    update, the tracker's pairs, those a test of every pair finds, and the tests it made."""
    rng = random.Random(5)
    if doubting:
        world.parts.__class__ = DoubtingParts  # (the same parts, measured with doubt)
    tracker = ContactTracker(world.parts, tests_per_update=100_000, max_pairs=100_000)
    keys = [f"p{i:02}" for i in range(24)]
    where = {key: [rng.uniform(0, 1.2), rng.uniform(0.1, 1.2), rng.uniform(0, 1.2)] for key in keys}
    for k, key in enumerate(keys):
        place(world, tracker, key, where[key], SHAPES[k % len(SHAPES)])
    for _ in range(rounds):
        for key in keys:
            where[key] = [x + rng.uniform(-0.006, 0.006) for x in where[key]]
            place(world, tracker, key, where[key])
        tracker.update()
        everything = [*keys, GROUND]
        yield tracker.overlaps().pairs, {pair(a, b) for i, a in enumerate(everything)
                                         for b in everything[i + 1:]
                                         if a != GROUND and world.parts.touching(a, b)}, tracker.tests


def test_a_pair_bullet_finds_anew_is_taken_as_found_and_one_it_had_is_measured_again(world):
    """Bullet keeps a pair's points from pass to pass, moved with the bodies: an old point
    may say two parts touch that have moved apart, so a pair that begins is measured again
    unless Bullet did not have it at the update before (its points are then all this pass's,
    the exact measure's own). The same wander, trusting new points or not: the same pairs
    after every update, exactly those a test of every pair finds, in fewer measures."""
    doubting = PhysicsWorld()
    try:
        trusted = doubted = 0  # tests after the first update (where every part is new)
        for n, ((pairs, exact, tests), (doubted_pairs, _, doubted_tests)) in enumerate(
                zip(wander(world), wander(doubting, doubting=True))):
            assert pairs == exact == doubted_pairs
            if n:
                trusted, doubted = trusted + tests, doubted + doubted_tests
        assert 0 < trusted < doubted * 0.75
    finally:
        doubting.close()


def test_parts_brought_to_a_crowd_one_by_one_touch_it_and_leave_it(world):
    """Bullet pairs no crowded part: a part brought next to a crowd meets it through its
    own measures (boxes brought into one spot one update at a time: those after the first
    seventeen used to touch none of them), and leaves it the same way. A part Bullet pairs
    with more than CROWD others joins the crowd, however its pairs came: the counts follow
    Bullet's pairs from update to update (only those it found or lost since change them),
    and after every update they are those of its pairs then."""
    tracker = ContactTracker(world.parts, tests_per_update=100_000, max_pairs=100_000)
    keys = [f"b{k:02}" for k in range(30)]
    for k, key in enumerate(keys):
        place(world, tracker, key, (3 * k + 5, 5, 0))
    tracker.update()

    def counted_anew():
        near = {}
        for a, b in tracker._found:
            if GROUND not in (a, b):
                for key in (a, b):
                    near[key] = near.get(key, 0) + 1
        return near
    for n, key in enumerate(keys):  # into one spot, one an update
        place(world, tracker, key, (-10, 5, 0))
        tracker.update()
        assert tracker._near == counted_anew()
        while tracker.deferred:
            tracker.update()
        assert len(tracker.overlaps().pairs) == n * (n + 1) // 2  # every pair of the pile
    assert len(tracker._crowded) == CROWD + 2  # (those Bullet paired with 17 others)
    # (askew: a box taken straight along its contact's normal out of two it lay wholly in
    # kept Bullet's points with one of them, 60 units deep, while Bullet paired no new
    # bodies: its broadphase drops old pairs only in step with new ones; noted, not mended)
    for k, key in enumerate(keys):  # and away again
        place(world, tracker, key, (3 * k + 5, 7, 3 * k + 5))
        tracker.update()
        assert tracker._near == counted_anew()
        while tracker.deferred:
            tracker.update()
        assert tracker.overlaps().of(key) == []
    assert tracker.overlaps().pairs == frozenset() and not tracker._crowded
