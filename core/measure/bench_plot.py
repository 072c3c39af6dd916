"""Draws the `rtiow bench` scaling series: Mrays/s against the sphere count, log-log."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(figures, png):
    results = json.load(figures)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for accel, style in (("embree", "o-"), ("naive", "s--")):
        points = [p[accel] for p in results["scaling"] if accel in p]
        ax.plot([p["spheres"] for p in points], [p["mrays_per_second"] for p in points], style,
                label=accel)
    cover = results["cover"]
    for accel, marker in (("embree", "o"), ("naive", "s")):
        ax.plot([cover["spheres"]], [cover[accel]["mrays_per_second"]], marker, mfc="none",
                ms=12, color="gray")
    ax.annotate("cover scene", (cover["spheres"], cover["embree"]["mrays_per_second"]),
                textcoords="offset points", xytext=(8, 8), color="gray")
    s = results["scaling_settings"]
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("spheres in the scene")
    ax.set_ylabel("Mrays/s (whole renderer)")
    ax.set_title(f"rtiow: Embree vs naive, {s['width']}x{s['height']}, {s['spp']} spp, "
                 f"depth {s['depth']}, {results['threads']} threads")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(png, format="png", dpi=90)


if __name__ == "__main__":
    # rtiow hands the figures on stdin and takes the PNG on stdout (no path crosses over);
    # anything a library prints goes to stderr, not into the image.
    png = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    main(sys.stdin, png)
    png.close()
