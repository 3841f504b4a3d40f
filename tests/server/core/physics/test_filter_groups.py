"""Bullet's collision filter groups: which kinds of body Bullet pairs (a pair is tested when
each one's group is in the other's mask), as the module documents them."""

from server.core.physics import filter_groups as groups

KINDS = {"ground": (groups.GROUND_GROUP, groups.GROUND_MASK), "body": (groups.BODY_GROUP, groups.BODY_MASK),
         "crowd": (groups.CROWD_GROUP, groups.CROWD_MASK), "resting": (groups.RESTING_GROUP, groups.RESTING_MASK)}


def _meets(a: str, b: str) -> bool:
    (group_a, mask_a), (group_b, mask_b) = KINDS[a], KINDS[b]
    return bool(group_a & mask_b) and bool(group_b & mask_a)


def test_each_kind_meets_what_the_module_says():
    met = {(a, b) for a in KINDS for b in KINDS if a <= b and _meets(a, b)} - {("ground", "ground")}
    # parts meet the ground, each other and resting bodies; a crowd meets nothing in
    # Bullet; a resting body meets only parts that move (there is one ground)
    assert met == {("body", "ground"), ("body", "body"), ("body", "resting")}


def test_every_group_is_its_own_bit():
    bits = [group for group, _ in KINDS.values()]
    assert all(bit and bit & (bit - 1) == 0 for bit in bits) and len(set(bits)) == len(bits)
