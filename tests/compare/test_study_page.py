"""compare.studies.study_page: a study's page written the one way (folder made, load stated, page printed)."""
import re

from compare.studies.study_page import load_line, write_page


def test_a_page_is_written_with_its_load_and_printed(tmp_path, capsys):
    path = write_page(tmp_path / "new" / "page.md", ["# A study", "", "| a | b |", "|---|---|", "| 1 | 2 |", "", ""])
    text = path.read_text()
    head, load = text.rsplit("\n\n", 1)
    # the table as given, its trailing blank lines dropped; then one blank line, the load line and a final newline
    assert head == "# A study\n\n| a | b |\n|---|---|\n| 1 | 2 |"
    assert re.fullmatch(r"Machine load while measured: \d+\.\d\d \(1-min average, \d+ cores\)\.\n", load), load
    assert capsys.readouterr().out == text + "\n"


def test_a_page_without_the_load_line(tmp_path, capsys):
    path = write_page(tmp_path / "page.md", ["# A study", "cost: stated in the text", ""], load=False)
    assert path.read_text() == "# A study\ncost: stated in the text\n"
    assert "load" not in capsys.readouterr().out
    assert load_line().startswith("Machine load while measured: ")
