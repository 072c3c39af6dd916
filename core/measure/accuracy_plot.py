"""Draws `rtiow accuracy`'s figures: error against time (log-log, one line per choice),
RMSE against spp with the fitted slopes, and the depth limit's bias against its time."""
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def xy(rows, x, y):
    return [r[x] for r in rows], [r[y] for r in rows]


def plot_error_against_time(ax1, r):
    for sampler, marker in zip(r["spp"], "os^"):
        ax1.plot(*xy(r["spp"][sampler], "seconds", "rel_mse"), marker + "-",
                 label="%s (spp 1..%d)" % (sampler, r["max_spp"]))
    for sampler, marker in zip(r["budget"], "os^"):
        ax1.plot(*xy(r["budget"][sampler], "seconds", "rel_mse"), marker + "--", mfc="none",
                 label="%s --adaptive (budget 32..%d)" % (sampler, r["max_spp"]))
    ax1.plot(*xy(r["image_error"], "seconds", "rel_mse"), "v-",
             label="%s --image-error" % r["image_error_sampler"])
    ax1.plot(*xy(r["adaptive"], "seconds", "rel_mse"), "<-", label="--target-error")
    ax1.plot(*xy(r["denoised"], "seconds", "rel_mse"), "*-", ms=8,
             label="%s --denoise (spp 2..%d, denoiser's time included)"
             % (r["denoised_sampler"], r["max_spp"]))
    for row in r["adaptive"]:
        ax1.annotate("%g" % row["parameter"], (row["seconds"], row["rel_mse"]),
                     textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax1.plot(*xy(r["depth_sweep"], "seconds", "rel_mse"), "d:", color="gray",
             label="depth limit 1..%d at %d spp" % (r["depth"], r["fixed_spp"]))
    for row in r["fresnel"]:
        ax1.plot([row["seconds"]], [row["rel_mse"]], "P", ms=9,
                 label="fresnel %s, %d spp" % (row["choice"], row["parameter"]))
    for row in r["intersector"]:
        ax1.plot([row["seconds"]], [row["rel_mse"]], "x" if row["choice"] == "naive" else "+",
                 ms=10, label="%s, %d spp" % (row["choice"], row["parameter"]))
    ax1.set_xscale("log")
    ax1.set_yscale("log")
    ax1.set_xlabel("render time (s)")
    ax1.set_ylabel("relMSE against the reference")
    ax1.set_title("error against time")
    ax1.grid(True, which="both", alpha=0.3)
    ax1.legend(fontsize=7)


def plot_convergence(ax2, r):
    s = r["summary"]
    for sampler, marker in zip(r["spp"], "os^"):
        ax2.plot(*xy(r["spp"][sampler], "parameter", "rmse"), marker + "-",
                 label="%s, slope %.3f" % (sampler, s["rmse_slope"][sampler]))
    first = r["spp"]["independent"][0]
    spp = [row["parameter"] for row in r["spp"]["independent"]]
    ax2.plot(spp, [first["rmse"] * (n / first["parameter"]) ** -0.5 for n in spp], "k--",
             alpha=0.4, label="slope -0.5")
    ax2.set_xscale("log", base=2)
    ax2.set_yscale("log")
    ax2.set_xlabel("samples per pixel")
    ax2.set_ylabel("RMSE")
    ax2.set_title("convergence")
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)


def plot_depth_limit(ax3, r):
    # Bias against time for the depth limit: values at or below the noise floor are drawn
    # on it (the floor is the difference's standard error, so they are indistinguishable).
    rows = r["depth_sweep"]
    full = max(rows, key=lambda row: row["parameter"])["seconds"]
    floor = min(row["mean_difference_error"] for row in rows)
    rel_time = [row["seconds"] / full for row in rows]
    lost = [max(-row["mean_difference"], floor) for row in rows]
    rms_bias = [max(row["rms_bias"], floor) for row in rows]
    ax3.plot(rel_time, lost, "o-", label="energy lost: -(mean difference)")
    ax3.plot(rel_time, rms_bias, "s--", label="RMS bias per pixel")
    ax3.plot(rel_time, [row["mean_difference_error"] for row in rows], ":", color="gray",
             label="standard error of the mean difference")
    for x, y, row in zip(rel_time, lost, rows):
        ax3.annotate("%d" % row["parameter"], (x, y), textcoords="offset points",
                     xytext=(4, 4), fontsize=7)
    ax3.set_yscale("log")
    ax3.set_xlabel("render time relative to depth %d" % r["depth"])
    ax3.set_ylabel("bias (relative to the image sum / per pixel)")
    ax3.set_title("depth limit at %d spp (labels: depth)" % r["fixed_spp"])
    ax3.grid(True, which="both", alpha=0.3)
    ax3.legend(fontsize=8)


def main(figures, png):
    r = json.load(figures)
    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(16, 5))
    plot_error_against_time(ax1, r)
    plot_convergence(ax2, r)
    plot_depth_limit(ax3, r)
    fig.suptitle("rtiow accuracy: %s %dx%d, reference %d spp" %
                 (r["scene"], r["width"], r["height"], r["reference_spp"]))
    fig.tight_layout()
    fig.savefig(png, format="png", dpi=80)


if __name__ == "__main__":
    # rtiow hands the figures on stdin and takes the PNG on stdout (no path crosses over);
    # anything a library prints goes to stderr, not into the image.
    png = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)
    main(sys.stdin, png)
    png.close()
