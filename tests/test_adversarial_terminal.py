"""Issue 20, item 11 on a real terminal: the progress line is ended before the next line, and Ctrl-C typed
at the terminal (the terminal's own SIGINT, not a signal sent by the test) gives its one line on a
line of its own.

main.py runs in a pseudo-terminal (Python's pty module) that is its standard output, its standard
error and its controlling terminal, as when a person types the command. tests/test_adversarial.py
checks the same with a stand-in stream; this checks what a person sees. POSIX only: Windows has no
pty module (the progress code is the same there; its console ends lines the same way).
"""
from __future__ import annotations

import os
import re
import sys
import time
from pathlib import Path

import pytest

pty = pytest.importorskip("pty", reason="needs a POSIX pseudo-terminal (the pty module)")

ROOT = Path(__file__).resolve().parents[1]
# 2,000,000 rk4 steps: about 4.5 s on a quiet machine (4 progress lines, one a second of computing),
# 15-20 s at load 20, well under the 60 s run-cost limit. (Euler-Cromer's 2,000,000 steps take 1.3 s
# since the stepping got faster: too short for a progress line to be sure.)
LONG_RUN = ["vertical", "--headless", "--set", "dt=0.00001", "--until", "20", "--integrator", "rk4"]


def on_a_terminal(argv: list[str], ctrl_c_after: str | None = None, timeout: float = 300) -> tuple[str, int]:
    """Everything main.py writes to its terminal (with the terminal's \\r\\n), and its exit status.
    ctrl_c_after: type Ctrl-C once this text has appeared."""
    pid, master = pty.fork()
    if pid == 0:                                    # the child: main.py on the terminal
        os.chdir(ROOT)
        os.execv(sys.executable, [sys.executable, str(ROOT / "main.py"), *argv])
    text, typed, deadline = b"", False, time.monotonic() + timeout
    try:
        while time.monotonic() < deadline:
            try:
                chunk = os.read(master, 4096)
            except OSError:                          # EIO: the program has ended and closed the terminal
                break
            if not chunk:
                break
            text += chunk
            if ctrl_c_after and not typed and ctrl_c_after.encode() in text:
                os.write(master, b"\x03")            # Ctrl-C, as typed: the terminal sends SIGINT
                typed = True
        else:
            os.kill(pid, 9)
            pytest.fail(f"main.py {' '.join(argv)} did not end within {timeout} s: {text[-300:]!r}")
    finally:
        os.close(master)
    _, status = os.waitpid(pid, 0)
    return text.decode("utf-8", "replace"), os.waitstatus_to_exitcode(status)


def test_the_progress_line_is_ended_before_the_report_on_a_terminal():
    """It read `...t = 20 svertical: 2000000 steps ...`: the redrawn progress line was never ended."""
    text, status = on_a_terminal(LONG_RUN)
    assert status == 0, text[-500:]
    assert "\rrunning: " in text, text[:300]                          # redrawn in place on a terminal
    report = text.index("vertical: 2000000 steps")
    assert text[:report].endswith("\n"), repr(text[report - 80:report + 40])
    assert not re.search(r"\d s(vertical|t =)", text)


def test_ctrl_c_typed_during_the_progress_line_is_one_line_of_its_own():
    text, status = on_a_terminal(LONG_RUN, ctrl_c_after="running: ")
    assert status == 130, text[-500:]
    message = "stopped: interrupted (Ctrl-C); no file was left half-written"
    assert message in text and "Traceback" not in text, text[-500:]
    before = text[:text.index(message)]
    assert before.endswith("\n"), repr(text[-200:])                 # not glued to `... t = 4.3 s`
    assert text.rstrip().endswith(message)


def test_ctrl_c_just_after_the_first_progress_line_is_written_still_ends_it(monkeypatch):
    """Found by the test above (1 run in 5): Ctrl-C between writing the line and noting that a line
    was open left `... t = 3.31776 s^Cstopped: ...` glued. Here the interrupt comes as the first
    line is flushed, every time."""
    import physics.simulate
    from reports import headless
    from scenes import configure

    class FirstFlushInterrupted:
        def __init__(self):
            self.text = ""

        def isatty(self):
            return True

        def write(self, text):
            self.text += text

        def flush(self):
            if self.text.count("running: ") == 1 and not self.text.endswith("\n"):
                raise KeyboardInterrupt

    monkeypatch.setattr(physics.simulate, "PROGRESS_EVERY", 0.0)
    stream = FirstFlushInterrupted()
    with pytest.raises(KeyboardInterrupt):
        headless.simulate(configure("damped"), until=300.0, every_step=False, progress=stream)
    assert stream.text.startswith("\rrunning: ") and stream.text.endswith(" s\n"), repr(stream.text)
