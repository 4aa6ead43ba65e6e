"""The field sheet (``pumplink sheet``): one A4 page, rendered by PDFium (pypdfium2), with the
figures a mechanic needs.

The expected figures are the formulas of docs/water.md §5 written out here for the village well
(10 m, a 23 mm main, η_v 0.87, a 0.25 m wheel at 316 deg/s): a 20-litre container takes
V / (η_v (π d²/4) 2π r_w) = 35.2 crank turns, V / Q = 40.1 s; an empty main fills in
H / (2π r_w η_v) = 7.32 turns; 6 million turns at 316/360 turns a second take 1,899 h.  The page is
A4, 210 x 297 mm = 595.28 x 841.89 pt.
"""

from __future__ import annotations

import math

import numpy as np
import pypdfium2 as pdfium
import pytest
from shipped import ROOT

from pumplink.inputs.pump import load_spec
from pumplink.output.sheet import sheet_html, write_sheet_pdf
from pumplink.studies.force import force_analysis
from pumplink.studies.sheet import field_sheet

VILLAGE = ROOT / "configs" / "village-10m.toml"
AREA = 1000.0 * math.pi * 0.023**2 / 4 / 1000.0  # the main's bore [m^2]
TURN = 0.87 * AREA * 2 * math.pi * 0.25  # the water a crank turn delivers [m^3]


@pytest.fixture(scope="module")
def village_sheet(tmp_path_factory):
    fs = field_sheet(force_analysis(load_spec(VILLAGE), keep_samples=False))
    path = write_sheet_pdf(fs, tmp_path_factory.mktemp("sheet") / "sheet.pdf", "test")
    return fs, path


def test_the_sheet_is_one_a4_page_with_the_mechanic_s_figures(village_sheet):
    fs, path = village_sheet
    pdf = pdfium.PdfDocument(str(path))
    assert len(pdf) == 1
    page = pdf[0]
    assert page.get_size() == pytest.approx((595.28, 841.89), abs=0.01)
    text = " ".join(page.get_textpage().get_text_range().split())  # the lines joined
    turns = 0.020 / TURN
    seconds = turns * 360.0 / 316.0
    assert round(turns) == 35 and round(seconds) == 40
    assert f"Expected: {round(turns)} turns in {round(seconds)} s" in text
    assert f"after {10.0 / (2 * math.pi * 0.25 * 0.87):.1f} turns" in text  # 7.3
    assert f"{6e6 / (316.0 / 360.0) / 3600.0:,.0f} h" in text  # 1,899 h
    assert "More than 41 turns: the pistons leak" in text  # 35.2 x 1.15
    assert "the ratchet must catch within 0.10 m at the grip (24 teeth" in text
    assert "DGUV Vorschrift 54" in text and "USAID" in text and "Field sheet: Village well, 10 m head" in text
    # everything printed lies on the page, inside its margins
    tp = page.get_textpage()
    boxes = np.array([tp.get_charbox(i) for i in range(tp.count_chars())])
    assert boxes[:, 0].min() >= 0.5 * 72 and boxes[:, 2].max() <= 595.28 - 0.5 * 72
    assert boxes[:, 1].min() >= 0.5 * 72 and boxes[:, 3].max() <= 841.89 - 0.5 * 72
    # and it is drawn: dark pixels in the top half, the bottom strip blank
    image = np.asarray(page.render(scale=0.5).to_pil().convert("L"))
    assert (image[: image.shape[0] // 2] < 128).sum() > 1000 and (image[-20:] > 250).all()


def test_the_report_s_sheet_is_the_pdf_s(village_sheet):
    """The report's section says what the page says (the same sentences)."""
    fs, path = village_sheet
    text = pdfium.PdfDocument(str(path))[0].get_textpage().get_text_range()
    section = sheet_html(fs)
    for words in ("Expected: 35 turns in 40 s", "the ratchet must catch within 0.10 m", "1,899 h"):
        assert words in section and words in " ".join(text.split())


def test_a_long_name_wraps_inside_the_page(village_sheet, tmp_path):
    """A spec's name of the most characters a spec allows wraps over the title's lines: the page
    stays one A4 page with everything inside its margins."""
    from dataclasses import replace

    from pumplink.inputs.toml import MAX_NAME_CHARS

    fs, _ = village_sheet
    name = ("Village well of the district's upper heights, hand pump " * 5)[:MAX_NAME_CHARS]
    path = write_sheet_pdf(replace(fs, name=name), tmp_path / "long.pdf", "test")
    pdf = pdfium.PdfDocument(str(path))
    assert len(pdf) == 1
    tp = pdf[0].get_textpage()
    boxes = np.array([tp.get_charbox(i) for i in range(tp.count_chars())])
    assert boxes[:, 0].min() >= 0.5 * 72 and boxes[:, 2].max() <= 595.28 - 0.5 * 72
    assert boxes[:, 1].min() >= 0.5 * 72 and boxes[:, 3].max() <= 841.89 - 0.5 * 72
    assert "hand pump" in " ".join(tp.get_text_range().split())
