"""RESULTS.md's generated section replaces the last one and keeps the notes below it."""

from bench.report import BEGIN, END, write


def test_the_section_is_replaced_and_the_notes_stay(tmp_path):
    path = tmp_path / "RESULTS.md"
    path.write_text("# Benchmark results\n\nOld notes.\n")
    write(path, ["run 1"])
    write(path, ["run 2"])
    assert path.read_text() == f"# Benchmark results\n\n{BEGIN}\nrun 2\n{END}\n\nOld notes.\n"


def test_a_target_not_measured_reads_none_and_unmet():
    from bench.report import TARGETS, headline_table
    results = {name: 0.0 for name in TARGETS} | {"cluster_busy_scenes_fps_median": None}
    [row] = [r for r in headline_table(results) if "cluster_busy_scenes_fps_median" in r]
    assert row == "| `cluster_busy_scenes_fps_median` | none | 60 Hz | **no** |"
