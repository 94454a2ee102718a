#!/usr/bin/env python3
"""Writes RUN_DIR/report.html: a self-contained page (plots embedded as data URIs) of a
validation run, readable offline: the pass/fail table, every metric with its limit, the
comparison with the baseline, and the plots.

Usage: html_report.py RUN_DIR     (reads RUN_DIR/report.json, format: reports/README.md)
The helpers (page, table, image) are shared with compare_report.py.
"""
import base64
import html
import json
import os
import sys

STYLE = """
body { font-family: sans-serif; margin: 2em; max-width: 1200px; color: #222; }
table { border-collapse: collapse; margin: 0.5em 0 1em 0; }
th, td { border: 1px solid #ccc; padding: 3px 8px; text-align: left; font-size: 0.9em; }
th { background: #f0f0f0; }
.pass, .identical { background: #dff0d8; }
.fail, .error, .regressed { background: #f2dede; font-weight: bold; }
.changed, .missing, .not_compared { background: #fcf8e3; }
img { max-width: 48%; margin: 4px; border: 1px solid #ddd; }
img.filmstrip { max-width: 100%; }
code { font-size: 0.9em; }
"""


def esc(value):
    return html.escape(str(value))


def number(value):
    """A number as text: %.4g, n/a for null."""
    if value is None:
        return "n/a"
    if isinstance(value, float):
        return f"{value:.4g}"
    return esc(value)


def table(headers, rows):
    """rows: lists of cells; a cell is text or a (text, css class) pair."""
    out = ["<table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in headers) + "</tr>"]
    for row in rows:
        cells = []
        for cell in row:
            text, css = cell if isinstance(cell, tuple) else (cell, "")
            cells.append(f'<td class="{css}">{text}</td>' if css else f"<td>{text}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    return "\n".join(out) + "</table>"


def image(path, css=""):
    """An <img> with the PNG embedded, or a note when the file is missing."""
    if not os.path.exists(path):
        return f"<p>missing plot: <code>{esc(path)}</code></p>"
    with open(path, "rb") as f:
        data = base64.b64encode(f.read()).decode("ascii")
    cls = f' class="{css}"' if css else ""
    return f'<img{cls} alt="{esc(os.path.basename(path))}" src="data:image/png;base64,{data}">'


def page(title, body):
    return (f"<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{esc(title)}</title>"
            f"<style>{STYLE}</style></head><body>\n<h1>{esc(title)}</h1>\n{body}\n</body></html>\n")


def header(report):
    s = report["summary"]
    counts = s.get("baseline", {})
    baseline = ", ".join(f"{n} {k}" for k, n in counts.items() if n)
    return (f"<p>commit <code>{esc(report['git_commit'])}</code>, {esc(report['threads'])} threads, "
            f"{esc(report['compiler'])}, flags <code>{esc(report.get('flags', ''))}</code></p>"
            f"<p><b>{s['passed']} passed, {s['failed']} failed, {s['errors']} errors</b>"
            + (f"; baselines: {esc(baseline)}" if baseline else "") + "</p>")


def key(c):
    """A run's key: <case>, or <case>.<method> for a method other than the case's own."""
    return c.get("run_id", c["name"])


def overview(cases):
    rows = []
    for c in cases:
        b = c.get("baseline", {}).get("status", "n/a")
        rows.append([f'<a href="#{esc(key(c))}">{esc(key(c))}</a>', esc(c.get("method", "sph")), esc(c["tier"]),
                     (esc(c["status"]), c["status"]), (esc(b), b), number(c["particles"]), number(c["steps"]),
                     number(c["wall_seconds"])])
    return table(["case", "method", "tier", "physics", "baseline", "particles", "steps", "wall [s]"], rows)


def metrics_table(metrics):
    rows = [[esc(name), number(m["value"]), esc(json.dumps(m["limit"])),
             ("pass", "pass") if m["pass"] else ("FAIL", "fail")] for name, m in metrics.items()]
    return table(["metric", "value", "limit", "gate"], rows)


def yes_no(flag):
    return "yes" if flag else "no"


def verdict(item):
    return ("ok", "pass") if item.get("pass", True) else ("REGRESSED", "regressed")


def baseline_section(b):
    status = b["status"]
    out = f'<p>baseline: <span class="{status}">{esc(status)}</span>'
    if "reason" in b:
        return out + f" ({esc(b['reason'])})</p>"
    prov = b["provenance"]
    out += (f" (blessed {esc(prov['date'])} at commit <code>{esc(prov['commit'][:12])}</code>, checksum "
            f"<code>{esc(b['state_checksum'])}</code>, same build: {yes_no(b['same_build'])}, "
            f"parameters changed: {yes_no(b['parameters_changed'])})</p>")
    rows = [[esc(n), number(s.get("relative_rms")), number(s.get("max_difference")), esc(json.dumps(s.get("limit", {}))),
             esc(s.get("note", "")), verdict(s)] for n, s in b["series"].items()]
    out += table(["series", "relative RMS", "max difference", "limit", "note", "verdict"], rows)
    rows = [[esc(n), number(m["baseline"]), number(m["value"]), number(m["delta"]), number(m["relative"]),
             esc(json.dumps(m["limit"])), verdict(m)] for n, m in b["metrics"].items()]
    return out + table(["metric", "baseline", "this run", "delta", "relative", "limit", "verdict"], rows)


def baseline_overlays(run_dir, c):
    """For a case that moved from its baseline: its plots redrawn with the baseline's series
    (<case>/baseline_<file>); returns the <img> tags."""
    b = c.get("baseline", {})
    if b.get("status") not in ("changed", "regressed") or not c.get("series") or not os.path.exists(b["file"]):
        return ""
    import overlay  # matplotlib only where a case moved

    with open(b["file"]) as f:
        base = {s["name"]: s for s in json.load(f)["series"]}
    with open(os.path.join(run_dir, c["series"])) as f:
        doc = json.load(f)
    run = {s["name"]: s for s in doc["series"]}
    tags = []
    for plot in doc["plots"]:
        path = os.path.join(run_dir, key(c), "baseline_" + plot["file"])
        overlay.draw(plot, base, run, ("baseline", "this run"), path)
        tags.append(image(path))
    return "<p>against the baseline:</p><div>" + "".join(tags) + "</div>"


def filmstrip(run_dir, c):
    """The case's filmstrip (its finest run drawn by `sandcastle render`), or why it has none."""
    if "filmstrip" in c:
        return "<div>" + image(os.path.join(run_dir, c["filmstrip"]), "filmstrip") + "</div>"
    if "filmstrip_note" in c:
        return f"<p>no filmstrip: {esc(c['filmstrip_note'])}</p>"
    return ""


def case_section(run_dir, c):
    out = f'<h2 id="{esc(key(c))}">{esc(key(c))} <span class="{c["status"]}">{esc(c["status"])}</span></h2>'
    if "message" in c:
        out += f"<p><code>{esc(c['message'])}</code></p>"
    out += metrics_table(c["metrics"])
    if "baseline" in c:
        out += baseline_section(c["baseline"]) + baseline_overlays(run_dir, c)
    return (out + filmstrip(run_dir, c) + "<div>" + "".join(image(os.path.join(run_dir, p)) for p in c["plots"])
            + "</div>")


def metric_cell(run, name):
    """A metric of one form of an errata run, coloured by its gate."""
    m = run["metrics"].get(name)
    if m is None:
        return "n/a"
    return (number(m["value"]), "pass") if m["pass"] else (number(m["value"]) + " FAIL", "fail")


def errata_section(errata):
    """The errata-impact table: each erratum's printed form against the corrected one, per case
    and metric, or the step at which the printed form blew up (report.json "errata")."""
    rows = []
    for e in errata:
        head = [esc(e["equation"]), f"<code>{esc(json.dumps(e['switch']))}</code>", esc(e["printed_form"])]
        if not e["cases"]:
            rows.append(head + ["(no affected case in this run)", "", "", ""])
        for c in e["cases"]:
            corrected, printed = c["corrected"], c["printed"]
            if printed.get("blew_up_at_step") is not None:
                rows.append(head + [esc(c["case"]), "all", (esc(corrected["status"]), corrected["status"]),
                                    (f"blew up at step {printed['blew_up_at_step']}", "error")])
                continue
            if printed["status"] == "error":
                rows.append(head + [esc(c["case"]), "all", (esc(corrected["status"]), corrected["status"]),
                                    (esc(printed.get("message", "error")), "error")])
                continue
            for name in corrected["metrics"]:
                rows.append(head + [esc(c["case"]), esc(name), metric_cell(corrected, name), metric_cell(printed, name)])
    return ("<h2 id=\"errata\">Errata impact</h2><p>Each erratum's printed form (its case-file switch, "
            "docs/equations.md &sect;5) run on the cases it affects at the finest spacing of the tier, "
            "against the corrected form of the normal run.</p>"
            + table(["eq", "switch", "printed form", "case", "metric", "corrected", "printed"], rows))


def methods_section(run_dir, comparisons):
    """One case run by several methods: a row per metric, a column per method beside the gate, and
    the overlay plots of each observable by every method (report.json "methods")."""
    out = ("<h2 id=\"methods\">Methods side by side</h2><p>The same case, observer, reference and gates, "
           "run by each method that supports it.</p>")
    for c in comparisons:
        methods = c["methods"]
        rows = []
        for name, m in c["metrics"].items():
            cells = []
            for method in methods:
                value, ok = m["values"].get(method), m["pass"].get(method)
                if value is None and ok is None:
                    cells.append("n/a")
                else:
                    cells.append((number(value), "pass") if ok else (number(value) + " FAIL", "fail"))
            rows.append([esc(name), esc(json.dumps(m["limit"]))] + cells)
        heads = [f'{m} ({c["status"][m]})' for m in methods]
        out += f'<h3>{esc(c["name"])}</h3>' + table(["metric", "gate"] + heads, rows)
        out += "<div>" + "".join(image(os.path.join(run_dir, p)) for p in c["plots"]) + "</div>"
    return out


def convergence_section(run_dir, studies):
    """Convergence studies: per case, method and metric the error at each spacing, the observed
    order (least-squares slope in log-log) beside the expected one, and the log-log plots
    (report.json "convergence")."""
    rows = []
    for s in studies:
        spacings = ", ".join(number(dx) for dx in s["spacings"])
        for name, m in s["metrics"].items():
            errors = ", ".join(number(e) for e in m["errors"])
            rows.append([esc(s["case"]), esc(s["method"]), esc(name), spacings, errors,
                         number(m["observed_order"]), number(m["expected_order"])])
        for r in s["runs"]:
            if r["status"] == "error":
                rows.append([esc(s["case"]), esc(s["method"]), (f"error at dx {number(r['spacing'])}", "error"),
                             esc(r["message"]), "", "", ""])
    out = ("<h2 id=\"convergence\">Convergence</h2><p>Each case run at the spacings of its study; the observed "
           "order is the least-squares slope of log(error) against log(dx).</p>"
           + table(["case", "method", "metric", "spacings [m]", "errors", "observed order", "expected order"], rows))
    for s in studies:
        out += "<div>" + "".join(image(os.path.join(run_dir, p)) for p in s["plots"]) + "</div>"
    return out


def main():
    run_dir = sys.argv[1]
    with open(os.path.join(run_dir, "report.json")) as f:
        report = json.load(f)
    body = header(report) + overview(report["cases"])
    if report.get("methods"):
        body += methods_section(run_dir, report["methods"])
    if "errata" in report:
        body += errata_section(report["errata"])
    if "convergence" in report:
        body += convergence_section(run_dir, report["convergence"])
    body += "".join(case_section(run_dir, c) for c in report["cases"])
    path = os.path.join(run_dir, "report.html")
    with open(path + ".tmp", "w") as f:
        f.write(page("sandcastle validation", body))
    os.replace(path + ".tmp", path)


if __name__ == "__main__":
    main()
