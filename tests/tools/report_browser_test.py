#!/usr/bin/python3
"""The campaign report of `rockfit report` in a real browser: headless Chromium driven through Selenium.

Builds the report of the bundled sample campaign (summary, batch, one earthquake response, a small fragility
study; in a Debug build the summary alone), opens it and checks

  * it loads without a console error or an uncaught script exception,
  * every figure is an inline SVG with a non-empty rendered size (none is reported missing),
  * the page has one trial section per trial of the campaign's manifest,
  * the sort buttons of a table work,
  * printed (DevTools Page.printToPDF) it gives A4 pages, no table is wider than the page, and no figure can be
    cut across pages: every figure
    has `break-inside: avoid` and, laid out for print at the printable width of A4, is shorter than the
    printable height (so Chromium's paginator can keep each one on a single page).

Then it checks the checker: the same checks must fail on a copy of the report whose script throws and on the
report written without gnuplot (figures missing). Exit 0: passed; 1: failed; 77: skipped (no Chromium,
chromedriver, Selenium or gnuplot) — ctest's SKIP_RETURN_CODE.

    report_browser_test.py --rockfit build/tools/rockfit --source-dir . --work-dir build/report_browser
    report_browser_test.py ... --screenshot docs/report.png   (also saves a screenshot of the page's top)
"""
import argparse
import base64
import os
import re
import shutil
import subprocess
import sys
import tomllib

SKIP = 77
CHROMIUM = "/usr/bin/chromium"
CHROMEDRIVER = "/usr/bin/chromedriver"
# A4 in CSS px (96 px per inch) and the page margins of the report's @page rule (14 mm top/bottom, 12 mm sides).
MM_PX = 96.0 / 25.4
A4_PRINTABLE_WIDTH_PX = (210 - 2 * 12) * MM_PX
A4_PRINTABLE_HEIGHT_PX = (297 - 2 * 14) * MM_PX
# A4 in PDF points (1/72 inch); Chromium rounds the page size to about a point.
A4_PT = (595.28, 841.89)
A4_TOLERANCE_PT = 1.5


def skip(reason):
    print(f"SKIP: {reason}")
    sys.exit(SKIP)


def run(cmd, **kwargs):
    print("$", " ".join(str(c) for c in cmd), flush=True)
    return subprocess.run([str(c) for c in cmd], check=True, **kwargs)


def make_driver():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service

    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--window-size=1100,900", "--force-device-scale-factor=1", "--hide-scrollbars"):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    return webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)


def pdf_pages(pdf):
    """The MediaBox of every page object of a PDF (Chromium writes them uncompressed)."""
    boxes = []
    for m in re.finditer(rb"/Type\s*/Page\b(?!s).*?/MediaBox\s*\[\s*([-\d.\s]+)\]", pdf, re.S):
        boxes.append([float(v) for v in m.group(1).split()])
    if not boxes:  # MediaBox before /Type in the dictionary
        for m in re.finditer(rb"/MediaBox\s*\[\s*([-\d.\s]+)\][^>]*?/Type\s*/Page\b(?!s)", pdf, re.S):
            boxes.append([float(v) for v in m.group(1).split()])
    return boxes


def check_report(driver, path, expected_trials):
    """Every failure found in the report at `path`, as sentences (empty: passed)."""
    failures = []
    driver.get_log("browser")  # drop what earlier pages logged
    driver.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "screen"})
    driver.set_window_size(1100, 900)
    driver.get("file://" + os.path.abspath(path))
    for entry in driver.get_log("browser"):
        if entry.get("level") in ("SEVERE", "ERROR"):
            failures.append(f"console error: {entry.get('message')}")

    figures = driver.execute_script("""
        return Array.from(document.querySelectorAll('figure')).map(function (f) {
          var svg = f.querySelector('svg');
          var r = svg ? svg.getBoundingClientRect() : null;
          return {name: f.getAttribute('data-figure'), missing: f.classList.contains('figure-missing'),
                  text: f.textContent.trim().slice(0, 200), width: r ? r.width : 0, height: r ? r.height : 0,
                  drawn: svg ? svg.querySelectorAll('path, polyline, line, use').length : 0};
        });""")
    if not figures:
        failures.append("the page has no figures")
    for f in figures:
        if f["missing"]:
            failures.append(f"figure {f['name']} is missing: {f['text']}")
        elif f["width"] <= 0 or f["height"] <= 0 or f["drawn"] == 0:
            failures.append(f"figure {f['name']} renders empty ({f['width']}×{f['height']} px, {f['drawn']} marks)")

    trials = driver.execute_script("return document.querySelectorAll('section.trial').length;")
    if trials != expected_trials:
        failures.append(f"{trials} trial sections, the campaign has {expected_trials} trials")

    # Sort the first sortable table by its last column, twice (descending after ascending).
    sorted_ok = driver.execute_script("""
        var table = document.querySelector('table.sortable');
        if (!table) return 'no sortable table';
        var th = table.tHead.rows[0].cells[table.tHead.rows[0].cells.length - 1];
        var button = th.querySelector('button');
        if (!button) return 'no sort button';
        button.click();
        if (th.getAttribute('aria-sort') !== 'ascending') return 'not ascending after one click';
        button.click();
        if (th.getAttribute('aria-sort') !== 'descending') return 'not descending after two clicks';
        return '';""")
    if sorted_ok:
        failures.append(f"table sorting: {sorted_ok}")
    for entry in driver.get_log("browser"):
        if entry.get("level") in ("SEVERE", "ERROR"):
            failures.append(f"console error after sorting: {entry.get('message')}")

    # Print: A4 pages.
    pdf = base64.b64decode(driver.execute_cdp_cmd("Page.printToPDF", {
        "printBackground": True, "preferCSSPageSize": True, "paperWidth": 8.27, "paperHeight": 11.69})["data"])
    pages = pdf_pages(pdf)
    if not pages:
        failures.append("the PDF has no pages that this check can read")
    for box in pages:
        w, h = box[2] - box[0], box[3] - box[1]
        if abs(w - A4_PT[0]) > A4_TOLERANCE_PT or abs(h - A4_PT[1]) > A4_TOLERANCE_PT:
            failures.append(f"a printed page is {w:.1f}×{h:.1f} pt, not A4")
            break
    if pages and len(pages) < expected_trials:
        failures.append(f"{len(pages)} printed pages for {expected_trials} trials (each trial starts a page)")

    # Print layout: every figure unbreakable and shorter than a page.
    driver.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "print"})
    driver.execute_cdp_cmd("Emulation.setDeviceMetricsOverride", {
        "width": int(A4_PRINTABLE_WIDTH_PX), "height": int(A4_PRINTABLE_HEIGHT_PX), "deviceScaleFactor": 1,
        "mobile": False})
    printed = driver.execute_script("""
        return Array.from(document.querySelectorAll('figure')).map(function (f) {
          var s = getComputedStyle(f);
          return {name: f.getAttribute('data-figure'), height: f.getBoundingClientRect().height,
                  width: f.getBoundingClientRect().width, avoid: s.breakInside};
        });""")
    wide_tables = driver.execute_script("""
        return Array.from(document.querySelectorAll('table')).filter(function (t) {
          return t.getBoundingClientRect().width > arguments[0] + 1;
        }).map(function (t) { return t.caption ? t.caption.textContent.slice(0, 80) : '(no caption)'; });""",
        A4_PRINTABLE_WIDTH_PX)
    driver.execute_cdp_cmd("Emulation.clearDeviceMetricsOverride", {})
    for caption in wide_tables:
        failures.append(f"table '{caption}' is wider than an A4 page in print: it would be cut")
    for f in printed:
        if f["avoid"] != "avoid":
            failures.append(f"figure {f['name']} may break across pages (break-inside: {f['avoid']})")
        if f["height"] > A4_PRINTABLE_HEIGHT_PX:
            failures.append(f"figure {f['name']} is {f['height']:.0f} px high in print, more than an A4 page "
                            f"({A4_PRINTABLE_HEIGHT_PX:.0f} px): it would be cut")
        if f["width"] > A4_PRINTABLE_WIDTH_PX + 1:
            failures.append(f"figure {f['name']} is {f['width']:.0f} px wide in print, wider than A4")
    print(f"{path}: {len(figures)} figures, {trials} trial sections, {len(pages)} A4 pages, "
          f"{len(failures)} failure(s)", flush=True)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--rockfit", required=True)
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--screenshot", help="also save a PNG of the top of the page here")
    parser.add_argument("--optimised", type=int, default=1,
                        help="0 for a Debug build: the report of the summary alone (its simulator runs ~150x slower, "
                             "too slow for the campaign's fits and the earthquake response)")
    args = parser.parse_args()

    for tool in (CHROMIUM, CHROMEDRIVER):
        if not os.access(tool, os.X_OK):
            skip(f"{tool} is not installed (apt-get install --no-install-recommends chromium chromium-driver)")
    try:
        import selenium  # noqa: F401
    except ImportError:
        skip("Selenium is not installed (apt-get install --no-install-recommends python3-selenium)")
    if shutil.which("gnuplot") is None:
        skip("gnuplot is not installed: the report would have no figures to check (apt-get install gnuplot-nox)")

    manifest = os.path.join(args.source_dir, "data-samples", "manifest.toml")
    with open(manifest, "rb") as f:
        expected_trials = len(tomllib.load(f)["trials"])
    work = args.work_dir
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    rockfit = args.rockfit
    campaign, fits = os.path.join(work, "campaign.h5"), os.path.join(work, "fits.h5")
    response = os.path.join(work, "response.h5")
    report = os.path.join(work, "report.html")
    quiet = {"stdout": subprocess.DEVNULL}
    run([rockfit, "summary", manifest, "-o", campaign], **quiet)
    fragility = os.path.join(work, "fragility.h5")
    inputs = []
    if args.optimised:
        run([rockfit, "batch", manifest, "-o", fits], **quiet)
        run([rockfit, "respond", "--manifest", manifest, "--block", "block2", "--fits", fits, "--group", "block2,A",
             "--record", os.path.join(args.source_dir, "data-samples", "ground-motions", "cp-seed2-0.45g.AT2"),
             "--angle", "30", "--format", "hdf5", "-o", response], **quiet)
        # A small fragility study of block2 with its fitted parameters (two levels, two samples each).
        run([rockfit, "fragility", "--manifest", manifest, "--block", "block2", "--fits", fits, "--group", "block2,A",
             "--synthetic-records", "1", "--synthetic-duration", "3", "--tail", "1", "--pga", "0.3,0.6",
             "--samples", "2", "--seed", "5", "-o", fragility], **quiet)
        inputs = ["--fits", fits, "--response", response, "--fragility", fragility]
    run([rockfit, "report", campaign, *inputs, "-o", report])

    # The checker's own check: a report whose script throws, and one written without gnuplot.
    throwing = os.path.join(work, "report-throws.html")
    with open(report, encoding="utf-8") as f:
        html = f.read()
    with open(throwing, "w", encoding="utf-8") as f:
        f.write(html.replace("</body>", "<script>throw new Error('deliberate failure');</script>\n</body>"))
    no_gnuplot = os.path.join(work, "report-no-gnuplot.html")
    env = dict(os.environ, ROCKFIT_GNUPLOT=os.path.join(work, "no-such-gnuplot"))
    run([rockfit, "report", campaign, *inputs[:2], "-o", no_gnuplot], env=env, stderr=subprocess.DEVNULL)

    driver = make_driver()
    try:
        failures = check_report(driver, report, expected_trials)
        if args.screenshot:
            driver.execute_cdp_cmd("Emulation.setEmulatedMedia", {"media": "screen"})
            driver.set_window_size(1000, 1300)
            driver.get("file://" + os.path.abspath(report))
            driver.save_screenshot(args.screenshot)
            print(f"screenshot {args.screenshot}")
        for broken, must_find in ((throwing, "console error"), (no_gnuplot, "is missing")):
            found = check_report(driver, broken, expected_trials)
            if not any(must_find in f for f in found):
                failures.append(f"the check passed {broken}, which it must fail ({must_find}); it found: {found}")
        # Without gnuplot the page still has every table of the same inputs with gnuplot (the fragility and
        # response files aside, which the run without gnuplot is not given).
        count = "return document.querySelectorAll('table').length - document.querySelectorAll('#earthquake table').length;"
        driver.get("file://" + os.path.abspath(report))
        with_gnuplot = driver.execute_script(count)
        driver.get("file://" + os.path.abspath(no_gnuplot))
        without = driver.execute_script(count)
        if without != with_gnuplot or without == 0:
            failures.append(f"the report without gnuplot has {without} tables, with gnuplot {with_gnuplot}")
    finally:
        driver.quit()
    for f in failures:
        print("FAIL:", f)
    print("PASS" if not failures else f"{len(failures)} failure(s)")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
