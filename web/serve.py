#!/usr/bin/python3
# Serves the page (build/web) for ./run.sh web: python3 web/serve.py FOLDER [--lan] [--port N].
# On this computer only (127.0.0.1) unless --lan: then on every network it is on, with the address
# other machines reach it by printed as text and as a QR code (Debian's qrencode) for phones.
# The first free port from 8000, or the one given.
import functools
import http.server
import shutil
import socket
import subprocess
import sys


class Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def lan_address():
    # The address a packet to the outside would leave from (a UDP socket sends nothing until
    # written to); 127.0.0.1 when there is no network.
    try:
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.connect(("192.0.2.1", 9))
            return s.getsockname()[0]
    except OSError:
        return "127.0.0.1"


def main(argv):
    usage = "usage: ./run.sh web [--lan] [--port N]"
    if not argv:
        sys.exit(usage)
    folder, rest, lan, ports = argv[0], argv[1:], False, range(8000, 8100)
    while rest:
        arg = rest.pop(0)
        if arg == "--lan":
            lan = True
        elif arg == "--port" and rest and rest[0].isdigit() and 0 < int(rest[0]) < 65536:
            ports = [int(rest.pop(0))]
        else:
            sys.exit(f"whatnext: ./run.sh web takes --lan and --port N (a port from 1 to 65535), not '{arg}'\n{usage}")
    handler = functools.partial(Quiet, directory=folder)
    for port in ports:
        try:
            server = http.server.ThreadingHTTPServer(("0.0.0.0" if lan else "127.0.0.1", port), handler)
            break
        except OSError:
            continue
    else:
        sys.exit(f"whatnext: no free port in {ports[0]}-{ports[-1]}")
    if not lan:
        print(f"whatnext: the page is at http://localhost:{port}/ (Ctrl-C stops the server; "
              "./run.sh web --lan serves it to the local network)", flush=True)
    else:
        url = f"http://{lan_address()}:{port}/"
        print(f"whatnext: the page is served to the local network at {url}", flush=True)
        print("whatnext: every machine that reaches this one can open it; Ctrl-C stops the server", flush=True)
        if url.startswith("http://127."):
            print("whatnext: this computer is on no network; other machines cannot reach it", flush=True)
        if shutil.which("qrencode"):
            subprocess.run(["qrencode", "-t", "UTF8", "-m", "2", url], check=False)
        else:
            print("whatnext: no QR code (scripts/install-deps.sh installs qrencode)", flush=True)
        print(f"whatnext: the page in one file, for a USB stick or any web space: {folder}/whatnext.html", flush=True)
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass


if __name__ == "__main__":
    main(sys.argv[1:])
