"""What the commands write: only in --out (or the file given), under names made safe from
whatever a model, task or data file calls its items, and all of a command's files or none."""
import errno
import json
import os
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from kinelab._files import NAME_BYTES, Outputs, safe_name
from kinelab.cli import main
from kinelab.model import MAX_NAME
from tests.cams.test_command import CAM_TASK
from tests.synthesis.test_cli import NOTES_6_5

ROOT = Path(__file__).resolve().parents[2]
EX = ROOT / "examples"

# what a model file from elsewhere may call its model, points and links ("ABSOLUTE" is
# replaced by the absolute path of a file beside --out): the model checker takes them all
# (the longest name it takes: longer ones are refused, see the test below)
HOSTILE = ["ABSOLUTE", "../../escaped", "a/b", "a\\b", "a_b", ".", "..", "CON", "x" * MAX_NAME,
           "\u03a1"]       # Greek capital rho, which looks like P: kept as it is
# and what a file's own name may hold on this system
HOSTILE_STEMS = ["a\\b", "m\x1b[2Jx", "..x", "nul"]


SYNTH = re.compile(r"solution_\d+\.(toml|png)|positions\.png|curves\.png|summary\.json")


def task(name: str) -> str:
    """A motion task (three positions) named ``../../<name>``, in TOML."""
    return f'name = "../../{name}"\n' + NOTES_6_5


def run(*args):
    return CliRunner().invoke(main, [str(a) for a in args])


def renamed(data, names: dict):
    """``data`` (a model file's content) with every name in ``names`` replaced, as a key
    and as a value."""
    if isinstance(data, dict):
        return {names.get(k, k): renamed(v, names) for k, v in data.items()}
    if isinstance(data, list):
        return [renamed(v, names) for v in data]
    return names.get(data, data) if isinstance(data, str) else data


def example(name: str) -> dict:
    return tomllib.loads((EX / f"{name}.toml").read_text())


def snapshot(root: Path, skip: Path | None = None) -> dict:
    """Every file and directory under ``root`` (hidden ones too), with its content and mode,
    but ``skip`` and what is in it."""
    found = {}
    for here, dirs, files in os.walk(root):
        here = Path(here)
        if skip is not None and (here == skip or skip in here.parents):
            continue
        for d in dirs:
            if here / d != skip:
                found[here / d] = ("dir", (here / d).is_symlink())
        for f in files:
            p = here / f
            found[p] = ("file", p.read_bytes() if not p.is_symlink() else os.readlink(p),
                        p.lstat().st_mode)
    return found


@pytest.fixture
def sandbox(tmp_path, monkeypatch):
    """A directory whose ``work`` is the current one, with --out ``work/out``; the hostile
    names that are paths point inside it, so that a write they steer is seen there."""
    work = tmp_path / "work"
    (work / "src").mkdir(parents=True)
    monkeypatch.chdir(work)
    names = [str(tmp_path / "victim") if n == "ABSOLUTE" else n for n in HOSTILE]
    return tmp_path, work, work / "out", names


def hostile_models(src: Path, names: list[str]) -> dict[str, Path]:
    """Model files whose model, points and floating links are named ``names``."""
    models = {}
    d = example("crank_rocker")
    coupler = next(lk for lk in d["links"] if lk["name"] == "coupler")
    for i, p in enumerate(names, 1):        # coupler points beside P, each traced by plot
        d["points"][p] = [82 + 5 * i, 261]
        coupler["points"].append(p)
        coupler["local"][p] = [150 + 5 * i, 100]
    d["outputs"]["report"] = ["rocker", *names]
    for k, name in enumerate(names):
        models[f"points{k}"] = src / f"points{k}.json"
        models[f"points{k}"].write_text(json.dumps({**d, "name": name}))
    six = renamed(example("stephenson6"), {"coupler": "x/y", "link5": "x\\y", "output": "CON"})
    models["links"] = src / "links.json"
    models["links"].write_text(json.dumps({**six, "name": names[1]}))
    for k, name in enumerate(names):
        models[f"engine{k}"] = src / f"engine{k}.json"
        models[f"engine{k}"].write_text(json.dumps({**example("engine"), "name": name}))
    return models


def curve(path: Path) -> Path:
    t = np.linspace(0.0, 1.0, 41)
    rows = "\n".join(f"{a:.17g},{b:.17g}" for a, b in zip(t, np.sin(3 * t) + 0.001 * np.cos(50 * t)))
    path.write_text("t [s],../../x [mm]\n" + rows + "\n")
    return path


def commands(work: Path, out: Path, names: list[str]) -> list[tuple[list, set | re.Pattern]]:
    """Every command that writes, on files named with ``names`` (a model's own, its points',
    its links') or with a file's own name from elsewhere, and the names of the files it
    must write in ``out`` (or the pattern of its own names)."""
    src = work / "src"
    m = hostile_models(src, names)
    k = len(names) - 1
    stems = {}
    for i, s in enumerate(HOSTILE_STEMS):      # a file's own name from elsewhere
        stems[s] = src / f"{s}.json"
        stems[s].write_text(m[f"points{i}"].read_text())
    odd = {s: safe_name(s) for s in [*HOSTILE_STEMS, "m\x1bx", *names]}
    cam = src / "c\x1bam.toml"         # a file's own name, odd, names the cam's outputs
    cam.write_text(CAM_TASK)
    cam_stem = safe_name("c\x1bam")
    data = curve(src / "m\x1bx.csv")
    (src / "task.toml").write_text(task("t\\\\x"))
    pyslvs = src / "..pyslvs"
    assert run("export", EX / "crank_rocker.toml", "--to", "pyslvs", "--out",
               pyslvs).exit_code == 0
    traced = names          # the file's [outputs]
    return [
        (["analyze", m["points0"], "--samples", "5", "-q", "--verify", "--out", out],
         {"points0.csv", "points0_certificate.json"}),
        (["analyze", stems["a\\b"], "--samples", "5", "-q", "--out", out], {odd["a\\b"] + ".csv"}),
        (["plot", m["points2"], "--samples", "5", "--format", "png", "--out", out],
         {f"points2_{n}.png" for n in ["motion", "coefficients", "transmission",
                                       *(f"path_{safe_name(p)}" for p in traced)]}),
        (["animate", stems["m\x1b[2Jx"], "--samples", "5", "--frames", "2", "--format", "gif",
          "--out", out], {odd["m\x1b[2Jx"] + ".gif"}),
        *[(["export", m["points3"], "--to", to, "--out", out], {f"points3.{to}"})
          for to in ("svg", "dxf", "pyslvs", "toml", "json")],
        (["import", pyslvs, "--out", out / "imported.toml"], {"imported.toml"}),
        (["gallery", "hoeken", "--out", out], {"hoeken.toml"}),
        (["derive", stems["..x"], "--out", out], {odd["..x"] + "_derivation.md"}),
        (["polygons", stems["nul"], "--at", "30", "--out", out],
         {odd["nul"] + "_velocity_polygon.png", odd["nul"] + "_acceleration_polygon.png"}),
        (["centres", m["links"], "--at", "30", "--centrodes", "--samples", "5", "--out", out],
         {"links_centres.png", *(f"links_centrodes_{safe_name(lk)}.png" for lk in ("x/y", "x\\y"))}),
        (["differentiate", data, "--out", out],
         {odd["m\x1bx"] + "_derivatives.csv", odd["m\x1bx"] + "_derivatives.png"}),
        *[(["dynamics", m[f"engine{i}"], "--samples", "5", "--out", out]
           + ([] if i == k else ["--no-plots"]),
           {f"engine{i}_dynamics.csv"} | (set() if i != k else {     # the model file's name
               f"engine{i}_{f}.png" for f in ("efforts", "reactions", "shaking")}))
          for i, name in enumerate(names)],
        (["synth", src / "task.toml", "--out", out], SYNTH),
        (["cam", cam, "--out", out], {f"{cam_stem}_{k}" for k in (
            "svaj.png", "profile.png", "pressure.png", "curvature.png", "profile.dxf",
            "profile.svg", "svaj.csv")}),
        (["sweep", m["engine1"], "--sobol", "2", "--range", "O2.x=0:0", "--samples", "8",
          "--out", out / "study.csv"], {"study.csv"}),
        (["atlas", "build", "--grid", "--range", "ground=3:3:1", "--range", "crank=1:1:1",
          "--range", "coupler=3:3:1", "--range", "rocker=2.5:2.5:1", "--range",
          "coupler_point_along=1.5:1.5:1", "--range", "coupler_point_perpendicular=1:1:1",
          "--samples", "24",
          "--out", out / "atlas.parquet"], {"atlas.parquet"}),
    ]


WRITERS = {"analyze", "plot", "animate", "export", "import", "derive", "polygons", "centres",
           "differentiate", "dynamics", "synth", "sweep", "atlas", "gallery", "cam"}
READERS = {"check", "mobility", "types", "serve"}     # write no file (serve: see tests/web)


def test_every_command_is_classed_as_writing_files_or_not():
    assert set(main.commands) == WRITERS | READERS


@pytest.mark.filterwarnings("ignore:constrained_layout not applied")    # 200-character legends
def test_no_command_writes_outside_out_whatever_the_names_in_its_files(sandbox):
    """Absolute paths, '..', separators of either system, '.', device names, the longest
    name a model may have, escape sequences: as a model's, a point's, a link's, a task's or a
    file's own name, each gives one safe file name in --out, and nothing is written
    elsewhere."""
    root, work, out, names = sandbox
    cases = commands(work, out, names)
    assert {c[0][0] for c in cases} == WRITERS
    before = snapshot(root)
    for args, expected in cases:
        if out.exists():
            for p in out.iterdir():
                p.unlink()
        result = run(*args)
        assert result.exit_code == 0, (args[:2], result.output)
        assert snapshot(root, skip=out) == before, args[:2]
        written = {p.name for p in out.iterdir()}
        if isinstance(expected, set):
            assert written == expected, args[:2]
        else:
            assert "summary.json" in written and all(map(expected.fullmatch, written)), written
        for name in written:
            assert name == Path(name).name and name not in (".", "..") and \
                not name.startswith(".") and name.isprintable() and "\\" not in name, name
            assert len(name.encode()) <= 255
    assert not (root / "victim").exists() and not (root / "escaped").exists()


def test_a_name_longer_than_a_model_takes_is_refused_and_nothing_is_written(tmp_path):
    """A point named with 10,000 characters (its figure's legend alone would take matplotlib
    half a minute): one line naming the file and the field, nothing in --out."""
    text = (ROOT / "examples" / "crank_rocker.toml").read_text().replace(
        '"P"', '"' + "x" * 10_000 + '"').replace("P = [", '"' + "x" * 10_000 + '" = [')
    path = tmp_path / "long.toml"
    path.write_text(text)
    out = tmp_path / "out"
    result = run("polygons", path, "--at", "30", "--out", out)
    assert result.exit_code == 2
    assert result.output.startswith("kinelab: error: long.toml: ")
    assert "expected a name of at most 200 characters, got 10,000" in result.output
    assert not out.exists() or not any(out.iterdir())


@pytest.mark.parametrize("name", ["x" * 10_000, "/" * 300, "é" * 5000, "a\x00b", "\ud800\x1b",
                                  "../..", "..\\..\\x", "C:\\x", "con.csv", "COM1", "LPT9 ",
                                  "a" * 200 + "\\b"])
def test_a_name_made_safe_is_one_short_plain_file_name(name):
    s = safe_name(name)
    assert s == Path(s).name and s not in ("", ".", "..") and ".." not in s
    assert all(c.isprintable() and c not in '/\\:*?"<>|' for c in s)
    assert not s.startswith((".", " ")) and not s.endswith((".", " "))
    assert len(s.encode("utf-8")) <= NAME_BYTES
    assert s.split(".")[0].rstrip().lower() not in ("con", "com1", "lpt9")
    assert safe_name(name) == s       # the same name every time


def test_readable_names_are_kept_and_unsafe_ones_never_meet():
    for ordinary in ("crank-rocker", "engine", "slotted link (Erthal)", "Whitworth quick-return",
                     "O2", "P", "\u03a1", "coupler 1", "élan", "连杆"):
        assert safe_name(ordinary) == ordinary
    near = ["a/b", "a\\b", "a:b", "a|b", "a_b", "a\x00b", "a\x1bb", "a..b", "a/../b", "a//b"]
    assert len({safe_name(n) for n in near}) == len(near)
    assert safe_name("x" * 10_000) != safe_name("x" * 10_001)


# -- all or nothing ------------------------------------------------------------------------
def cam_task(src: Path) -> Path:
    (src / "cam.toml").write_text(CAM_TASK)
    return src / "cam.toml"


def multi_output_commands(src: Path) -> dict[str, list]:
    (src / "task.toml").write_text(task("task"))
    data = curve(src / "stroke.csv")
    return {
        "analyze": ["analyze", EX / "crank_rocker.toml", "--samples", "9", "-q", "--verify"],
        "dynamics": ["dynamics", EX / "engine.toml", "--samples", "9", "--verify"],
        "plot": ["plot", EX / "crank_rocker.toml", "--samples", "9"],
        "polygons": ["polygons", EX / "slotted_link.toml", "--at", "60", "--verify"],
        "centres": ["centres", EX / "crank_rocker.toml", "--at", "30", "--centrodes",
                    "--samples", "9"],
        "differentiate": ["differentiate", data],
        "synth": ["synth", src / "task.toml"],
        "cam": ["cam", cam_task(src)],
    }


def written_in_order(monkeypatch, args, out) -> list[str]:
    """The names a command writes, in the order it writes them."""
    names = []
    write = Outputs.write

    def spy(self, name, writer):
        path = write(self, name, writer)
        names.append(path.name)
        return path
    monkeypatch.setattr(Outputs, "write", spy)
    result = run(*args, "--out", out)
    monkeypatch.setattr(Outputs, "write", write)
    assert result.exit_code == 0, result.output
    assert sorted(names) == sorted(p.name for p in out.iterdir())
    return names


def existing_outputs(out: Path, first: str) -> dict:
    """``out`` with an older version of the first output and a file of its own."""
    out.mkdir()
    (out / first).write_bytes(b"an older version\n")
    (out / "notes.txt").write_text("mine\n")
    return snapshot(out)


@pytest.mark.parametrize("command", ["analyze", "dynamics", "plot", "polygons", "centres",
                                     "differentiate", "synth", "cam"])
def test_a_command_whose_last_output_fails_leaves_its_directory_as_it_was(command, tmp_path,
                                                                         monkeypatch):
    """A directory where the last file goes, or a disk full as it is written: exit status
    2, one line naming the file, no new file, the older version of the first untouched."""
    args = multi_output_commands(tmp_path)[command]
    names = written_in_order(monkeypatch, args, tmp_path / "first")
    assert len(names) >= 2
    last = names[-1]

    out = tmp_path / "taken"
    before = existing_outputs(out, names[0])
    (out / last).mkdir()
    before = snapshot(out)
    result = run(*args, "--out", out)
    assert result.exit_code == 2
    assert result.stderr == (f"kinelab: error: {out / last}: cannot write it: it is a directory; "
                             "choose another file or directory\n")
    assert snapshot(out) == before

    out = tmp_path / "full"
    before = existing_outputs(out, names[0])
    write = Outputs.write

    def full(self, name, writer):
        if name != last:
            return write(self, name, writer)

        def fails(path):
            Path(path).write_bytes(b"half")
            raise OSError(errno.ENOSPC, "No space left on device")
        return write(self, name, fails)
    monkeypatch.setattr(Outputs, "write", full)
    result = run(*args, "--out", out)
    assert result.exit_code == 2
    assert result.stderr == (f"kinelab: error: {out / last}: cannot write it: No space left on "
                             "device; choose another file or directory\n")
    assert snapshot(out) == before


def test_a_failed_command_removes_the_directory_it_made(tmp_path, monkeypatch):
    write = Outputs.write

    def fails(self, name, writer):
        if name.endswith("_shaking.png"):
            raise OSError(errno.EIO, "Input/output error", name)
        return write(self, name, writer)
    monkeypatch.setattr(Outputs, "write", fails)
    result = run("dynamics", EX / "engine.toml", "--samples", "9", "--out", tmp_path / "a" / "b")
    assert result.exit_code == 2 and result.stderr.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_a_symbolic_link_at_an_outputs_name_is_refused(tmp_path):
    """kinelab writes neither through a link (it could lead out of --out) nor over it."""
    outside = tmp_path / "outside.csv"
    outside.write_text("keep\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / "crank_rocker.csv").symlink_to(outside)
    result = run("analyze", EX / "crank_rocker.toml", "--samples", "5", "-q", "--out", out)
    assert result.exit_code == 2
    assert result.stderr == (f"kinelab: error: {out / 'crank_rocker.csv'}: cannot write it: it "
                             "is a symbolic link, and kinelab writes neither through one nor "
                             "over it; remove the link or choose another directory\n")
    assert outside.read_text() == "keep\n" and (out / "crank_rocker.csv").is_symlink()
    assert [p.name for p in out.iterdir()] == ["crank_rocker.csv"]


def test_names_mathtext_would_read_are_drawn_in_every_figure(tmp_path):
    """A model, points, links, joints and columns named with $ (and a backslash, a brace):
    each command's figures show them as text (mathtext failed on them)."""
    names = {"crank-rocker": "$m$", "P": "a$b", "coupler": "$x$", "B": "\\frac{",
             "crank angle": "$\\alpha{$"}
    (tmp_path / "crank_rocker.json").write_text(json.dumps(renamed(example("crank_rocker"), names)))
    names = {"engine": "$m$", "rod": "$x$", "jB": "$j$", "crank angle": "$\\alpha{$"}
    (tmp_path / "engine.json").write_text(json.dumps(renamed(example("engine"), names)))
    data = curve(tmp_path / "c.csv")
    data.write_text(data.read_text().replace("../../x [mm]", "$x$ [mm]"))
    for args in (["plot", "crank_rocker.json", "--samples", "7"],
                 ["polygons", "crank_rocker.json", "--at", "30"],
                 ["centres", "crank_rocker.json", "--at", "30", "--centrodes", "--samples", "7"],
                 ["animate", "crank_rocker.json", "--samples", "5", "--frames", "2", "--format",
                  "gif"],
                 ["dynamics", "engine.json", "--samples", "7"],
                 ["differentiate", "c.csv"]):
        result = run(*args[:1], tmp_path / args[1], *args[2:], "--out", tmp_path / "out")
        assert result.exit_code == 0, (args, result.output)
