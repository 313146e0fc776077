"""Matplotlib figures of the benchmark report (PNG files, headless backend)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from inherit_sg.benchmark.report import dataset_name

GROUPS = ("A-C", "D", "E", "F", "overall")


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_accuracy(docs: list[dict[str, Any]], path: Path) -> Path:
    """Accuracy within 1 m per category group, ours vs flat, one panel per dataset."""
    plt = _pyplot()
    fig, axes = plt.subplots(1, len(docs), figsize=(3.6 * len(docs), 3.2), squeeze=False)
    width = 0.38
    for ax, doc in zip(axes[0], docs, strict=True):
        xs = range(len(GROUPS))
        for k, (system, colour) in enumerate((("ours", "tab:blue"), ("flat", "tab:gray"))):
            acc = doc["accuracy"][system]
            values = [acc[g]["within_1m"] or 0.0 for g in GROUPS]
            ax.bar([x + (k - 0.5) * width for x in xs], values, width, label=system, color=colour)
        ax.set_xticks(list(xs), GROUPS)
        ax.set_ylim(0, 100)
        ax.set_title(dataset_name(doc), fontsize=9)
        ax.set_ylabel("within 1 m (%)")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=2, fontsize=8)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return _save(fig, plt, path)


def plot_latency_scale(rows: list[dict[str, Any]], path: Path) -> Path:
    """Total latency p50 / p99 against the number of objects in the map (log x)."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(5, 3.2))
    objects = [r["objects"] for r in rows]
    for name, style in (("first pass", "-o"), ("repeat pass", "--s")):
        for stat in ("p50", "p99"):
            ys = [r[name]["total"][stat] for r in rows]
            ax.plot(objects, ys, style, label=f"{name} {stat}")
    ax.set_xscale("log")
    ax.set_xlabel("objects in the map")
    ax.set_ylabel("request latency (ms)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, plt, path)


def plot_storage(docs: list[dict[str, Any]], path: Path) -> Path:
    """Bytes per node (features, text, images) of object, room and area nodes."""
    plt = _pyplot()
    kinds = ("object", "room", "area")
    parts = (("feature_bytes", "features"), ("text_bytes", "text"), ("image_bytes", "images"))
    fig, axes = plt.subplots(1, len(docs), figsize=(3.6 * len(docs), 3.2), squeeze=False)
    for ax, doc in zip(axes[0], docs, strict=True):
        bottom = [0.0] * len(kinds)
        for key, name in parts:
            values = [doc["storage"][k].get(key, 0.0) / 1024.0 for k in kinds]
            ax.bar(kinds, values, bottom=bottom, label=name)
            bottom = [b + v for b, v in zip(bottom, values, strict=True)]
        ax.set_title(dataset_name(doc), fontsize=9)
        ax.set_ylabel("KB per node")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    return _save(fig, plt, path)


def _save(fig: Any, plt: Any, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
