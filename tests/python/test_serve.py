"""The class server of ./run.sh web (web/serve.py): it cannot be locked out by idle connections,
serves only regular files inside its folder, and answers bad requests and bad options in one line.

Everything runs on the loopback interface; every wait is bounded, and the server is stopped at the end.
"""

import importlib.util
import os
import pathlib
import re
import resource
import shutil
import socket
import subprocess
import sys
import time

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
SERVE = ROOT / "web" / "serve.py"
FILE_LIMIT = 64       # the server's open-file limit in these tests
IDLE_CLIENTS = 200    # more than the limit: they would lock everyone out if the server kept them
PAGE = b"<!doctype html><title>whatnext</title><p>the page</p>\n"


def low_file_limit():
    hard = resource.getrlimit(resource.RLIMIT_NOFILE)[1]
    resource.setrlimit(resource.RLIMIT_NOFILE, (FILE_LIMIT, hard))


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    """A served folder with a page, a folder without a page, and links out of the folder."""
    base = tmp_path_factory.mktemp("serve")
    root, outside = base / "web", base / "outside"
    (root / "plain").mkdir(parents=True)
    outside.mkdir()
    (root / "index.html").write_bytes(PAGE)
    (root / "plain" / "listed-if-listing.txt").write_text("inside\n")
    (outside / "secret.txt").write_text("SECRET-OUTSIDE\n")
    (root / "secret-link.txt").symlink_to(outside / "secret.txt")
    (root / "folder-link").symlink_to(outside)
    (root / "inner-link.html").symlink_to(root / "index.html")
    return root


@pytest.fixture(scope="module")
def server(site):
    proc = subprocess.Popen([sys.executable, str(SERVE), str(site)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=low_file_limit)
    try:
        line = proc.stdout.readline()  # the server prints its address before it serves
        port = int(re.search(r"http://localhost:(\d+)/", line).group(1))
        yield proc, port
    finally:
        proc.kill()
        proc.wait(timeout=10)
    assert proc.stderr.read() == "", "the server wrote to stderr (a traceback?)"


def request(port, raw, timeout=5.0):
    """The whole reply to raw request bytes: (status, headers text, body)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        s.sendall(raw)
        reply = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            reply += chunk
    head, _, body = reply.partition(b"\r\n\r\n")
    status = int(head.split(b" ", 2)[1])
    return status, head.decode("latin-1"), body


def get(port, path):
    return request(port, f"GET {path} HTTP/1.1\r\nHost: localhost\r\n\r\n".encode("latin-1"))


def thread_count(pid):
    status = pathlib.Path(f"/proc/{pid}/status").read_text()
    return int(re.search(r"^Threads:\s+(\d+)", status, re.M).group(1))


def cpu_seconds(pid):
    fields = pathlib.Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def test_serves_the_page(server):
    _, port = server
    status, head, body = get(port, "/")
    assert status == 200 and body == PAGE
    assert "text/html" in head
    assert get(port, "/inner-link.html")[2] == PAGE  # a link that stays inside is fine


def test_idle_clients_cannot_lock_out_a_new_one(server):
    proc, port = server
    idle = []
    try:
        # One after the other, each given a moment to connect, so that a server that keeps them
        # has them all (a few seconds at most; a server that accepts no more makes them wait).
        deadline = time.monotonic() + 6.0
        for _ in range(IDLE_CLIENTS):
            s = socket.socket()
            s.settimeout(max(0.01, min(0.3, deadline - time.monotonic())))
            try:
                s.connect(("127.0.0.1", port))  # and then sends nothing
            except OSError:
                pass
            idle.append(s)
        assert thread_count(proc.pid) <= 2, "a thread per connection"
        cpu_before, wall_before = cpu_seconds(proc.pid), time.monotonic()
        start = time.monotonic()
        status, _, body = get(port, "/")
        took = time.monotonic() - start
        assert status == 200 and body == PAGE
        assert took < 1.0, f"a new client waited {took:.2f} s behind {IDLE_CLIENTS} idle ones"
        # The idle ones do not make the server spin: it waits for them, it does not poll.
        time.sleep(1.0)
        cpu = cpu_seconds(proc.pid) - cpu_before
        assert cpu < 0.3 * (time.monotonic() - wall_before), f"{cpu:.2f} s of CPU while clients idle"
    finally:
        for s in idle:
            s.close()


def test_an_idle_connection_is_closed_within_seconds(server):
    _, port = server
    with socket.create_connection(("127.0.0.1", port), timeout=20) as s:
        s.sendall(b"GET / HTTP/1.1\r\n")  # half a request, then silence
        start = time.monotonic()
        try:
            ended = s.recv(100) == b""
        except ConnectionResetError:
            ended = True
        assert ended and time.monotonic() - start < 10


def test_no_link_out_of_the_folder(server):
    _, port = server
    for path in ("/secret-link.txt", "/folder-link/secret.txt"):
        status, _, body = get(port, path)
        assert status == 403, path
        assert b"SECRET" not in body
        assert body.count(b"\n") == 1


def test_no_folder_listing(server):
    _, port = server
    status, _, body = get(port, "/plain/")
    assert status == 404 and b"listed-if-listing" not in body
    status, head, _ = get(port, "/plain")
    assert status == 301 and "Location: /plain/" in head


@pytest.mark.parametrize("path", [
    "/a%00b", "/%2e%2e/outside/secret.txt", "/..%2f..%2fetc%2fpasswd", "/%2E%2e/", "/plain/%2e%2e/%2e%2e/",
    "/%c0%ae%c0%ae/", "/%ff", "/a%5cb", "/a%0ab", "http://localhost/index.html"])
def test_bad_paths_answered_in_one_line(server, path):
    _, port = server
    status, _, body = get(port, path)
    assert 400 <= status < 500, path
    assert body.count(b"\n") == 1 and b"Traceback" not in body
    assert b"SECRET" not in body


def test_raw_nul_and_garbage_answered(server):
    _, port = server
    for raw in (b"GET /a\x00b HTTP/1.1\r\n\r\n", b"GET /\xff HTTP/1.1\r\n\r\n", b"\x00\x01\x02\r\n\r\n",
                b"GET / FTP/9\r\n\r\n", b"POST / HTTP/1.1\r\nContent-Length: 0\r\n\r\n",
                b"GET /" + b"a" * 10000 + b" HTTP/1.1\r\n\r\n"):
        status, _, body = request(port, raw)
        assert 400 <= status < 500 and body.count(b"\n") == 1, raw[:40]
    assert get(port, "/")[2] == PAGE  # and it still serves


@pytest.mark.parametrize("args", [
    ["--port", "²"], ["--port", "0"], ["--port", "65536"], ["--port", "-1"], ["--port", "80x"],
    ["--port"], ["--colour"], []])
def test_bad_options_answered_in_one_line(site, args):
    folder = [] if args == [] else [str(site)]
    if args == []:
        args = ["--lan"]  # no folder: the option where the folder belongs
    proc = subprocess.run([sys.executable, str(SERVE), *folder, *args], capture_output=True,
                          text=True, timeout=30)
    assert proc.returncode == 2
    assert proc.stdout == "" and proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr


# The QR code of --lan: it must scan whatever the terminal's theme. The terminal's text is drawn
# into an image the way a terminal does (each character cell two modules high), once with dark
# text on a light background and once the other way round, and decoded by zbar.
HALF = {" ": (0, 0), "\u2580": (1, 0), "\u2584": (0, 1), "\u2588": (1, 1)}  # (top, bottom) in foreground
SGR = re.compile(r"\x1b\[([0-9;]*)m")


def draw_terminal(text, light_theme):
    """A grey image (rows of 0/255) of terminal text, cells one module wide and two high."""
    default_fg, default_bg = (0, 255) if light_theme else (255, 0)
    palette = {0: 0, 7: 255}  # ANSI black and white; the themes keep those dark and light
    lines = text.splitlines()
    width = max(len(SGR.sub("", line)) for line in lines) + 8
    rows = [[default_bg] * width for _ in range(4)]
    for line in lines:
        fg, bg, top, bottom = default_fg, default_bg, [default_bg] * 4, [default_bg] * 4
        pos = 0
        for m in re.finditer(r"\x1b\[[0-9;]*m|.", line):
            token = m.group(0)
            code = SGR.fullmatch(token)
            if code:
                for n in map(int, filter(None, code.group(1).split(";"))) if code.group(1) else [0]:
                    if n == 0:
                        fg, bg = default_fg, default_bg
                    elif 30 <= n <= 37:
                        fg = palette.get(n - 30, 128)
                    elif 40 <= n <= 47:
                        bg = palette.get(n - 40, 128)
                continue
            up, down = HALF[token]
            top.append(fg if up else bg)
            bottom.append(fg if down else bg)
            pos += 1
        pad = [default_bg] * (width - len(top))
        rows += [top + pad, bottom + pad]
    return rows + [[default_bg] * width for _ in range(4)]


def decode(rows, path, scale=8):
    """What zbarimg reads in the image (a binary PGM, each module scale pixels)."""
    height, width = len(rows) * scale, len(rows[0]) * scale
    pixels = b"".join(bytes(v for v in row for _ in range(scale)) * scale for row in rows)
    path.write_bytes(f"P5 {width} {height} 255\n".encode() + pixels)
    proc = subprocess.run(["zbarimg", "--raw", "-q", str(path)], capture_output=True, text=True, timeout=60)
    return proc.stdout.strip()


needs_qr = pytest.mark.skipif(not (shutil.which("qrencode") and shutil.which("zbarimg")),
                              reason="needs qrencode and zbarimg (zbar-tools)")


@needs_qr
def test_terminal_qr_scans_on_light_and_dark_themes(tmp_path, capfd):
    spec = importlib.util.spec_from_file_location("serve", SERVE)
    serve = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(serve)
    url = "http://192.168.1.20:8000/"
    png = tmp_path / "web-address-qr.png"
    serve.print_qr(url, str(png))
    out = capfd.readouterr().out
    art = "\n".join(line for line in out.splitlines() if "\x1b[" in line)
    assert decode(draw_terminal(art, True), tmp_path / "light.pgm") == url
    assert decode(draw_terminal(art, False), tmp_path / "dark.pgm") == url
    assert str(png) in out
    scanned = subprocess.run(["zbarimg", "--raw", "-q", str(png)], capture_output=True, text=True, timeout=60)
    assert scanned.stdout.strip() == url


@needs_qr
def test_the_qr_drawing_can_fail(tmp_path):
    """The check above can fail: a code drawn in the theme's own colours (qrencode -t UTF8) reads
    inverted on a light theme, and zbar does not read it there."""
    url = "http://192.168.1.20:8000/"
    art = subprocess.run(["qrencode", "-t", "UTF8", "-m", "4", url], capture_output=True, text=True).stdout
    assert decode(draw_terminal(art, False), tmp_path / "dark.pgm") == url
    assert decode(draw_terminal(art, True), tmp_path / "light.pgm") != url
