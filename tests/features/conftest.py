"""Feature tests of the core use the same fresh scene as its unit tests."""

from tests.server.core.conftest import scene  # noqa: F401  (a fixture, found by name)
