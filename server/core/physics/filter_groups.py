"""Bullet's collision filter groups of a world (a pair is tested when each one's group is
in the other's mask).

- The ground (GROUND_GROUP) meets every part.
- Parts (BODY_GROUP) meet the ground, each other and resting bodies, through Bullet's own
  broadphase and narrowphase.
- A part in a kinematic crowd (CROWD_GROUP) meets nothing there, so Bullet's pair cache
  never grows with the square of a pile: its pairs are measured one by one, a budget a
  tick (contacts.py).
- A resting body (RESTING_GROUP, dynamic mode: resting.py) meets parts that move, not the
  ground or other resting bodies: Bullet neither pairs nor solves a resting heap's contacts.
"""

GROUND_GROUP, GROUND_MASK = 1, -1
BODY_GROUP, BODY_MASK = 2, 1 | 2 | 8
CROWD_GROUP, CROWD_MASK = 4, 0
RESTING_GROUP, RESTING_MASK = 8, 2
