"""The HTML report escapes every cell exactly once (list cells were escaped twice)."""
from html.parser import HTMLParser

from embroact.export.report.report import report_html


class _Cells(HTMLParser):
    def __init__(self):
        super().__init__()
        self.cells, self._in = [], False

    def handle_starttag(self, tag, attrs):
        self._in = tag == "td"
        if self._in:
            self.cells.append("")

    def handle_endtag(self, tag):
        self._in = False if tag == "td" else self._in

    def handle_data(self, data):
        if self._in:
            self.cells[-1] += data


def test_list_and_scalar_cells_read_back_as_written():
    data = {"title": "t", "generator": "g", "actuators": [], "findings": [],
            "worksheet": {"note": "a<b & c", "size_mm": ["x<y", "p&q", 1.5]}}
    parser = _Cells()
    parser.feed(report_html(data))
    # an HTML parser (not embroact) decodes each cell to the text that was written
    assert "a<b & c" in parser.cells and "x<y, p&q, 1.5" in parser.cells
