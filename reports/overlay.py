"""Overlay plots of two runs of a case (shared by compare_report.py and html_report.py).

draw(plot, series_a, series_b, labels, path): redraws one plot description of series.json
(format: reports/README.md) with both runs' series; a series equal in both (the reference, or an
unchanged observable) is drawn once, one that differs is drawn for A (solid) and B (dashed).
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def _curve(ax, s, style, label, dashed):
    if style == "markers":
        ax.plot(s["x"], s["y"], "s" if dashed else "o", ms=5, mfc="none", label=label)
    else:
        ax.plot(s["x"], s["y"], "--" if dashed else "-", lw=1.6, label=label)


def draw(plot, series_a, series_b, labels, path):
    """labels: the names of run A and run B in the legend."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4), dpi=110)
    for curve in plot["curves"]:
        a, b = series_a.get(curve["series"]), series_b.get(curve["series"])
        same = a is not None and b is not None and a["x"] == b["x"] and a["y"] == b["y"]
        if a is not None:
            _curve(ax, a, curve["style"], curve["label"] if same else f"{labels[0]}: {curve['label']}", False)
        if b is not None and not same:
            _curve(ax, b, curve["style"], f"{labels[1]}: {curve['label']}", True)
    ax.set_title(plot["title"], fontsize=10)
    ax.set_xlabel(plot["x_label"])
    ax.set_ylabel(plot["y_label"])
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
