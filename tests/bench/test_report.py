"""RESULTS.md's generated section replaces the last one and keeps the notes below it."""

from bench.report import BEGIN, END, write


def test_the_section_is_replaced_and_the_notes_stay(tmp_path):
    path = tmp_path / "RESULTS.md"
    path.write_text("# Benchmark results\n\nOld notes.\n")
    write(path, ["run 1"])
    write(path, ["run 2"])
    assert path.read_text() == f"# Benchmark results\n\n{BEGIN}\nrun 2\n{END}\n\nOld notes.\n"
