"""The episodes' rewards are MyoSuite's, and every grip pattern has its object's name."""

from __future__ import annotations

import pytest

from virtual_prosthetics.gym.episodes import EPISODES, OBJECTS, hold_reward, relocate_reward
from virtual_prosthetics.tasks.grasp import PATTERN_NAMES


def test_hold_rewards_nearness_with_bonuses_and_punishes_a_drop():
    assert hold_reward(0.005, 0.0, False) == pytest.approx(-0.5 + 8)  # both bonuses
    assert hold_reward(0.015, 0.0, False) == pytest.approx(-1.5 + 4)  # within twice 10 mm
    assert hold_reward(0.1, 0.0, True) == pytest.approx(-10 - 10)


def test_relocate_rewards_nearness_in_place_and_turn():
    assert relocate_reward(0.02, 0.5, False) == pytest.approx(-2.5)


def test_every_pattern_has_an_object_name_and_every_episode_offers_known_patterns():
    assert sorted(OBJECTS.values()) == sorted(PATTERN_NAMES)
    for episode in EPISODES.values():
        assert set(episode.patterns) <= set(PATTERN_NAMES) and episode.seconds > 0
