"""Our filters in the real MeshLab 2025.07 desktop application, driven under Xvfb.

scripts/test builds the application once (scripts/meshlab --build-only, cached in
~/.cache/meshregrid or $MESHREGRID_CACHE_DIR). Set MESHREGRID_SKIP_GUI=1 where no display server can be installed.
A screenshot of the Filters menu is kept in test-artifacts/.
"""
import os
import pathlib
import re
import select
import shutil
import subprocess
import time

import pymeshlab
import pytest

import meshregrid
from conftest import REPO, shared_mesh

LISTER = pathlib.Path(meshregrid.plugin_dir()).parent / "tests" / "gui" / "list_meshlab_filters"
ARTIFACTS = REPO / "test-artifacts"

pytestmark = pytest.mark.skipif(os.environ.get("MESHREGRID_SKIP_GUI") == "1", reason="MESHREGRID_SKIP_GUI=1")


def wait_for(predicate, timeout=30.0, what="condition"):
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        value = predicate()
        if value:
            return value
        time.sleep(0.2)
    raise AssertionError(f"timed out after {timeout}s waiting for {what}")


class MeshLabWindow:
    """A running MeshLab under its own Xvfb display, driven with xdotool."""

    def __init__(self, env, log_path):
        self.env = env
        self.log_path = log_path

    def xdo(self, *args):
        return subprocess.run(["xdotool", *map(str, args)], env=self.env, capture_output=True, text=True,
                              timeout=30).stdout.strip()

    def visible_window(self, name):
        ids = self.xdo("search", "--onlyvisible", "--name", re.escape(name)).split()
        return ids[0] if ids else None

    def geometry(self, window):
        out = self.xdo("getwindowgeometry", "--shell", window)
        values = dict(line.split("=") for line in out.splitlines() if "=" in line)
        return int(values["X"]), int(values["Y"]), int(values["WIDTH"]), int(values["HEIGHT"])

    def click(self, x, y):
        self.xdo("mousemove", x, y, "click", "1")

    def log(self):
        return self.log_path.read_text(errors="replace")

    def screenshot(self, path):
        subprocess.run(["import", "-window", "root", str(path)], env=self.env, check=True, timeout=30)

    def main_window(self):
        return wait_for(lambda: self.visible_window("MeshLab 2025.07d"), 60, "the MeshLab main window")

    def open_filter_by_search(self, menu_name, attempts=3):
        """Types the filter's name into MeshLab's action search and opens its dialog."""
        for attempt in range(attempts):
            x, y, w, _ = self.geometry(self.main_window())
            self.click(x + w - 22, y + 46)  # the search button at the right end of the toolbar
            time.sleep(0.5 + attempt)
            self.xdo("type", "--delay", "30", menu_name)
            time.sleep(0.5 + attempt)
            self.xdo("key", "Down", "Return")
            try:
                return wait_for(lambda: self.visible_window(menu_name), 10, f"the dialog of {menu_name!r}")
            except AssertionError:
                self.xdo("key", "Escape", "Escape")  # close a search menu left open, then retry
        raise AssertionError(f"MeshLab's search did not open {menu_name!r} in {attempts} attempts")

    def press_dialog_button(self, dialog, which):
        x, y, w, h = self.geometry(dialog)
        self.click(x + (3 * w // 4 if which == "Apply" else w // 4), y + h - 23)


def start_xvfb(log_path, timeout=60.0):
    """Starts Xvfb on a free display; returns (process, display number) once it accepts clients.

    Xvfb's -displayfd writes the number only when the server is ready. Waiting for its socket
    file instead let MeshLab start too early on a fresh machine ("could not connect to display")."""
    read_end, write_end = os.pipe()
    with open(log_path, "w") as log:
        xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0", "1400x900x24", "-nolisten",
                                 "tcp"], pass_fds=(write_end,), stdout=log, stderr=subprocess.STDOUT)
    os.close(write_end)
    answer = b""
    end = time.monotonic() + timeout
    with os.fdopen(read_end, "rb", buffering=0) as pipe:
        while not answer.endswith(b"\n") and time.monotonic() < end:
            if not select.select([pipe], [], [], 0.5)[0]:
                continue
            chunk = pipe.read(16)
            if not chunk:
                break  # Xvfb exited
            answer += chunk
    if not answer.strip().isdigit():
        xvfb.kill()
        xvfb.wait(timeout=30)
        pytest.fail(f"Xvfb did not start:\n{pathlib.Path(log_path).read_text(errors='replace')[-2000:]}")
    return xvfb, int(answer)


@pytest.fixture(scope="module")
def meshlab(tmp_path_factory):
    for tool in ("Xvfb", "xdotool", "import"):
        if not shutil.which(tool):
            pytest.fail(f"{tool} missing: run scripts/meshlab --build-only (or set MESHREGRID_SKIP_GUI=1)")
    # Returns at once when the cached build exists (scripts/test built it before pytest).
    built = subprocess.run([str(REPO / "scripts" / "meshlab"), "--build-only"], capture_output=True, text=True,
                           timeout=3600)
    if built.returncode != 0:
        pytest.fail(f"the MeshLab GUI could not be built:\n{built.stderr[-3000:]}")
    gui_exe = pathlib.Path(built.stdout.strip().splitlines()[-1])
    home = tmp_path_factory.mktemp("meshlab-home")
    plugins = home / "data" / "VCG" / "MeshLab_64bit_dp" / "MeshLabExtraPlugins" / "2025.07d"
    plugins.mkdir(parents=True)
    for so in pathlib.Path(meshregrid.plugin_dir()).glob("libfilter_meshregrid_*.so"):
        shutil.copy(so, plugins)
    (home / "config" / "VCG").mkdir(parents=True)
    # the first start asks about statistics unless this says the question was answered
    (home / "config" / "VCG" / "MeshLab_64bit_dp.conf").write_text("[General]\ninformativeShown=true\n")
    xvfb, display = start_xvfb(home / "xvfb.log")
    env = {**os.environ, "DISPLAY": f":{display}", "XDG_DATA_HOME": str(home / "data"),
           "XDG_CONFIG_HOME": str(home / "config"), "HOME": str(home)}
    env.pop("QT_QPA_PLATFORM", None)
    log_path = home / "meshlab.log"
    with open(log_path, "w") as log:
        app = subprocess.Popen([str(gui_exe), str(shared_mesh("cad/part.off"))], env=env, stdout=log,
                               stderr=subprocess.STDOUT)
    window = MeshLabWindow(env, log_path)
    try:
        window.main_window()
        wait_for(lambda: "All files opened" in window.log(), 60, "the mesh to load")
        yield window
    finally:
        app.kill()
        app.wait(timeout=30)
        xvfb.terminate()  # (not killed: it then removes its lock and socket)
        try:
            xvfb.wait(timeout=30)
        except subprocess.TimeoutExpired:
            xvfb.kill()
            xvfb.wait(timeout=30)


def menu_names():
    out = subprocess.run([str(LISTER), str(meshregrid.plugin_dir())], capture_output=True, text=True,
                         timeout=120, check=True).stdout
    return {row.split("\t")[1]: row.split("\t")[2] for row in out.splitlines()}


def test_filters_menu_screenshot_shows_our_selection_filter(meshlab):
    x, y, _, _ = meshlab.geometry(meshlab.main_window())
    meshlab.click(x + 120, y + 10)  # Filters
    time.sleep(0.5)
    meshlab.xdo("key", "Down", "Down", "Right")  # Selection submenu
    time.sleep(1.0)
    ARTIFACTS.mkdir(exist_ok=True)
    shot = ARTIFACTS / "meshlab_filters_menu.png"
    meshlab.screenshot(shot)
    meshlab.xdo("key", "Escape", "Escape", "Escape")
    assert shot.stat().st_size > 10_000


def test_every_filter_of_ours_is_found_by_the_running_application(meshlab):
    names = menu_names()
    assert "compute_feature_lines_and_patches" in names
    for python_name in meshregrid.available_filters():
        dialog = meshlab.open_filter_by_search(names[python_name])
        meshlab.press_dialog_button(dialog, "Close")
        wait_for(lambda: not meshlab.visible_window(names[python_name]), 20, "the dialog to close")


def test_apply_feature_lines_through_the_gui_matches_pymeshlab(meshlab):
    name = menu_names()["compute_feature_lines_and_patches"]
    dialog = meshlab.open_filter_by_search(name)
    meshlab.press_dialog_button(dialog, "Apply")
    line = wait_for(lambda: re.search(r"Feature lines: (\d+) ridge edges, (\d+) corners, (\d+) lines, (\d+) patches",
                                      meshlab.log()), 30, "the filter's log line")
    ARTIFACTS.mkdir(exist_ok=True)
    meshlab.screenshot(ARTIFACTS / "meshlab_feature_lines_applied.png")
    meshlab.press_dialog_button(dialog, "Close")
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(shared_mesh("cad/part.off")))
    r = ms.compute_feature_lines_and_patches()
    assert tuple(map(int, line.groups())) == (r["ridge_edges"], r["corners"], r["lines"], r["patches"])
