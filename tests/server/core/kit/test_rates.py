"""A connection's rates: token buckets on the caller's clock."""

from server.core.kit.rates import TokenBucket


def test_a_bucket_allows_two_seconds_worth_at_once_then_its_rate():
    bucket = TokenBucket(100, now=0.0)
    assert bucket.take(200, now=0.0)
    assert not bucket.take(1, now=0.0)          # empty: nothing spent
    assert bucket.take(50, now=0.5)              # refilled at 100 a second
    assert not bucket.take(60, now=0.5)
    assert bucket.take(200, now=100.0) and not bucket.take(1, now=100.0)   # capped at 2 s worth
