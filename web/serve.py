#!/usr/bin/python3
# Serves the page (build/web) for ./run.sh web: python3 web/serve.py FOLDER [--lan] [--port N].
# On this computer only (127.0.0.1) unless --lan: then on every network it is on, with the address
# other machines reach it by printed as text and as a QR code (Debian's qrencode) for phones.
# The first free port from 8000, or the one given.
#
# A class's phones must not be able to lock the others out, so this is one event loop (selectors)
# and no thread per connection: a connection that has not sent its request within HEADER_SECONDS
# is closed, a reply nobody reads for STALL_SECONDS is dropped, and when the open-file limit is
# near, the connection idle the longest makes room for the new one. Only regular files inside the
# folder are served (no links out of it, no listings); every refusal is one line of text.
import errno
import mimetypes
import os
import resource
import selectors
import shutil
import socket
import subprocess
import sys
import time
import urllib.parse

HEADER_SECONDS = 5   # from connecting to the end of the request's head
STALL_SECONDS = 10   # a reply that makes no progress for this long is dropped
MAX_HEAD = 8192      # bytes of request line and headers
SPARE_FILES = 16     # open files kept free for the listener, the selector and the file being read
USAGE = "usage: ./run.sh web [--lan] [--port N]"

TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
         ".mjs": "text/javascript; charset=utf-8", ".css": "text/css; charset=utf-8",
         ".json": "application/json", ".wasm": "application/wasm", ".svg": "image/svg+xml",
         ".toml": "text/plain; charset=utf-8", ".txt": "text/plain; charset=utf-8"}


def refuse(message):
    """A bad command line: one line on stderr, exit code 2."""
    print(f"whatnext: ./run.sh web: {message} ({USAGE})", file=sys.stderr)
    sys.exit(2)


def parse_args(argv):
    if not argv or argv[0].startswith("-"):
        refuse("the folder to serve comes first")
    folder, rest, lan, ports = argv[0], argv[1:], False, range(8000, 8100)
    while rest:
        arg = rest.pop(0)
        if arg == "--lan":
            lan = True
        elif arg == "--port":
            given = rest.pop(0) if rest else ""
            # ASCII digits only: str.isdigit() accepts '²', which int() then rejects
            if not (given.isascii() and given.isdigit() and 0 < int(given) < 65536):
                refuse(f"--port takes a port from 1 to 65535, not '{given}'")
            ports = [int(given)]
        else:
            refuse(f"it takes --lan and --port N, not '{arg}'")
    if not os.path.isdir(folder):
        refuse(f"there is no folder '{folder}' to serve")
    return folder, lan, ports


def lan_address():
    # The address a packet to the outside would leave from (a UDP socket sends nothing until
    # written to); 127.0.0.1 when there is no network.
    try:
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.connect(("192.0.2.1", 9))
            return s.getsockname()[0]
    except OSError:
        return "127.0.0.1"


def print_qr(url, png):
    """The address as a QR code in the terminal and as a PNG file (path png) to show full screen.
    The terminal code is drawn with explicit colours, dark modules on a light quiet zone of four
    modules, so it scans on light and dark terminal themes alike."""
    if not shutil.which("qrencode"):
        print("whatnext: no QR code (scripts/install-deps.sh installs qrencode)", flush=True)
        return
    subprocess.run(["qrencode", "-t", "ANSIUTF8", "-m", "4", url], check=False)
    part = png + ".part"
    try:
        subprocess.run(["qrencode", "-t", "PNG", "-s", "10", "-m", "4", "-o", part, url], check=True,
                       stderr=subprocess.DEVNULL)
        os.replace(part, png)
        print(f"whatnext: the same QR code as an image, to show full screen: {png}", flush=True)
    except (OSError, subprocess.CalledProcessError):
        try:
            os.remove(part)
        except OSError:
            pass


def page(status, reason, body=b"", ctype="text/plain; charset=utf-8", extra=""):
    head = (f"HTTP/1.1 {status} {reason}\r\nContent-Type: {ctype}\r\nContent-Length: {len(body)}\r\n"
            f"Cache-Control: no-cache\r\nX-Content-Type-Options: nosniff\r\n{extra}"
            "Connection: close\r\n\r\n")
    return head.encode("ascii"), body


def one_line(status, reason, why, extra=""):
    return page(status, reason, f"{status} {reason}: {why}\n".encode("utf-8"), extra=extra)


class Files:
    """The served folder: resolves a request's path to a regular file inside it."""

    def __init__(self, folder):
        self.root = os.path.realpath(folder)
        self.cache = {}  # real path -> (mtime_ns, size, bytes): phones of a class ask for the same files

    def inside(self, path):
        return path == self.root or path.startswith(self.root + os.sep)

    def read(self, path):
        with open(path, "rb") as f:
            st = os.fstat(f.fileno())
            key = (st.st_mtime_ns, st.st_size)
            hit = self.cache.get(path)
            if hit and hit[0] == key:
                return hit[1]
            data = f.read()
        self.cache[path] = (key, data)
        return data

    def answer(self, method, target):
        """(head, body) for GET or HEAD of the request target, never an exception."""
        if method not in ("GET", "HEAD"):
            return one_line(405, "Method Not Allowed", f"only GET and HEAD, not {method}",
                            "Allow: GET, HEAD\r\n")
        path = target.split("#", 1)[0].split("?", 1)[0]
        if not path.startswith("/"):
            return one_line(400, "Bad Request", "the path must start with /")
        try:
            rel = urllib.parse.unquote(path, errors="strict")
        except UnicodeDecodeError:
            return one_line(400, "Bad Request", "the path is not UTF-8")
        if any(ord(c) < 32 or c == "\x7f" for c in rel) or "\\" in rel:
            return one_line(400, "Bad Request", "the path has a control character or a backslash")
        parts = rel.split("/")
        if ".." in parts:
            return one_line(400, "Bad Request", "the path may not go up with ..")
        full = os.path.realpath(os.path.join(self.root, *[p for p in parts if p]))
        if not self.inside(full):
            return one_line(403, "Forbidden", "a link out of the served folder")
        if os.path.isdir(full):
            if not rel.endswith("/"):
                location = urllib.parse.quote(rel + "/")
                return one_line(301, "Moved Permanently", location, f"Location: {location}\r\n")
            full = os.path.realpath(os.path.join(full, "index.html"))
            if not self.inside(full):
                return one_line(403, "Forbidden", "a link out of the served folder")
        if not os.path.isfile(full):
            return one_line(404, "Not Found", "no such file (folders are not listed)")
        try:
            body = self.read(full)
        except OSError:
            return one_line(404, "Not Found", "the file cannot be read")
        ext = os.path.splitext(full)[1].lower()
        ctype = TYPES.get(ext) or mimetypes.guess_type(full)[0] or "application/octet-stream"
        head, _ = page(200, "OK", body, ctype)
        return head, (b"" if method == "HEAD" else body)


def parse_head(raw):
    """(method, target) of a complete request head, or a one-line refusal (head, body)."""
    line = raw.split(b"\n", 1)[0].rstrip(b"\r")
    try:
        text = line.decode("ascii")
    except UnicodeDecodeError:
        return one_line(400, "Bad Request", "the request line is not ASCII")
    words = text.split(" ")
    if len(words) != 3 or not words[2].startswith("HTTP/1."):
        return one_line(400, "Bad Request", "not an HTTP/1 request line")
    return words[0], words[1]


class Connection:
    __slots__ = ("sock", "since", "inbuf", "out", "writing")

    def __init__(self, sock, now):
        self.sock, self.since, self.inbuf, self.out, self.writing = sock, now, b"", [], False


class Server:
    def __init__(self, listener, files):
        self.listener, self.files = listener, files
        self.sel = selectors.DefaultSelector()
        self.conns = {}  # socket -> Connection, oldest first
        soft = resource.getrlimit(resource.RLIMIT_NOFILE)[0]
        self.room = max(4, (soft if soft != resource.RLIM_INFINITY else 4096) - SPARE_FILES)
        self.listening_again = 0.0  # when accepting is paused (no file to accept into), until then
        listener.setblocking(False)
        self.sel.register(listener, selectors.EVENT_READ, None)

    def close(self, conn):
        self.conns.pop(conn.sock, None)
        try:
            self.sel.unregister(conn.sock)
        except (KeyError, ValueError):
            pass
        conn.sock.close()

    def make_room(self):
        """Close the connection idle the longest (a request not sent, a reply not read)."""
        if not self.conns:
            return False
        self.close(min(self.conns.values(), key=lambda c: c.since))
        return True

    def accept(self, now):
        for _ in range(256):  # then serve the others before accepting more
            if len(self.conns) >= self.room:
                self.make_room()
            try:
                sock, _ = self.listener.accept()
            except BlockingIOError:
                return
            except OSError as e:
                if e.errno in (errno.EMFILE, errno.ENFILE, errno.ENOBUFS, errno.ENOMEM):
                    if not self.make_room():  # nothing of ours to close: wait instead of spinning
                        self.sel.unregister(self.listener)
                        self.listening_again = now + 0.1
                        return
                continue
            sock.setblocking(False)
            conn = Connection(sock, now)
            self.conns[sock] = conn
            self.sel.register(sock, selectors.EVENT_READ, conn)

    def read(self, conn, now):
        try:
            data = conn.sock.recv(MAX_HEAD)
        except (BlockingIOError, InterruptedError):
            return
        except OSError:
            return self.close(conn)
        if not data:
            return self.close(conn)
        conn.inbuf += data
        end = conn.inbuf.find(b"\r\n\r\n")
        if end < 0:
            end = conn.inbuf.find(b"\n\n")
        if end < 0:
            if len(conn.inbuf) <= MAX_HEAD:
                return
            head, body = one_line(431, "Request Header Fields Too Large", f"more than {MAX_HEAD} bytes")
        else:
            request = parse_head(conn.inbuf[:end])
            try:
                head, body = self.files.answer(*request) if isinstance(request[0], str) else request
            except Exception as e:  # a bug must cost one reply, not the server
                head, body = one_line(500, "Internal Server Error", type(e).__name__)
        conn.inbuf, conn.out, conn.writing, conn.since = b"", [memoryview(head), memoryview(body)], True, now
        self.sel.modify(conn.sock, selectors.EVENT_WRITE, conn)
        self.write(conn, now)

    def write(self, conn, now):
        while conn.out:
            if not conn.out[0]:
                conn.out.pop(0)
                continue
            try:
                n = conn.sock.send(conn.out[0])
            except (BlockingIOError, InterruptedError):
                return
            except OSError:
                return self.close(conn)
            conn.out[0] = conn.out[0][n:]
            conn.since = now
        try:
            conn.sock.shutdown(socket.SHUT_WR)
        except OSError:
            pass
        self.close(conn)

    def expire(self, now):
        for conn in list(self.conns.values()):
            if now - conn.since > (STALL_SECONDS if conn.writing else HEADER_SECONDS):
                self.close(conn)

    def run(self):
        next_sweep = 0.0
        while True:
            events = self.sel.select(0.25)
            now = time.monotonic()
            for key, mask in events:
                if key.data is None:
                    self.accept(now)
                elif key.data.sock in self.conns:
                    (self.write if key.data.writing else self.read)(key.data, now)
            if self.listening_again and now >= self.listening_again:
                self.listening_again = 0.0
                self.sel.register(self.listener, selectors.EVENT_READ, None)
            if now >= next_sweep:
                self.expire(now)
                next_sweep = now + 0.25


def main(argv):
    folder, lan, ports = parse_args(argv)
    for port in ports:
        listener = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        listener.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            listener.bind(("0.0.0.0" if lan else "127.0.0.1", port))
            listener.listen(512)
            break
        except OSError:
            listener.close()
    else:
        print(f"whatnext: ./run.sh web: no free port in {ports[0]}-{ports[-1]}", file=sys.stderr)
        sys.exit(2)
    if not lan:
        print(f"whatnext: the page is at http://localhost:{port}/ (Ctrl-C stops the server; "
              "./run.sh web --lan serves it to the local network)", flush=True)
    else:
        url = f"http://{lan_address()}:{port}/"
        print(f"whatnext: the page is served to the local network at {url}", flush=True)
        print("whatnext: every machine that reaches this one can open it; Ctrl-C stops the server", flush=True)
        if url.startswith("http://127."):
            print("whatnext: this computer is on no network; other machines cannot reach it", flush=True)
        print_qr(url, os.path.join(os.path.dirname(os.path.realpath(folder)), "web-address-qr.png"))
        print(f"whatnext: the page in one file, for a USB stick or any web space: {folder}/whatnext.html", flush=True)
    try:
        Server(listener, Files(folder)).run()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main(sys.argv[1:])
