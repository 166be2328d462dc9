"""browser.loopback_server: vpython's servers on 127.0.0.1 only, no file leaks, clean exits.

Each test runs a small driver program in a subprocess (start() blocks until a browser connects,
and vpython's servers live for the whole process), with its working directory holding a
secret.png and a decoy glow.min.js, and another secret.png one folder up.
"""

from __future__ import annotations

import base64
import os
import queue
import re
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from browser_support import CHROMIUM, ENDS_WITHIN, PATIENCE

ROOT = Path(__file__).resolve().parents[1]

DRIVER = """
import sys, time
from browser import loopback_server
info = loopback_server.start(open_browser=False, remind_after=float(sys.argv[1]))
print("CONNECTED", info.url, info.http_port, info.socket_port, flush=True)
connected_at = info.last_contact()
import vpython
ball = vpython.sphere()
reported = looping = False
while True:
    vpython.rate(30)
    if not looping:
        print("IN THE RATE LOOP", flush=True)   # a test waits for this, not for a guessed time
        looping = True
    if not reported and time.monotonic() - connected_at > 1.0:
        print("CONTACT since=%.3f advanced=%.3f"
              % (info.seconds_since_contact(), info.last_contact() - connected_at), flush=True)
        reported = True
"""

# Prepended to DRIVER to hold `import vpython` for a while, so that a test can act while vpython
# is still loading, after start() has printed the URL.
SLOW_VPYTHON = """
import importlib.abc, sys, time
class SlowVpython(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path, target=None):
        if name == "vpython":
            print("LOADING VPYTHON", flush=True)
            time.sleep(float(sys.argv[2]))
            print("VPYTHON LOADING GOES ON", flush=True)
        return None
sys.meta_path.insert(0, SlowVpython())
"""

CWD_SECRET = b"CWD-SECRET-7f3a91"
PARENT_SECRET = b"PARENT-SECRET-c2d804"
DECOY_JS = b"// DECOY-JS-55e1 from the working directory"


class Driver:
    """The driver program, with its stdout/stderr read by threads so no read can hang."""

    def __init__(self, cwd: Path, remind_after: float = 60.0, slow_vpython: float = 0.0):
        env = dict(os.environ, PYTHONPATH=str(ROOT))
        env.pop("VPYTHON_HTTP_PORT", None)
        code = (SLOW_VPYTHON if slow_vpython else "") + DRIVER
        self.proc = subprocess.Popen(
            [sys.executable, "-c", code, str(remind_after), str(slow_vpython)], cwd=cwd, env=env,
            stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.lines = {"out": queue.Queue(), "err": queue.Queue()}
        self.seen = {"out": [], "err": []}
        for name, stream in (("out", self.proc.stdout), ("err", self.proc.stderr)):
            threading.Thread(target=self._pump, args=(stream, name), daemon=True).start()

    def _pump(self, stream, name):
        for line in stream:
            self.lines[name].put(line)
        self.lines[name].put(None)

    def expect(self, pattern: str, stream: str = "out", timeout: float = 10.0) -> re.Match:
        deadline = time.monotonic() + timeout
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                raise AssertionError(f"no line matching {pattern!r} on std{stream} within "
                                     f"{timeout} s; seen: {self.seen[stream]}")
            try:
                line = self.lines[stream].get(timeout=remaining)
            except queue.Empty:
                continue
            if line is None:
                raise AssertionError(f"std{stream} closed before {pattern!r}; "
                                     f"seen: {self.seen[stream]}")
            self.seen[stream].append(line)
            match = re.search(pattern, line)
            if match:
                return match

    def http_port(self) -> int:
        match = self.expect(r"^Open http://127\.0\.0\.1:(\d+)/ in a browser$", timeout=10)
        return int(match.group(1))

    def drain(self, stream: str = "out") -> list[str]:
        """Every line seen so far on a stream, without waiting for more."""
        while True:
            try:
                line = self.lines[stream].get_nowait()
            except queue.Empty:
                return self.seen[stream]
            if line is None:
                return self.seen[stream]
            self.seen[stream].append(line)

    def stderr_text(self) -> str:
        """All of stderr; call only once the process has ended."""
        self.proc.wait(timeout=5)
        while True:
            try:
                line = self.lines["err"].get(timeout=2)
            except queue.Empty:
                break
            if line is None:
                break
            self.seen["err"].append(line)
        return "".join(self.seen["err"])

    def wait(self, timeout: float) -> int:
        return self.proc.wait(timeout=timeout)

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait(timeout=5)


@pytest.fixture
def sandbox(tmp_path: Path) -> Path:
    (tmp_path / "secret.png").write_bytes(PARENT_SECRET)
    cwd = tmp_path / "run"
    cwd.mkdir()
    (cwd / "secret.png").write_bytes(CWD_SECRET)
    (cwd / "glow.min.js").write_bytes(DECOY_JS)
    return cwd


@pytest.fixture
def run_driver(sandbox):
    drivers = []

    def run(remind_after: float = 60.0, slow_vpython: float = 0.0) -> Driver:
        driver = Driver(sandbox, remind_after, slow_vpython)
        drivers.append(driver)
        return driver

    yield run
    for driver in drivers:
        driver.kill()


# ---------------------------------------------------------------------------------- helpers

def raw_get(port: int, path: str, timeout: float = 5, headers: str = "") -> tuple[int, bytes]:
    """GET with the path sent byte for byte (no client-side normalising), and more headers."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as sock:
        sock.sendall(f"GET {path} HTTP/1.0\r\nHost: 127.0.0.1:{port}\r\n{headers}\r\n".encode("latin-1"))
        data = b""
        while chunk := sock.recv(65536):
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split()[1]), body


def websocket_port(http_port: int) -> int:
    status, page = raw_get(http_port, "/")
    assert status == 200
    return int(re.search(rb"var sock = '(\d+)'", page).group(1))


def ws_handshake(port: int, origin: str | None) -> tuple[socket.socket, bytes]:
    """Send a websocket Upgrade request; return the socket and the response's status line."""
    sock = socket.create_connection(("127.0.0.1", port), timeout=5)
    key = base64.b64encode(os.urandom(16)).decode()
    request = (f"GET / HTTP/1.1\r\nHost: localhost:{port}\r\nUpgrade: websocket\r\n"
               f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n")
    if origin is not None:
        request += f"Origin: {origin}\r\n"
    sock.sendall((request + "\r\n").encode())
    response = b""
    while b"\r\n" not in response:
        chunk = sock.recv(4096)
        if not chunk:
            break
        response += chunk
    return sock, response.split(b"\r\n", 1)[0]


def listening_sockets(pid: int) -> list[tuple[str, str, int]]:
    """(table, address, port) of each TCP socket in LISTEN state that the process holds."""
    inodes = set()
    for fd in os.listdir(f"/proc/{pid}/fd"):
        try:
            match = re.fullmatch(r"socket:\[(\d+)\]", os.readlink(f"/proc/{pid}/fd/{fd}"))
        except OSError:
            continue
        if match:
            inodes.add(match.group(1))
    found = []
    for table, family in (("tcp", socket.AF_INET), ("tcp6", socket.AF_INET6)):
        with open(f"/proc/net/{table}") as f:
            next(f)
            for line in f:
                fields = line.split()
                local, state, inode = fields[1], fields[3], fields[9]
                if state != "0A" or inode not in inodes:  # 0A = LISTEN
                    continue
                address_hex, port_hex = local.split(":")
                raw = bytes.fromhex(address_hex)  # 32-bit words, each little-endian
                raw = b"".join(raw[i:i + 4][::-1] for i in range(0, len(raw), 4))
                found.append((table, socket.inet_ntop(family, raw), int(port_hex, 16)))
    return found


def wait_for_listeners(pid: int, count: int, timeout: float = 10.0):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        found = listening_sockets(pid)
        if len(found) >= count:
            return found
        time.sleep(0.05)
    raise AssertionError(f"process {pid} listens on {listening_sockets(pid)}, wanted {count}")


def assert_clean_exit(driver: Driver, timeout: float, since: float | None = None) -> float:
    """Wait for exit status 0 and no traceback; return the seconds from `since` (or now)."""
    t0 = time.monotonic() if since is None else since
    status = driver.wait(timeout)
    elapsed = time.monotonic() - t0
    err = driver.stderr_text()
    assert status == 0, err
    assert "Traceback" not in err and "Exception" not in err, err
    return elapsed


# ------------------------------------------------------------------------------------ tests

def test_the_printed_url_already_accepts_connections_while_vpython_loads(run_driver):
    # The driver holds `import vpython` for 4 s, after start() prints the URL. A browser pointed at
    # the URL in that time must connect; its request is answered once vpython has loaded.
    driver = run_driver(slow_vpython=4.0)
    port = driver.http_port()
    assert 1 <= port <= 65535
    assert ("tcp", "127.0.0.1", port) in listening_sockets(driver.proc.pid)
    driver.expect(r"^LOADING VPYTHON$")
    with socket.create_connection(("127.0.0.1", port), timeout=5) as early:
        early.sendall(f"GET / HTTP/1.0\r\nHost: 127.0.0.1:{port}\r\n\r\n".encode())
        assert "VPYTHON LOADING GOES ON\n" not in driver.drain()  # connected while it loads
        early.settimeout(60)
        reply = b""
        while chunk := early.recv(65536):
            reply += chunk
    assert reply.startswith(b"HTTP/1.0 200") and b"glow" in reply
    assert driver.proc.poll() is None


def test_the_reminder_names_a_url_that_accepts_connections(run_driver):
    driver = run_driver(remind_after=0.5, slow_vpython=4.0)
    port = driver.http_port()
    match = driver.expect(r"Still waiting for a browser: open http://127\.0\.0\.1:(\d+)/ ",
                          stream="err", timeout=10)
    assert int(match.group(1)) == port
    with socket.create_connection(("127.0.0.1", port), timeout=5):
        pass
    assert raw_get(port, "/", timeout=60)[0] == 200


def test_both_servers_listen_on_loopback_only_before_any_browser(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    found = wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)
    assert sorted(found) == sorted([("tcp", "127.0.0.1", http_port),
                                    ("tcp", "127.0.0.1", ws_port)])
    assert driver.proc.poll() is None


def test_serves_the_page_and_vpython_files_but_nothing_else(run_driver, sandbox):
    driver = run_driver()
    port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)

    status, page = raw_get(port, "/")
    assert status == 200 and b"glow" in page and b"var sock = 'XXX'" not in page
    for path in ["/glow.min.js", "/jquery.min.js", "/ide.css", "/Roboto-Medium.ttf",
                 "/NimbusRomNo9L-Med.otf", "/favicon.ico", "/wood_texture.jpg",
                 "/images/ui-icons_217bc0_256x240.png", "/glow.min.js?v=1"]:
        status, body = raw_get(port, path)
        assert status == 200 and body, path
    status, js = raw_get(port, "/glow.min.js")
    assert DECOY_JS not in js  # vpython's own copy, not the working directory's

    parent_secret = sandbox.parent / "secret.png"
    attacks = [
        "/secret.png", "/../secret.png", "/%2e%2e/secret.png", "/%2E%2E/secret.png",
        "/..%2fsecret.png", "/%2e%2e%2fsecret.png", "/images/../../secret.png",
        "/images/%2e%2e/%2e%2e/secret.png", "/..\\secret.png", "/..%5csecret.png",
        "/" + str(parent_secret), "/" + "../" * 12 + str(parent_secret).lstrip("/"),
        "/%2f" + str(parent_secret).lstrip("/"), f"http://127.0.0.1:{port}/../secret.png",
        "//etc/passwd", "/../../../../etc/hostname.html", "/../../../../etc/passwd",
        "/images/", "/glowcomm.html/../secret.png", "/nothing.png", "/secret.txt",
    ]
    for path in attacks:
        status, body = raw_get(port, path)
        assert status == 404, path
        assert CWD_SECRET not in body and PARENT_SECRET not in body, path
    assert driver.proc.poll() is None


def test_reminds_on_stderr_while_no_browser_connects(run_driver):
    driver = run_driver(remind_after=1)
    port = driver.http_port()
    match = driver.expect(r"Still waiting for a browser: open (\S+) \(Ctrl-C to quit\)",
                          stream="err", timeout=5)
    assert match.group(1) == f"http://127.0.0.1:{port}/"


def test_foreign_websockets_are_refused_and_cannot_stop_the_program(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)

    for origin in ["http://evil.example", f"http://evil.example:{http_port}",
                   f"http://127.0.0.1:{ws_port}", f"https://127.0.0.1:{http_port}", "null", None]:
        sock, status_line = ws_handshake(ws_port, origin)
        sock.close()
        assert status_line.startswith(b"HTTP/1.1 ") and b" 101 " not in status_line, origin
    with socket.create_connection(("127.0.0.1", ws_port), timeout=5):
        pass  # a bare connect and close: vpython alone would SIGINT itself on this

    time.sleep(0.5)
    assert driver.proc.poll() is None
    assert raw_get(http_port, "/")[0] == 200


def test_own_origin_connects_and_closing_it_ends_the_program(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)

    sock, status_line = ws_handshake(ws_port, f"http://localhost:{http_port}")
    try:
        assert b" 101 " in status_line
        match = driver.expect(r"^CONNECTED (\S+) (\d+) (\d+)$", timeout=5)
        assert match.groups() == (f"http://127.0.0.1:{http_port}/", str(http_port), str(ws_port))
    finally:
        closed_at = time.monotonic()
        sock.close()
    assert assert_clean_exit(driver, timeout=60, since=closed_at) < ENDS_WITHIN


def test_ctrl_c_while_running_exits_cleanly(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    sock, status_line = ws_handshake(websocket_port(http_port), f"http://127.0.0.1:{http_port}")
    try:
        assert b" 101 " in status_line
        driver.expect(r"^CONNECTED ", timeout=5)
        driver.expect(r"^IN THE RATE LOOP$", timeout=60)   # it said so: no sleep guessing when
        driver.proc.send_signal(signal.SIGINT)
        assert assert_clean_exit(driver, timeout=60) < ENDS_WITHIN   # ends on Ctrl-C, not hangs
    finally:
        sock.close()


def test_ctrl_c_while_waiting_exits_cleanly(run_driver):
    driver = run_driver()
    driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    driver.proc.send_signal(signal.SIGINT)
    assert assert_clean_exit(driver, timeout=60) < ENDS_WITHIN   # ends on Ctrl-C, not hangs


def test_ctrl_c_while_vpython_loads_exits_cleanly(run_driver):
    driver = run_driver()
    driver.http_port()  # printed just before vpython is imported
    driver.proc.send_signal(signal.SIGINT)
    assert assert_clean_exit(driver, timeout=60) < ENDS_WITHIN   # ends on Ctrl-C, not hangs


BUSY_PORT_CHECK = """
import sys
from browser.loopback_server import ServerError, start
assert "vpython" not in sys.modules
for port in [int(sys.argv[1]), 0, -1, 70000, "8000", 1.5, True]:
    try:
        start(port=port, open_browser=False)
    except ServerError as exc:
        print("ERROR", exc)
    else:
        print("STARTED", port)
print("VPYTHON IMPORTED" if "vpython" in sys.modules else "VPYTHON NOT IMPORTED")
"""


def test_busy_or_invalid_port_raises_a_clear_error_without_importing_vpython(sandbox):
    with socket.socket() as held:
        held.bind(("127.0.0.1", 0))
        held.listen()
        port = held.getsockname()[1]
        result = subprocess.run(
            [sys.executable, "-c", BUSY_PORT_CHECK, str(port)], cwd=sandbox,
            env=dict(os.environ, PYTHONPATH=str(ROOT)), capture_output=True, text=True,
            timeout=20)
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert lines[0] == f"ERROR port {port} is already in use; pick another with --port"
    assert lines[1:7] == [f"ERROR invalid port {p}: use a whole number from 1 to 65535"
                          for p in ["0", "-1", "70000", "'8000'", "1.5", "True"]]
    assert lines[7] == "VPYTHON NOT IMPORTED"


@pytest.mark.browser
@pytest.mark.skipif(not os.path.exists(CHROMIUM), reason=f"no browser at {CHROMIUM}")
def test_real_browser_connects_and_closing_the_page_ends_the_program(run_driver, browser):
    driver = run_driver()
    port = driver.http_port()
    page = browser.new_page(viewport={"width": 800, "height": 600})   # conftest's browser: the module's Chromium
    try:
        failed = []
        page.on("response", lambda r: r.status >= 400 and failed.append((r.status, r.url)))
        page.goto(f"http://127.0.0.1:{port}/")
        driver.expect(r"^CONNECTED ", timeout=PATIENCE)
        contact = driver.expect(r"^CONTACT since=([\d.]+) advanced=([\d.]+)$", timeout=PATIENCE)
        since, advanced = map(float, contact.groups())
        assert since < 1.0 and advanced > 0.3  # the page keeps polling, and we see it
        assert failed == []
        closed_at = time.monotonic()
        page.close()
        elapsed = assert_clean_exit(driver, timeout=60, since=closed_at)
        assert elapsed < ENDS_WITHIN, f"took {elapsed:.2f} s to exit after the page closed"
    finally:
        if not page.is_closed():
            page.close()


# ------------------------------------------------------- hostile clients and the page's lifecycle

def get_with_host(port: int, host: str | None, path: str = "/") -> tuple[int, bytes]:
    """GET with exactly this Host header (None: none at all), as a DNS-rebinding page would send."""
    with socket.create_connection(("127.0.0.1", port), timeout=5) as sock:
        header = f"Host: {host}\r\n" if host is not None else ""
        sock.sendall(f"GET {path} HTTP/1.0\r\n{header}\r\n".encode("latin-1"))
        data = b""
        while chunk := sock.recv(65536):
            data += chunk
    head, _, body = data.partition(b"\r\n\r\n")
    return int(head.split()[1]), body


def ws_frame(payload: bytes, opcode: int = 1) -> bytes:
    """One masked websocket frame, as a client must send it."""
    mask = os.urandom(4)
    n = len(payload)
    length = bytes([0x80 | n]) if n < 126 else bytes([0x80 | 126]) + n.to_bytes(2, "big")
    return bytes([0x80 | opcode]) + length + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(payload))


def refusal_lines(driver: Driver) -> list[str]:
    return [line for line in driver.drain("err") if line.startswith("note: refused")]


def test_only_requests_for_this_programs_host_and_port_are_answered(run_driver):
    driver = run_driver()
    port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    for host in [f"127.0.0.1:{port}", f"localhost:{port}"]:
        assert get_with_host(port, host)[0] == 200, host
    for host in [f"evil.example:{port}", "evil.example", f"127.0.0.1:{port + 1}", "127.0.0.1",
                 f"localhost.:{port}", f"127.0.0.1:{port}.evil.example", "", None]:
        status, body = get_with_host(port, host)
        assert status == 421 and b"glow" not in body, host
    assert get_with_host(port, f"evil.example:{port}", "/glow.min.js")[0] == 421
    assert driver.proc.poll() is None


def test_garbage_on_the_websocket_gives_at_most_one_line_and_no_traceback(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    sock, status_line = ws_handshake(websocket_port(http_port), f"http://127.0.0.1:{http_port}")
    try:
        assert b" 101 " in status_line
        driver.expect(r"^CONNECTED ", timeout=5)
        for payload in [b"not json", b"[1,2", b'[{"event":"zzz"}]', b"{}", b"[null]", b"9" * 100]:
            sock.sendall(ws_frame(payload))
        time.sleep(2.5)  # longer than the gathering of one report
        assert driver.proc.poll() is None
        lines = refusal_lines(driver)
        assert len(lines) <= 1 and all("could not have sent" in line for line in lines), lines
        assert not any("Traceback" in line or "Error" in line for line in driver.drain("err"))
    finally:
        sock.close()
    assert_clean_exit(driver, timeout=5)


def test_refused_connections_are_counted_and_reported_at_most_every_few_seconds(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)
    for n in range(60):
        sock, status_line = ws_handshake(ws_port, "http://evil.example")
        sock.close()
        assert b" 403 " in status_line
    for n in range(20):
        assert get_with_host(http_port, "rebind.example")[0] == 421
    lines = []
    count = lambda pattern: sum(int(n) for line in lines for n in re.findall(pattern, line))
    # Wait for the reports to add up to the 80 refusals: a report comes every REPORT_EVERY s, or
    # later on a busy computer, where a fixed sleep of REPORT_EVERY + 1.5 s may look too early.
    deadline = time.monotonic() + 60
    while count(r"refused (\d+) connections") < 80 and time.monotonic() < deadline:
        lines = refusal_lines(driver)
        time.sleep(0.1)
    lines = refusal_lines(driver)
    assert 1 <= len(lines) <= 2, lines  # 80 refusals in a second or two: one line, or two 5 s apart
    assert count(r"refused (\d+) connections") == 80
    assert count(r"(\d+) from another web page") == 60 and count(r"(\d+) with a Host header") == 20
    assert driver.proc.poll() is None


def test_a_second_tab_is_refused_and_closing_it_does_not_end_the_program(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)
    page, status_line = ws_handshake(ws_port, f"http://127.0.0.1:{http_port}")
    try:
        assert b" 101 " in status_line
        driver.expect(r"^CONNECTED ", timeout=5)
        assert raw_get(http_port, "/status") == (200, b"busy")
        second, second_status = ws_handshake(ws_port, f"http://127.0.0.1:{http_port}")
        second.close()
        assert b" 409 " in second_status
        time.sleep(1.5)  # past the grace after a close
        assert driver.proc.poll() is None
        page.sendall(ws_frame(b"trigger"))  # the first tab still gets its updates
        page.settimeout(5)
        assert page.recv(2)[0] & 0x0F == 1  # a text frame back
    finally:
        closed_at = time.monotonic()
        page.close()
    assert assert_clean_exit(driver, timeout=60, since=closed_at) < ENDS_WITHIN


def test_a_reload_reconnects_and_the_program_keeps_running(run_driver):
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    ws_port = websocket_port(http_port)
    origin = f"http://127.0.0.1:{http_port}"
    page, status_line = ws_handshake(ws_port, origin)
    assert b" 101 " in status_line
    driver.expect(r"^CONNECTED ", timeout=5)
    # A reload: the browser fetches the page again, then the old page's websocket closes, the new
    # page's first script says it is loading, and the page connects once its scripts have loaded
    # (seconds, on a slow machine).
    assert raw_get(http_port, "/")[0] == 200
    page.close()
    raw_get(http_port, "/loading")
    time.sleep(3.0)
    assert driver.proc.poll() is None
    page, status_line = ws_handshake(ws_port, origin)
    assert b" 101 " in status_line
    # The 101 reply can reach us before the server has finished opening the connection; a reply
    # to a message shows it has (the page is answered only once open).
    page.sendall(ws_frame(b"trigger"))
    page.settimeout(5)
    assert page.recv(2)[0] & 0x0F == 1  # a text frame back
    assert raw_get(http_port, "/status") == (200, b"busy")
    closed_at = time.monotonic()
    page.close()
    assert assert_clean_exit(driver, timeout=60, since=closed_at) < ENDS_WITHIN


@pytest.mark.parametrize("headers", ["", "Sec-Fetch-Mode: navigate\r\nSec-Purpose: prefetch\r\n"],
                         ids=["bare", "prefetch"])
def test_a_fetch_of_the_page_that_no_page_follows_does_not_delay_the_end(run_driver, headers):
    # Something fetches "/" (curl, a browser's prefetch) while the page is open, and then the
    # page closes: no new page is loading, so this is not a reload to wait for.
    driver = run_driver()
    http_port = driver.http_port()
    wait_for_listeners(driver.proc.pid, 2)
    page, status_line = ws_handshake(websocket_port(http_port), f"http://127.0.0.1:{http_port}")
    assert b" 101 " in status_line
    driver.expect(r"^CONNECTED ", timeout=5)
    assert raw_get(http_port, "/", headers=headers)[0] == 200
    closed_at = time.monotonic()
    page.close()
    elapsed = assert_clean_exit(driver, timeout=40, since=closed_at)  # generous: it was 20 s
    assert elapsed < ENDS_WITHIN, f"took {elapsed:.1f} s to end after the page closed"


def test_every_patch_is_undone_once_vpython_has_started_or_failed_to():
    import asyncio.base_events
    import http.server

    from browser.server.patches import patched
    from browser.server.start import reserve
    from browser.server.state import ServerState

    patch_points = lambda: (http.server.HTTPServer, asyncio.base_events.BaseEventLoop.create_server,
                            threading.Thread, signal.signal)
    before = patch_points()
    state = ServerState.on(reserve(None), open_browser=False)
    try:
        with pytest.raises(ZeroDivisionError):
            with patched(state):
                assert all(now is not then for now, then in zip(patch_points(), before))
                assert not threading.Thread(target=print).daemon  # not vpython's: unchanged
                1 / 0
    finally:
        state.reservation.close()
    assert patch_points() == before
