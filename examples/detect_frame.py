"""Detect a part in one depth frame held in numpy and draw the top pose on it with matplotlib.

    PYTHONPATH=build/python python3 examples/detect_frame.py MODEL.ppfm SCENE_DIR IM_ID OUT.png

The frame is read from a BOP scene folder (depth/IM_ID.png and scene_camera.json), as a camera
would hand it over: a uint16 array, the 3 x 3 camera matrix and the depth scale. The picture
shows the depth image in grey, the model's points at the top pose in colour (by their depth),
and every other detection's position as a small cross.
"""
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files, no window
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import binpick  # noqa: E402


def project(points, K):
    """Pixel coordinates (u, v) of camera-frame points (mm)."""
    uvw = points @ K.T
    return uvw[:, 0] / uvw[:, 2], uvw[:, 1] / uvw[:, 2]


def main(model_path, scene_dir, im_id, out):
    scene = Path(scene_dir)
    cam = json.loads((scene / "scene_camera.json").read_text())[str(int(im_id))]
    depth = binpick.read_depth_png(str(scene / "depth" / f"{int(im_id):06d}.png"))
    K = np.reshape(cam["cam_K"], (3, 3))
    model = binpick.Model.load(model_path)
    found = binpick.Detector(model).detect(depth, K, cam["depth_scale"])
    if not found:
        sys.exit("detect_frame.py: no detection")
    top = found[0]
    print(f"top pose: score {top.score:.3f}\nR = {top.R.tolist()}\nt = {top.t.tolist()} mm")

    fig, ax = plt.subplots(figsize=(depth.shape[1] / 100, depth.shape[0] / 100), dpi=100)
    shown = np.where(depth > 0, depth * cam["depth_scale"], np.nan)
    near = top.t[2] - model.diameter  # grey spread over the depths around the part
    ax.imshow(shown, cmap="gray", vmin=near, vmax=near + 4 * model.diameter)
    points = model.points @ top.R.T + top.t
    u, v = project(points, K)
    ax.scatter(u, v, s=2, c=points[:, 2], cmap="viridis")
    others = np.array([d.t for d in found[1:]]).reshape(-1, 3)
    if len(others):
        ax.scatter(*project(others, K), marker="x", s=30, c="tab:red")
    ax.set_title(f"top pose: score {top.score:.2f} (red: {len(others)} more detections)")
    ax.set_axis_off()
    fig.savefig(out, bbox_inches="tight")
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    try:
        main(*sys.argv[1:])
    except ValueError as e:  # binpick's InputError: one line, exit 2 as the command line
        print(f"detect_frame.py: error: {e}", file=sys.stderr)
        sys.exit(2)
