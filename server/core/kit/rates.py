"""Per-connection rates: token buckets refilled by the clock the caller passes in."""

from __future__ import annotations


class TokenBucket:
    """Up to ``rate`` units a second, with bursts of up to two seconds' worth."""

    def __init__(self, rate: int, now: float) -> None:
        self.rate = rate
        self.capacity = 2.0 * rate
        self._tokens = self.capacity
        self._time = now

    def take(self, amount: float, now: float) -> bool:
        """Spend ``amount`` if the bucket holds it (then True); else spend nothing."""
        self._tokens = min(self.capacity, self._tokens + (now - self._time) * self.rate)
        self._time = now
        if amount > self._tokens:
            return False
        self._tokens -= amount
        return True
