#!/usr/bin/env python3
"""Draws the overlay plots of `sandcastle compare` and writes OUT_DIR/compare.html.

Usage: compare_report.py OUT_DIR   (reads OUT_DIR/compare.json, format: reports/README.md)
Every plot of run A's series.json is redrawn to OUT_DIR/<case>/<file> with both runs
(overlay.py: a series equal in both is drawn once, one that differs for A solid and B dashed).
"""
import json
import os
import sys

import overlay
from html_report import esc, image, number, page, table


def load(path):
    with open(path) as f:
        return json.load(f)


def plots_of(out_dir, case):
    """Draws the case's overlays; returns their paths."""
    files = case["series_file"]
    if not files["a"] or not files["b"] or not os.path.exists(files["a"]) or not os.path.exists(files["b"]):
        return []
    doc_a, doc_b = load(files["a"]), load(files["b"])
    series_a = {s["name"]: s for s in doc_a["series"]}
    series_b = {s["name"]: s for s in doc_b["series"]}
    os.makedirs(os.path.join(out_dir, case["name"]), exist_ok=True)
    paths = []
    for plot in doc_a["plots"]:
        path = os.path.join(out_dir, case["name"], plot["file"])
        overlay.draw(plot, series_a, series_b, ("A", "B"), path)
        paths.append(path)
    return paths


def case_section(out_dir, c):
    state = "identical" if c["identical"] else "changed"
    out = (f'<h2>{esc(c["name"])} <span class="{state}">{state}</span></h2><p>status {esc(c["status"]["a"])} &rarr; '
           f'{esc(c["status"]["b"])}, checksum <code>{esc(c["state_checksum"]["a"])}</code> &rarr; '
           f'<code>{esc(c["state_checksum"]["b"])}</code></p>')
    rows = [[esc(n), number(m["a"]), number(m["b"]), number(m["delta"]), number(m["relative"])]
            for n, m in c["metrics"].items()]
    out += table(["metric", "A", "B", "delta", "relative"], rows)
    rows = [[esc(n), number(s.get("relative_rms")), number(s.get("max_difference")), esc(s.get("note", ""))]
            for n, s in c["series"].items()]
    out += table(["series", "relative RMS", "max difference", "note"], rows)
    return out + "<div>" + "".join(image(p) for p in plots_of(out_dir, c)) + "</div>"


def main():
    out_dir = sys.argv[1]
    doc = load(os.path.join(out_dir, "compare.json"))
    body = "".join(f"<p>{side}: <code>{esc(doc[key]['dir'])}</code>, commit <code>{esc(doc[key]['git_commit'])}</code>, "
                   f"{esc(doc[key]['compiler'])}</p>" for side, key in (("A", "run_a"), ("B", "run_b")))
    body += "".join(case_section(out_dir, c) for c in doc["cases"])
    for key in ("only_in_a", "only_in_b"):
        if doc[key]:
            body += f"<p>{esc(key)}: {esc(', '.join(doc[key]))}</p>"
    path = os.path.join(out_dir, "compare.html")
    with open(path + ".tmp", "w") as f:
        f.write(page("sandcastle compare", body))
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
