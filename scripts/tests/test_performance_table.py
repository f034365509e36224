"""scripts/performance-table.py on a recorded `pliant bench --json --quick` output
(data/bench-quick.json, from the development machine): the table between the markers is
rebuilt from it, every row reading the JSON's numbers, and nothing outside the markers
changes; a page without markers or a partial report is refused with a message."""

import json
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).parent
SCRIPT = HERE.parent / "performance-table.py"
FIXTURE = HERE / "data" / "bench-quick.json"

PAGE = """# Performance

Before the table.

<!-- bench:begin -->
| an old | table |
<!-- bench:end -->

After the table.
"""


def run(doc: Path, json_path: Path = FIXTURE):
    return subprocess.run([sys.executable, str(SCRIPT), str(json_path), "--doc", str(doc),
                           "--measured", "2026-12-06, quick"], capture_output=True, text=True)


def table_rows(page: str):
    block = page.split("<!-- bench:begin -->")[1].split("<!-- bench:end -->")[0]
    return {line.split(" | ")[0].lstrip("| "): line for line in block.splitlines() if line.startswith("| ")}


def test_the_table_is_rebuilt_from_the_json_between_the_markers(tmp_path):
    doc = tmp_path / "performance.md"
    doc.write_text(PAGE)
    result = run(doc)
    assert result.returncode == 0, result.stderr
    page = doc.read_text()
    assert page.startswith("# Performance\n\nBefore the table.\n\n<!-- bench:begin -->\n")
    assert page.endswith("<!-- bench:end -->\n\nAfter the table.\n")
    assert "an old" not in page
    assert "Measured 2026-12-06, quick on AMD EPYC, 2 logical cores" in page
    assert "--quick: short windows" in page

    report = json.loads(FIXTURE.read_text())
    rows = table_rows(page)
    head = next(r for r in report["rows"] if r["name"] == "1 hose × 100")
    assert f"{head['ns_per_element_step']:.1f} ns per element-step" in rows["explicit element step, 1 hose × 100"]
    thousand = next(r for r in report["rows"] if r["name"] == "1 hose × 1000")
    assert f"{thousand['realtime_factor']:.2f}× real time" in rows["one 1\u202f000-element hose"]
    many = [r for r in report["rows"] if r["name"].startswith("30 hoses × 30")]
    assert len(many) == 2
    for r in many:
        assert f"{r['realtime_factor']:.2f}×" in rows["30 hoses × 30 elements"]
    contact = report["contact"]
    contact_row = next(v for k, v in rows.items() if k.startswith("rigid contact"))
    assert f"{contact['ratio']:.2f}× the contact-free step" in contact_row
    assert f"{contact['moving_ratio']:.2f}× the floor at rest" in rows["the same floor moving"]
    newton = report["newton"]
    assert f"{newton['static_update_ms_30']:.3f} ms" in rows["quasi-static update, 30 elements"]
    bay = next(v for k, v in rows.items() if k.startswith("engine bay"))
    for r in report["engine_bay"]["rows"]:
        if not r["sleeping"]:
            assert f"{r['solver']} {r['realtime_factor']:.2f}×" in bay
    # the header and the nine rows of this report
    assert len(rows) == 1 + 9, list(rows)

    # again from the same JSON: the same page
    assert run(doc).returncode == 0
    assert doc.read_text() == page


def test_a_page_without_markers_is_refused_and_left_alone(tmp_path):
    doc = tmp_path / "performance.md"
    doc.write_text("# Performance\n\nno markers\n")
    result = run(doc)
    assert result.returncode == 1
    assert "needs one `<!-- bench:begin -->` followed by one `<!-- bench:end -->`" in result.stderr
    assert doc.read_text() == "# Performance\n\nno markers\n"


def test_a_partial_report_is_refused_naming_the_missing_field(tmp_path):
    doc = tmp_path / "performance.md"
    doc.write_text(PAGE)
    partial = tmp_path / "contact-only.json"
    report = json.loads(FIXTURE.read_text())
    partial.write_text(json.dumps(report["contact"]))
    result = run(doc, partial)
    assert result.returncode == 1
    assert "contact-only.json: report: no field `rows`" in result.stderr
    assert doc.read_text() == PAGE


def test_quasi_static_updates_that_did_not_converge_are_named_in_their_row(tmp_path):
    doc = tmp_path / "performance.md"
    doc.write_text(PAGE)
    counted = tmp_path / "unconverged.json"
    report = json.loads(FIXTURE.read_text())
    report["newton"]["static_unconverged_30"] = 0
    report["newton"]["static_contact_unconverged_30"] = 31
    counted.write_text(json.dumps(report))
    assert run(doc, counted).returncode == 0
    row = table_rows(doc.read_text())["quasi-static update, 30 elements"]
    assert "; 31 updates against the part did not converge" in row
    assert "; 0 updates" not in row
