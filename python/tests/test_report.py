"""rockfit.report: the campaign page of `rockfit report`, the same code and the same summary as its --json."""
import pathlib

import pytest

from conftest import MANIFEST, run_cli, run_cli_plain

SAMPLE_TRIALS = 16  # data-samples/manifest.toml


@pytest.fixture(scope="module")
def summary_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("report") / "campaign.h5"
    code, _, err = run_cli_plain("summary", MANIFEST, "-o", path)
    assert code == 0, err
    return path


def test_report_equals_the_program(rockfit, summary_file, tmp_path):
    page = tmp_path / "report.html"
    result = rockfit.report(summary_file, page, figures=False)  # pathlib paths
    cli = run_cli("report", summary_file, "-o", tmp_path / "cli.html", "--no-figures")
    assert result.trials == cli["trials"] == SAMPLE_TRIALS
    assert result.trials_fitted == 0
    assert result.figures == 0 and len(result.figures_missing) == len(cli["figures_missing"])
    assert result.gaps == cli["gaps"]
    assert any("no fits file was given" in g["what"] for g in result.gaps)
    html = page.read_text(encoding="utf-8")
    assert html.count('<section class="trial"') == SAMPLE_TRIALS
    assert result.bytes == len(html.encode("utf-8"))


def test_report_of_a_file_that_is_not_a_summary_raises_input_error(rockfit, tmp_path):
    bad = tmp_path / "bad.h5"
    bad.write_text("not HDF5")
    with pytest.raises(rockfit.InputError):
        rockfit.report(bad, tmp_path / "out.html")
    assert not (tmp_path / "out.html").exists()
