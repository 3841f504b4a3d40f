"""Feature tests: behaviour across many modules (fuzzing, persistence, hand kinematics and
contacts), kept apart from the tests that mirror one module each."""
