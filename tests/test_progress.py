"""Progress (issue 34): a tqdm bar on standard error only when it is a
terminal (a pseudo-terminal here), never ``\\r`` lines in a log file;
``--quiet`` and ``progress=False`` silence it; a progress function gets the
run's simulated time."""
import fcntl
import io
import os
import pty
import struct
import sys
import termios
import threading
import time

import pytest

import acausal2d
from acausal2d import RunOptions, progress
from acausal2d.cli import main
from conftest import MODELS, assert_copied, same_time

PENDULUM = os.path.join(MODELS, "pendulum.py")
RUN = ["--stop-time", "1", "--intervals", "20"]


class Terminal:
    """``sys.stderr`` replaced by the slave side of a pseudo-terminal; what
    is written there is read from the master side by a thread (so that a
    full pty buffer never blocks the writer)."""

    def __init__(self):
        self.master, slave = pty.openpty()
        # a terminal of 100 x 24 characters (a new pty has 0 x 0, where tqdm draws nothing)
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))
        self.stream = io.TextIOWrapper(os.fdopen(slave, "wb", buffering=0), encoding="utf-8",
                                       write_through=True)
        self.chunks = []
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        while True:
            try:
                data = os.read(self.master, 4096)
            except OSError:             # the slave side closed
                return
            if not data:
                return
            self.chunks.append(data)

    def text(self):
        """What was written; the slave side is closed once the reader has
        drained it (Linux drops unread pty data when the slave closes)."""
        count = -1
        while count != len(self.chunks):
            count = len(self.chunks)
            time.sleep(0.3)
        self.stream.close()
        self.reader.join(timeout=10)
        os.close(self.master)
        return b"".join(self.chunks).decode("utf-8", "replace")


@pytest.fixture
def no_delay(monkeypatch):
    """The bar from the first update (a short run would otherwise show none)."""
    monkeypatch.setattr(progress, "DELAY", 0.0)


@pytest.fixture
def terminal(monkeypatch):
    """A Terminal; ``terminal.attach()`` makes it ``sys.stderr`` (in the
    test's body: pytest sets its own ``sys.stderr`` again after the setup)."""
    term = Terminal()
    assert term.stream.isatty()
    term.attach = lambda: monkeypatch.setattr(sys, "stderr", term.stream)
    return term


def test_the_bar_is_drawn_on_a_terminal(no_delay, terminal, tmp_path):
    terminal.attach()
    assert main(["simulate", PENDULUM, "--out", str(tmp_path)] + RUN) == 0
    text = terminal.text()
    assert "t = " in text and "/ 1 s" in text and "\r" in text
    assert text.split("\r")[-2].strip() == "" and text.endswith("\r")  # erased at the end


def test_quiet_silences_the_bar(no_delay, terminal, tmp_path):
    terminal.attach()
    assert main(["simulate", PENDULUM, "--out", str(tmp_path), "--quiet"] + RUN) == 0
    assert "t = " not in terminal.text()


def test_progress_false_silences_the_api(no_delay, terminal):
    terminal.attach()
    acausal2d.simulate(PENDULUM, options=RunOptions(stop_time=0.5, intervals=10,
                                                     progress=False))
    acausal2d.simulate(PENDULUM, stop_time=0.5, intervals=10, progress=False)
    assert "t = " not in terminal.text()


def test_no_bar_when_stderr_is_not_a_terminal(no_delay, tmp_path, capfd):
    assert main(["simulate", PENDULUM, "--out", str(tmp_path)] + RUN) == 0
    err = capfd.readouterr().err
    assert "\r" not in err and "t = " not in err and "%|" not in err


def test_the_sweep_counts_its_points_on_a_terminal(no_delay, terminal):
    terminal.attach()
    table = acausal2d.sweep(PENDULUM, vary={"body.m": [1.0, 2.0]}, outputs=["revolute.phi"],
                            stop_time=0.2, scheduler="serial")
    assert len(table.rows) == 2 and not table.failed
    text = terminal.text()
    assert "0/2 [" in text and "points/s" in text
    assert "t = " not in text                      # its points draw no bars of their own


def test_a_progress_function_follows_simulated_time():
    seen = []
    acausal2d.simulate(PENDULUM, stop_time=0.5, intervals=10,
                       progress=lambda t, t_end: seen.append((t, t_end)))
    times = [t for t, _ in seen]
    assert seen
    assert_copied([t_end for _, t_end in seen], [0.5] * len(seen))    # the stop time handed on
    assert times == sorted(times) and same_time(times[-1], 0.5)
