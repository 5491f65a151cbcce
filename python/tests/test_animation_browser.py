"""The animation page of ``noslip simulate --html`` played in a real browser: headless
Chromium (Debian's ``chromium``; CI installs it, see ``.ci/run``) loads the page written by
the CLI, runs its script in virtual time and reports the page's state.

- No console message and nothing in the page's ``#errors`` element (its script reports any
  uncaught error there).
- Frames advance: the DOM dumped after 0.5 s and after 3 s of virtual time shows a later
  frame (``#frame``) the second time.
- What is drawn changes: screenshots of two frames differ.

Without a Chromium these are skipped, saying so. And without a browser: the page of
``noslip.simulate(..., html=True)`` is the CLI's, byte for byte."""

import re
import shutil
import subprocess
from pathlib import Path

import pytest

import noslip
from conftest import run_cli

BROWSERS = ("chromium", "chromium-browser", "google-chrome")


def browser() -> str:
    """The headless browser to use, or skip the test.

    Returns
    -------
    str
        The path of the first of ``BROWSERS`` found on ``PATH``.
    """
    for name in BROWSERS:
        found = shutil.which(name)
        if found:
            return found
    pytest.skip(
        "no Chromium on PATH (apt-get install -y chromium): the page was not tested "
        "in a browser"
    )


def chromium(page: str, profile: Path, *flags: str) -> subprocess.CompletedProcess[str]:
    """Run headless Chromium on ``page`` (a ``file://`` URL) with ``flags``.

    Parameters
    ----------
    page : str
        The URL.
    profile : Path
        A fresh user-data directory (nothing read from or left in ``$HOME``).
    *flags : str
        More command-line flags (``--dump-dom``, ``--screenshot=...``).

    Returns
    -------
    subprocess.CompletedProcess[str]
        The finished process, its output captured.
    """
    command = [
        browser(),
        "--headless",
        "--no-sandbox",  # CI runs as root
        "--disable-gpu",
        "--disable-dev-shm-usage",  # containers' small /dev/shm
        "--no-first-run",
        "--enable-logging=stderr",
        "--v=0",
        f"--user-data-dir={profile}",
        *flags,
        page,
    ]
    out = subprocess.run(command, capture_output=True, text=True, timeout=180, check=False)
    assert out.returncode == 0, out.stderr
    return out


def console_lines(stderr: str) -> list[str]:
    """The page's console messages in Chromium's log (``CONSOLE(line)`` entries)."""
    return [line for line in stderr.splitlines() if "CONSOLE" in line]


@pytest.fixture(scope="module")
def page(cli: Path, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """The page of 3000 contacts of the Sinai table, written by the CLI."""
    browser()
    root = Path(__file__).resolve().parents[2]
    out = tmp_path_factory.mktemp("animation")
    html = out / "set" / "sinai.html"
    run_cli(
        cli,
        "simulate",
        str(root / "scenes" / "sinai.toml"),
        "--quiet",
        "--events",
        "3000",
        "--out",
        str(out / "set"),
        "--html",
        str(html),
    )
    return html


def frame_of(dom: str) -> int:
    """The frame the page shows, from its dumped DOM."""
    found = re.search(r'<span id="frame">(\d+)</span>', dom)
    assert found, dom[:2000]
    return int(found.group(1))


def test_page_plays_without_errors(page: Path, tmp_path: Path) -> None:
    frames = []
    for budget in (500, 3000):
        out = chromium(
            page.as_uri(),
            tmp_path / f"profile-{budget}",
            f"--virtual-time-budget={budget}",
            "--dump-dom",
        )
        assert console_lines(out.stderr) == []
        errors = re.search(r'<pre id="errors"[^>]*>(.*?)</pre>', out.stdout, re.S)
        assert errors is not None and errors.group(1) == "", out.stdout[-2000:]
        frames.append(frame_of(out.stdout))
    # 50 ms a frame: about 10 frames after 0.5 s, 60 after 3 s (fewer if the page loops).
    assert 0 < frames[0] < frames[1], frames


def test_two_frames_look_different(page: Path, tmp_path: Path) -> None:
    shots = []
    for frame in (0, 100):
        shot = tmp_path / f"frame-{frame}.png"
        out = chromium(
            f"{page.as_uri()}#frame={frame}&pause",
            tmp_path / f"profile-{frame}",
            "--window-size=1100,760",
            "--virtual-time-budget=1000",
            f"--screenshot={shot}",
        )
        assert console_lines(out.stderr) == []
        data = shot.read_bytes()
        assert data.startswith(b"\x89PNG\r\n\x1a\n")
        shots.append(data)
    assert shots[0] != shots[1]


def test_python_page_is_the_clis(cli: Path, tmp_path: Path) -> None:
    root = Path(__file__).resolve().parents[2]
    scene = root / "scenes" / "cube3d.toml"
    html = tmp_path / "set" / "cube3d.html"
    out = str(tmp_path / "set")
    run_cli(cli, "simulate", str(scene), "--events", "700", "--out", out, "--html", str(html))
    page = noslip.simulate(scene, events=700, html=True).html
    assert page is not None and page == html.read_text()
    assert noslip.simulate(scene, events=10).html is None
