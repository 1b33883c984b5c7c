#!/usr/bin/python3
"""report.html in a real browser (issue 30): for each reports folder given, remake its page with
`rapid summarize DIR --html-only` in a scratch copy, open it from file:// in headless Chromium with
name resolution switched off, and check

  - the page's own #selftest (experiments/report/report_page.hpp): every sortable column sorts both
    ways, every figure decoded, every seed chart drawn, a Table I link opens its drill-down, no
    script error;
  - no console message at all (Chromium's log) and no link or source that leaves the folder;
  - the DOM against summary.json: every Table I cell's key, exact mean, text and best mark, every
    probability of improvement, every cell's drill-down with each seed's status and final return;
  - then takes a screenshot of the page, kept under --artifacts as <folder name>.png.

Exit 0 when every folder passes, 1 otherwise, 77 (CTest's skip) when Chromium is not installed
unless RAPID_REQUIRE_BROWSER=1 (scripts/test-browser, CI) makes that a failure too.
"""
import argparse
import html.parser
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

CHROMIUM_FLAGS = ["--headless", "--disable-gpu", "--no-sandbox", "--no-first-run", "--hide-scrollbars",
                  # Nothing may be fetched: every name fails to resolve.
                  "--host-resolver-rules=MAP * ~NOTFOUND"]


def find_chromium():
    for name in ("chromium", "chromium-browser"):
        path = shutil.which(name)
        if path:
            return path
    return None


def fixed(x, decimals):
    text = f"{x:.{decimals}f}"
    if text.startswith("-") and set(text) <= set("-0."):
        text = text[1:]  # no "-0.0", as experiments/report/format.cpp
    return text


def table_decimals(summary):
    magnitude = max([abs(c["mean"]) for c in summary["cells"] if c["mean"] is not None] or [0.0])
    return 1 if magnitude >= 100 else 2 if magnitude >= 1 else 3


def cell_text(cell, decimals):
    note = f" (n={cell['n_ok']}/{cell['n_expected']})"
    if cell["mean"] is None:
        return "—" + note
    text = fixed(cell["mean"], decimals) + " ± " + fixed(cell["std"], decimals)
    return text + (note if cell["n_ok"] < cell["n_expected"] else "")


def axis_label(value):
    """A value as experiments/sweep/grid.cpp's axis_value_label spells it."""
    if isinstance(value, list):
        return "x".join(axis_label(v) for v in value)
    return value if isinstance(value, str) else json.dumps(value)


def canonical_key(key):
    """A cell key with its axis values sorted, so the grid's axis order does not matter."""
    parts = key.split("/")
    return "/".join(parts[:3] + [",".join(sorted(parts[3].split(",")))] if len(parts) > 3 else parts)


def cell_key(cell):
    axis = ",".join(f"{k}={axis_label(v)}" for k, v in cell.get("axis", {}).items())
    return canonical_key(f"{cell['scenario']}/{cell['dataset'] or 'none'}/{cell['algo']}" + (f"/{axis}" if axis else ""))


class PageDom(html.parser.HTMLParser):
    """The parts of the page the checks read: tables by id (rows of cells with their attributes and
    text), the drill-downs (their seed rows), the selftest result, every src and href."""

    def __init__(self):
        super().__init__()
        self.tables, self.details, self.links = {}, [], []
        self.selftest = None
        self._table, self._row, self._cell, self._in_selftest = None, None, None, False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for key in ("src", "href"):
            if key in a:
                self.links.append(a[key])
        if tag == "table":
            self._table = a.get("id") or ("seeds" if "seeds" in a.get("class", "") else "other")
            if self._table == "seeds" and self.details:
                self.details[-1]["seeds"] = []
            else:
                self.tables.setdefault(self._table, [])
        elif tag == "tr" and self._table is not None:
            self._row = {"attrs": a, "cells": []}
        elif tag == "td" and self._row is not None:
            self._cell = {"attrs": a, "text": ""}
        elif tag == "details" and "cell-detail" in a.get("class", ""):
            self.details.append({"id": a.get("id"), "cell": a.get("data-cell"), "seeds": []})
        elif tag == "pre" and a.get("id") == "selftest":
            self.selftest = {"status": a.get("data-status"), "text": ""}
            self._in_selftest = True

    def handle_endtag(self, tag):
        if tag == "td" and self._cell is not None:
            self._cell["text"] = self._cell["text"].strip()
            self._row["cells"].append(self._cell)
            self._cell = None
        elif tag == "tr" and self._row is not None:
            if self._row["cells"]:
                if self._table == "seeds":
                    self.details[-1]["seeds"].append(self._row)
                else:
                    self.tables[self._table].append(self._row)
            self._row = None
        elif tag == "table":
            self._table = None
        elif tag == "pre":
            self._in_selftest = False

    def handle_data(self, data):
        if self._cell is not None:
            self._cell["text"] += data
        if self._in_selftest:
            self.selftest["text"] += data


def same_number(attribute, value):
    if value is None:
        return attribute == ""
    return attribute != "" and math.isclose(float(attribute), value, rel_tol=0, abs_tol=0)


def check_dom(dom, summary, figures, problems):
    decimals = table_decimals(summary)
    cells = {cell_key(c): c for c in summary["cells"]}
    table_rows = dom.tables.get("table-i-cells", [])
    if len(table_rows) != len(summary["table"]):
        problems.append(f"Table I has {len(table_rows)} rows, summary.json {len(summary['table'])}")
    for row, dom_row in zip(summary["table"], table_rows):
        dom_cells = {td["attrs"]["data-cell"]: td for td in dom_row["cells"] if "data-cell" in td["attrs"]}
        for column in row["columns"]:
            key = column["cell"]
            td = dom_cells.get(key)
            if td is None:
                problems.append(f"Table I: no cell {key} in its row")
                continue
            cell = cells[canonical_key(key)]
            if not same_number(td["attrs"].get("data-sort", ""), cell["mean"]):
                problems.append(f"Table I {key}: mean {td['attrs'].get('data-sort')} != summary.json {cell['mean']}")
            if td["text"] != cell_text(cell, decimals):
                problems.append(f"Table I {key}: shows '{td['text']}', summary.json gives '{cell_text(cell, decimals)}'")
            best = "best" in td["attrs"].get("class", "").split()
            if best != (row["best"] == column["algo"]):
                problems.append(f"Table I {key}: best mark {best}, summary.json's best is {row['best']}")
    poi_rows = dom.tables.get("poi-table", [])
    if len(poi_rows) != len(summary["probability_of_improvement"]):
        problems.append(f"{len(poi_rows)} probability-of-improvement rows, summary.json "
                        f"{len(summary['probability_of_improvement'])}")
    for entry, dom_row in zip(summary["probability_of_improvement"], poi_rows):
        td = next(td for td in dom_row["cells"] if td["attrs"].get("class") == "p")
        if not same_number(td["attrs"].get("data-sort", ""), entry["p"]):
            problems.append(f"P({entry['algo']} > {entry['baseline']}) in {entry['scenario']}/{entry['dataset']}: "
                            f"{td['attrs'].get('data-sort')} != summary.json {entry['p']}")
    if len(dom.details) != len(summary["cells"]):
        problems.append(f"{len(dom.details)} drill-downs, summary.json has {len(summary['cells'])} cells")
    for cell, detail in zip(summary["cells"], dom.details):
        if len(detail["seeds"]) != len(cell["seeds"]):
            problems.append(f"{detail['cell']}: {len(detail['seeds'])} seed rows, summary.json {len(cell['seeds'])}")
        for seed, row in zip(cell["seeds"], detail["seeds"]):
            status = next(td["text"] for td in row["cells"] if "status" in td["attrs"].get("class", ""))
            final = next(td for td in row["cells"] if td["attrs"].get("class") == "final")
            if row["attrs"].get("data-seed") != str(seed["seed"]) or status != seed["status"] or \
                    not same_number(final["attrs"].get("data-sort", ""), seed["final"]):
                problems.append(f"{detail['cell']} seed {seed['seed']}: page says seed {row['attrs'].get('data-seed')} "
                                f"{status} {final['attrs'].get('data-sort')}, summary.json {seed['status']} {seed['final']}")
    for link in dom.links:
        if re.match(r"^[a-z][a-z0-9+.-]*:", link) and not link.startswith("data:"):
            problems.append(f"a link or source leaves the folder: {link[:80]}")
    if dom.selftest is None:
        problems.append("no #selftest element")
        return
    if dom.selftest["status"] != "pass":
        problems.append(f"#selftest: {dom.selftest['status']}: {dom.selftest['text'][:2000]}")
        return
    result = json.loads(dom.selftest["text"])
    if result["figures"]["count"] != figures:
        problems.append(f"{result['figures']['count']} figures rendered, the folder has {figures} PNGs")
    drawn = sum(1 for c in summary["cells"] if c["n_ok"] > 0)
    if result["curves"]["count"] != drawn:
        problems.append(f"{result['curves']['count']} seed charts, {drawn} cells have ok seeds")
    # rliable's figures, counted against summary.json: a point per comparison and per algorithm
    # with a value, a profile per scenario with an ok run; and the drill-downs' seed dots.
    def numeric(x):
        return isinstance(x, (int, float)) and not isinstance(x, bool)
    expected = {
        "poi": sum(1 for e in summary.get("probability_of_improvement", []) if numeric(e.get("p"))),
        "iqm": sum(1 for e in summary.get("aggregate_iqm", []) if numeric(e.get("iqm"))),
        "profiles": len({c["scenario"] for c in summary["cells"]
                         if any(s.get("status") == "ok" and numeric(s.get("final")) for s in c["seeds"])}),
        # a dot per ok seed with a final return, in its cell's drill-down
        "seed_dots": sum(1 for c in summary["cells"] for s in c["seeds"]
                         if s.get("status") == "ok" and numeric(s.get("final"))),
    }
    for key, count in expected.items():
        if result["rliable"][key] != count:
            problems.append(f"{result['rliable'][key]} {key} drawn, summary.json gives {count}")
    if result["rliable"]["empty"]:
        problems.append(f"empty profile lines: {result['rliable']['empty'][:5]}")
    if not any(t["id"] == "table-i-cells" for t in result["tables"]):
        problems.append("the selftest did not sort Table I")


def run_chromium(chromium, args, profile):
    return subprocess.run([chromium, *CHROMIUM_FLAGS, f"--user-data-dir={profile}", *args],
                          capture_output=True, text=True, timeout=300)


def check_folder(rapid, chromium, folder, artifacts, scratch):
    name = os.path.relpath(folder, os.path.join(folder, "..", "..")).replace(os.sep, "-") \
        if os.path.basename(os.path.dirname(folder)) == "ablations" else os.path.basename(folder)
    copy = os.path.join(scratch, name)
    shutil.copytree(folder, copy)
    made = subprocess.run([rapid, "summarize", copy, "--html-only"], capture_output=True, text=True)
    if made.returncode != 0:
        return [f"rapid summarize --html-only: exit {made.returncode}: {made.stdout}{made.stderr}"]
    with open(os.path.join(copy, "summary.json")) as f:
        summary = json.load(f)
    figures = len([f for f in os.listdir(copy) if f.endswith(".png") and
                   (f.startswith("figure") or f.startswith("sensitivity-"))])
    url = "file://" + os.path.join(copy, "report.html")
    profile = os.path.join(scratch, name + "-profile")
    shown = run_chromium(chromium, ["--enable-logging=stderr", "--v=0", "--virtual-time-budget=15000",
                                    "--dump-dom", url + "#selftest"], profile)
    problems = []
    if shown.returncode != 0:
        problems.append(f"chromium --dump-dom exited {shown.returncode}: {shown.stderr[-2000:]}")
    # The page writes nothing to the console; anything there is a script error or a failed load.
    problems += [f"console: {line}" for line in shown.stderr.splitlines() if ":CONSOLE" in line]
    dom = PageDom()
    dom.feed(shown.stdout)
    check_dom(dom, summary, figures, problems)
    os.makedirs(artifacts, exist_ok=True)
    screenshot = os.path.abspath(os.path.join(artifacts, name + ".png"))
    shot = run_chromium(chromium, ["--window-size=1280,3000", "--virtual-time-budget=5000",
                                   f"--screenshot={screenshot}", url], profile)
    if shot.returncode != 0 or not os.path.isfile(screenshot) or os.path.getsize(screenshot) < 10000:
        problems.append(f"no screenshot at {screenshot}: {shot.stderr[-1000:]}")
    print(f"{name}: {'ok' if not problems else 'FAILED'} (page {os.path.getsize(os.path.join(copy, 'report.html')) // 1024} kB, "
          f"screenshot {screenshot})")
    return problems


HOSTILE = "<img src=x onerror=document.documentElement.setAttribute('data-xss',1)>"


def check_hostile(rapid, chromium, folder, scratch):
    """A summary.json edited to carry a script in the fields that once reached the page raw
    (issue 46: grid.seeds, the status counts, the provenance counts): `--html-only` shows it as
    text and Chromium runs nothing of it."""
    copy = os.path.join(scratch, "hostile")
    shutil.copytree(folder, copy)
    with open(os.path.join(copy, "summary.json")) as f:
        summary = json.load(f)
    summary["status_counts"] = {"ok": HOSTILE}
    summary["grid"]["seeds"] = [HOSTILE]
    summary.setdefault("provenance", {})["code_revisions"] = {"0000000": HOSTILE}
    with open(os.path.join(copy, "summary.json"), "w") as f:
        json.dump(summary, f)
    made = subprocess.run([rapid, "summarize", copy, "--html-only"], capture_output=True, text=True)
    if made.returncode != 0:
        return [f"hostile summary.json: rapid summarize --html-only: exit {made.returncode}: {made.stdout}{made.stderr}"]
    shown = run_chromium(chromium, ["--virtual-time-budget=5000", "--dump-dom",
                                    "file://" + os.path.join(copy, "report.html")], os.path.join(scratch, "hostile-profile"))
    problems = []
    html_tag = re.search(r"<html[^>]*>", shown.stdout)
    if html_tag is None:
        problems.append(f"hostile summary.json: no page in chromium's DOM: {shown.stderr[-1000:]}")
    elif "data-xss" in html_tag.group(0):
        problems.append(f"hostile summary.json: the page ran the injected handler: {html_tag.group(0)}")
    if "&lt;img src=x" not in shown.stdout:
        problems.append("hostile summary.json: the injected text is not shown as text")
    print(f"hostile summary.json: {'ok' if not problems else 'FAILED'}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folders", nargs="+", help="reports folders (results/quick, …)")
    parser.add_argument("--rapid", required=True, help="the rapid binary")
    parser.add_argument("--artifacts", required=True, help="where the screenshots are kept")
    args = parser.parse_args()
    chromium = find_chromium()
    if chromium is None:
        if os.environ.get("RAPID_REQUIRE_BROWSER") == "1":
            print("check_report_page: chromium is not installed (scripts/test-browser installs it)")
            return 1
        print("SKIP: chromium is not installed; scripts/test-browser installs it and runs this test")
        return 77
    failed = False
    with tempfile.TemporaryDirectory(prefix="rapid-browser-") as scratch:
        for folder in args.folders:
            for problem in check_folder(args.rapid, chromium, os.path.abspath(folder), args.artifacts, scratch):
                failed = True
                print(f"  {problem}")
        # The first folder whose summary has provenance, so that all three fields reach the page.
        with_provenance = [f for f in args.folders if "provenance" in json.load(open(os.path.join(f, "summary.json")))]
        for problem in check_hostile(args.rapid, chromium, os.path.abspath((with_provenance or args.folders)[0]), scratch):
            failed = True
            print(f"  {problem}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
