"""What a light viewer reports: frames per second, late frames and frames it never got."""

from bench.viewers import summary


def test_a_pause_counts_as_late_and_missing_sequence_numbers_as_skipped():
    arrivals = [k / 60 for k in range(60)] + [1.5]  # 60 frames at 60 Hz, then a half-second gap
    seqs = list(range(1, 61)) + [90]
    found = summary(arrivals, seqs)
    assert found["frames"] == 61 and found["late"] == 1 and found["skipped"] == 29
    assert 39 < found["fps"] < 41  # 60 frames over 1.5 s
    assert summary([], []) == {"frames": 0, "fps": 0.0, "late": 0, "skipped": 0}
