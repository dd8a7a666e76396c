#!/usr/bin/env python3
"""Registers binpick datasets with a copy of the BOP toolkit (github.com/thodan/bop_toolkit), the
one change its scripts need before they read a dataset they do not know by name.

  tools/bop_toolkit_register.py TOOLKIT_COPY NAME[,NAME...] --scenes N --size W,H [--obj-ids 1]
                                [--delta 15]

Edits, in TOOLKIT_COPY (a copy: the edits are not undone):
  bop_toolkit_lib/dataset_params.py  the objects of each NAME ("bop19" and "ad" lists) and its
                                     split parameters (test scenes 0..N-1, image size W x H);
  scripts/eval_bop19_pose.py         VSD's delta for each NAME (mm; 15 as binpick's eval);
  scripts/calc_gt_info.py            written as calc_gt_info_NAME.py with the dataset NAME and
                                     no sensor or modality (the script takes no arguments).

Exits 1 with a message if the toolkit's files do not have the lines this script edits (another
version of the toolkit): say which, rather than run the toolkit on a half-registered dataset.
"""
import argparse
import os
import re
import sys


def edit(path, pattern, replacement, what):
    with open(path) as f:
        text = f.read()
    new, n = re.subn(pattern, replacement, text, count=1, flags=re.S)
    if n != 1:
        sys.exit("bop_toolkit_register: %s: no %s to edit (another toolkit version?)" % (path, what))
    with open(path, "w") as f:
        f.write(new)
    return new


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("toolkit")
    ap.add_argument("names")
    ap.add_argument("--scenes", type=int, required=True)
    ap.add_argument("--size", required=True, help="W,H")
    ap.add_argument("--obj-ids", default="1")
    ap.add_argument("--delta", type=float, default=15.0)
    a = ap.parse_args()
    names = a.names.split(",")
    width, height = (int(v) for v in a.size.split(","))
    obj_ids = [int(v) for v in a.obj_ids.split(",")]
    params = os.path.join(a.toolkit, "bop_toolkit_lib", "dataset_params.py")
    quoted = ", ".join('"%s"' % n for n in names)

    # Objects: the first dict of obj_ids per dataset ("bop19") lists every object, the second
    # (used by the "ad" error only) none. Both end with the "xyzibd" entry in the toolkit
    # versions of 2024-2025.
    with open(params) as f:
        text = f.read()
    ends = list(re.finditer(r'"xyzibd": \[[^\]]*\],?(?=\s*\})', text))
    if len(ends) < 2:
        sys.exit("bop_toolkit_register: %s: no two obj_ids lists ending with xyzibd "
                 "(another toolkit version?)" % params)
    for m, ids in reversed(list(zip(ends[:2], [obj_ids, []]))):
        entry = m.group(0).rstrip(",") + "," + "".join('\n        "%s": %s,' % (n, ids) for n in names)
        text = text[:m.start()] + entry + text[m.end():]
    with open(params, "w") as f:
        f.write(text)
    split = (
        "\n    # binpick datasets (tools/bop_toolkit_register.py)."
        "\n    elif dataset_name in [%s]:"
        '\n        p["scene_ids"] = {"test": list(range(%d))}[split]'
        '\n        p["im_size"] = (%d, %d)'
        '\n        if split == "test":'
        '\n            p["depth_range"] = None'
        '\n            p["azimuth_range"] = None'
        '\n            p["elev_range"] = None'
        "\n\n    else:\n        raise ValueError(\"Unknown BOP dataset"
    ) % (quoted, a.scenes, width, height)
    edit(params, r'\n    else:\n        raise ValueError\("Unknown BOP dataset', split.replace("\\", r"\\"),
         "'Unknown BOP dataset' branch")

    deltas = "".join('\n                "%s": %g,' % (n, a.delta) for n in names)
    edit(os.path.join(a.toolkit, "scripts", "eval_bop19_pose.py"), r'("hope": 15,)',
         r"\1" + deltas, "vsd_deltas entry for hope")

    calc = os.path.join(a.toolkit, "scripts", "calc_gt_info.py")
    with open(calc) as f:
        source = f.read()
    for n in names:
        out, k = re.subn(r'"dataset": "[^"]*",', '"dataset": "%s",' % n, source, count=1)
        # Older versions have no sensor or modality parameter: nothing to change there.
        out = re.sub(r'"modality": "[^"]*",', '"modality": None,', out, count=1)
        out = re.sub(r'"sensor": "[^"]*",', '"sensor": None,', out, count=1)
        if k != 1:
            sys.exit("bop_toolkit_register: %s: no \"dataset\" parameter" % calc)
        with open(os.path.join(a.toolkit, "scripts", "calc_gt_info_%s.py" % n), "w") as f:
            f.write(out)


if __name__ == "__main__":
    main()
