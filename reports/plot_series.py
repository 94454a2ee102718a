#!/usr/bin/env python3
"""Draws the PNG plots of a validation run.

Usage: plot_series.py RUN_DIR
Reads RUN_DIR/report.json, and for every case its series.json (format: reports/README.md) and
for every side-by-side comparison of methods its methods.json and for every convergence study its
series.json, and writes each plot they describe next to them. Uses matplotlib (Debian: python3-matplotlib).
"""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def draw(case_dir, doc):
    series = {s["name"]: s for s in doc["series"]}
    for plot in doc["plots"]:
        fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=110)
        for curve in plot["curves"]:
            s = series.get(curve["series"])
            if s is None:
                continue
            if curve["style"] == "markers":
                ax.plot(s["x"], s["y"], "o", ms=5, mfc="none", label=curve["label"])
            else:
                ax.plot(s["x"], s["y"], "-", lw=1.6, label=curve["label"])
        if plot.get("log_log"):
            ax.set_xscale("log")
            ax.set_yscale("log")
        ax.set_title(plot["title"], fontsize=10)
        ax.set_xlabel(plot["x_label"])
        ax.set_ylabel(plot["y_label"])
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(case_dir, plot["file"]))
        plt.close(fig)


def main():
    run_dir = sys.argv[1]
    with open(os.path.join(run_dir, "report.json")) as f:
        report = json.load(f)
    for case in report["cases"] + report.get("methods", []) + report.get("convergence", []):
        if not case.get("series"):
            continue
        path = os.path.join(run_dir, case["series"])
        if not os.path.exists(path):
            continue
        with open(path) as f:
            draw(os.path.dirname(path), json.load(f))


if __name__ == "__main__":
    main()
