#!/usr/bin/env bash
# whatnext in one command on a fresh Debian 12 machine (run as root, or with the packages present):
#   ./run.sh          install what is missing, build, run the paper's example 1 with its
#                     timeline, plots and animation (into out/)
#   ./run.sh test     install what is missing, build, run every test; then again under the
#                     sanitizers with the fuzz harnesses (build-asan/)
#   ./run.sh web      install what is missing, build, serve the page (build/web) on localhost;
#                     with --lan on the local network too, with its address as text and QR code
#   ./run.sh notebook install what is missing (Debian's Jupyter too), build, open examples/whatnext.ipynb
set -euo pipefail
cd "$(dirname "$0")"
job="${1:-example}"
./scripts/install-deps.sh
# Clang 14 (installed for the sanitizer build too): the command's sweeps run 7-8 % faster than with
# GCC 12, the same bytes out (docs/performance.md, "The machine and the build").
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 >/dev/null
cmake --build build -j "$(nproc)"
case "$job" in
  example)
    mkdir -p out
    ./build/whatnext run --example 1 --events out/example1.json --csv out/example1.csv \
      --plots out --animate out/example1.gif
    echo "whatnext: plots, animation, events and CSV of example 1 are in out/"
    ;;
  test)
    failed=0
    ctest --test-dir build --output-on-failure -j "$(nproc)" || failed=1
    # The same tests, and the fuzz harnesses of fuzz/ for a fixed number of inputs each, built with
    # clang under AddressSanitizer and UndefinedBehaviorSanitizer; run even when the first pass
    # failed, so that one run reports everything.
    cmake -S . -B build-asan -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=Debug \
      -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" -DWHATNEXT_SANITIZE=ON -DWHATNEXT_FUZZ=ON -DWHATNEXT_BENCH=OFF \
      -DWHATNEXT_WEB=OFF -DWHATNEXT_PYTHON=OFF >/dev/null
    cmake --build build-asan -j "$(nproc)"
    ctest --test-dir build-asan --output-on-failure -j "$(nproc)" || failed=1
    exit "$failed"
    ;;
  web)
    # The page is static files: any web server does. web/serve.py takes the first free port from
    # 8000 and listens on this computer only, unless --lan asks for the local network (a class's
    # phones): then it prints the address to type and a QR code of it.
    exec /usr/bin/python3 web/serve.py build/web "${@:2}"
    ;;
  notebook)
    # Debian's Jupyter (jupyter-notebook, installed above from scripts/debian-packages.txt) on the
    # notebooks of examples/, with the module just built. It prints the address to open (with its
    # token) and serves until Ctrl-C. Root (CI, containers) needs --allow-root.
    export PYTHONPATH="$PWD/build/python${PYTHONPATH:+:$PYTHONPATH}"
    # Without a display (a server, a container) no browser is started: open the printed address.
    flags=()
    [ "$(id -u)" = 0 ] && flags+=(--allow-root)
    [ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && flags+=(--no-browser)
    echo "whatnext: opening examples/whatnext.ipynb (the students' exercises: examples/students.ipynb)"
    exec jupyter notebook "${flags[@]}" --notebook-dir="$PWD/examples" "$PWD/examples/whatnext.ipynb"
    ;;
  *)
    echo "usage: ./run.sh [example|test|web [--lan]|notebook]" >&2
    exit 2
    ;;
esac
