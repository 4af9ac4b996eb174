"""The README's before/after pictures of hider.mpl.resolve: two
intersecting surfaces and a line through them, drawn by matplotlib alone
and with resolve.

Run from the repository root with the package installed:
``python crates/python/examples/pictures.py docs/images``.
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hider.mpl  # noqa: E402


def scene(ax):
    x = np.linspace(-1, 1, 40)
    X, Y = np.meshgrid(x, x)
    ax.plot_surface(X, Y, X * Y, cmap="viridis", linewidth=0.3, edgecolor="k", alpha=1)
    ax.plot_surface(X, Y, 0.5 * np.sin(3 * X) + 0.3 * Y, cmap="autumn")
    ax.plot([0, 0], [0, 0], [-1.2, 1.2], color="tab:red", linewidth=2.5)
    ax.view_init(elev=25, azim=-55)


def main(out):
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    for name, resolved in [("python-before.png", False), ("python-after.png", True)]:
        fig = plt.figure(figsize=(4, 4), dpi=90)
        ax = fig.add_subplot(projection="3d")
        scene(ax)
        ax.set_title("hider.mpl.resolve(ax)" if resolved else "matplotlib alone")
        if resolved:
            hider.mpl.resolve(ax)
        fig.savefig(out / name)
        plt.close(fig)
        print(out / name)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "docs/images")
