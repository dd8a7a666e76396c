"""The batch verbs from Python (python/module/bind_commands.cpp): the command line's verbs with
its options by keyword, its outputs byte for byte, its messages, and progress to a callback."""
import json
from pathlib import Path

import pytest

import binpick
from conftest import run


class Recorder:
    """A progress callback that keeps every call."""

    def __init__(self):
        self.calls = []

    def __call__(self, label, done, total, status):
        assert isinstance(status, str) and 0 <= done <= total
        self.calls.append((label, done, total))


def files(root):
    return {p.relative_to(root): p.read_bytes() for p in sorted(Path(root).rglob("*"))
            if p.is_file() and p.suffix in (".png", ".ply") or p.name.startswith("scene_")}


def test_synth_from_python_writes_the_command_lines_bins(bins, tmp_path):
    progress = Recorder()
    binpick.synth(model="builtin:bracket", out=tmp_path / "data", bins=2, objects=35, width=640,
                  height=360, progress=progress)
    ours, theirs = files(tmp_path / "data" / "test"), files(bins / "data" / "test")
    assert len(ours) >= 2 * 4 and ours == theirs
    # Each bin's waves, then its summary with all of it done.
    assert {label for label, _, _ in progress.calls} == {"bin 1/2", "bin 2/2"}
    assert progress.calls[-1][1] == progress.calls[-1][2]


def test_detect_and_eval_from_python_write_the_command_lines_files(bins, tmp_path):
    progress = Recorder()
    binpick.detect(model=bins / "bracket.ppfm", dataset=bins / "data", out=tmp_path / "two.csv",
                   hypotheses=2, more_hypotheses=0, progress=progress)

    def without_time(path):
        return [line.rsplit(",", 1)[0] for line in Path(path).read_text().splitlines()]

    assert without_time(tmp_path / "two.csv") == without_time(bins / "two.csv")
    assert progress.calls[-1] == ("detect", 2, 2)
    binpick.eval(dataset=bins / "data", results=bins / "two.csv", out=tmp_path / "py_eval",
                 pictures=0, no_vsd=True)
    run("eval", "--dataset", bins / "data", "--results", bins / "two.csv", "--out",
        tmp_path / "cli_eval", "--pictures", "0", "--no-vsd")
    assert ((tmp_path / "py_eval" / "curves.csv").read_bytes() ==
            (tmp_path / "cli_eval" / "curves.csv").read_bytes())
    report = json.loads((tmp_path / "py_eval" / "report.json").read_text())
    assert report  # what eval writes, from Python as from the shell
    binpick.command_line(["eval", "--dataset", str(bins / "data"), "--results",
                          str(bins / "two.csv"), "--out", str(tmp_path / "line_eval"),
                          "--pictures", "0", "--no-vsd"])
    assert ((tmp_path / "line_eval" / "curves.csv").read_bytes() ==
            (tmp_path / "cli_eval" / "curves.csv").read_bytes())


def test_bad_options_raise_the_command_lines_message(bins, tmp_path):
    cases = [
        (dict(model="builtin:bracket", out=tmp_path / "a", nope=1), "binpick synth has no option --nope"),
        (dict(model="builtin:bracket", out=tmp_path / "a", bins="many"), "--bins"),
        (dict(model="builtin:bracket"), "--out is required"),
        (dict(model="builtin:nothing", out=tmp_path / "a"), "unknown built-in part 'nothing'"),
        (dict(model="builtin:bracket", out=tmp_path / "a", masks=3), "a flag, True or False"),
    ]
    for options, message in cases:
        with pytest.raises(ValueError, match=message):
            binpick.synth(**options)
    with pytest.raises(ValueError, match="no_such.ppfm"):
        binpick.detect(model=tmp_path / "no_such.ppfm", dataset=bins / "data", out=tmp_path / "r.csv")
    with pytest.raises(ValueError, match="has no verb 'bake'"):
        binpick.command("bake")
    assert not (tmp_path / "r.csv").exists()


def test_an_exception_in_the_callback_stops_the_verb_and_a_rerun_finishes_it(bins, tmp_path):
    class Stop(Exception):
        pass

    def stop_at_second_bin(label, done, total, status):
        if label == "bin 2/2":
            raise Stop

    options = dict(model="builtin:bracket", out=tmp_path / "data", bins=2, objects=35,
                   width=640, height=360)
    with pytest.raises(Stop):
        binpick.synth(progress=stop_at_second_bin, **options)
    assert not (tmp_path / "data" / "test" / "000001" / "scene_gt.json").exists()
    progress = Recorder()
    binpick.synth(progress=progress, **options)  # resumes: the first bin is not made again
    assert {label for label, _, _ in progress.calls} == {"bin 2/2"}
    assert files(tmp_path / "data" / "test") == files(bins / "data" / "test")
