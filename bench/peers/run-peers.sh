#!/bin/sh
# What users would pick instead of whatnext, measured side by side in one run on this machine
# (docs/performance.md, "Peers"): example 1's lid-open time and the time per run of
#   * whatnext (the reference: its run at tolerance 1e-14, and its sweep's default accuracy),
#   * SciPy's solve_ivp on the paper's equations (scipy_example1.py, DOP853, several rtol),
#   * MuJoCo (example1.xml: the rope as a tendon length limit, time step 1e-5 s, several rope
#     stiffnesses).
# Needs python3-scipy and libmujoco-dev, which only this measurement uses (not the tests): they
# are installed here with apt-get if missing (as root), and are not in scripts/debian-packages.txt.
#
# Usage: bench/peers/run-peers.sh [WHATNEXT]    (default build/whatnext)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
whatnext=$(realpath "${1:-$root/build/whatnext}")
if ! dpkg -s libmujoco-dev python3-scipy >/dev/null 2>&1; then
  apt-get install -y libmujoco-dev python3-scipy >/dev/null
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM
cc -O2 -o "$work/mujoco_example1" "$here/mujoco_example1.c" -lmujoco -lm

echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg); $(date -u '+%Y-%m-%d %H:%M UTC')"
echo "whatnext: $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?'); $(python3 -c 'import scipy; print("SciPy", scipy.__version__)' 2>/dev/null || /usr/bin/python3 -c 'import scipy; print("SciPy", scipy.__version__)'); MuJoCo $(dpkg-query -W -f '${Version}' libmujoco-dev)"

# The reference: whatnext at tolerance 1e-14 (its events agree with a 1e-15 run to 1e-12 s).
"$whatnext" run --example 1 --set run.tolerance=1e-14 --events "$work/ref.json" >/dev/null
ref=$(/usr/bin/python3 -c "import json,sys; print(next(e['t'] for e in json.load(open(sys.argv[1]))['events'] if e['type']=='lid_open'))" "$work/ref.json")
echo "reference lid_open (whatnext, tolerance 1e-14): $ref s"
error() { /usr/bin/python3 -c "import sys; t=float(sys.argv[1]); r=float(sys.argv[2]); print(f'{t:.12f} s, error {t-r:+.2e} s ({100*(t-r)/r:+.3f} %)')" "$1" "$ref"; }

# whatnext: 10,000 runs of example 1 in one process on one core, as a sweep does them (the
# default accuracy 1e-8 s), the whole process's wall time divided by 10,000.
cd "$work"
start=$(date +%s.%N)
"$whatnext" sweep --example 1 --spread masses.lid=+-1e-12 --samples 10000 --threads 1 --out w.csv >/dev/null
end=$(date +%s.%N)
t=$(/usr/bin/python3 -c "import csv; r=list(csv.DictReader(open('w.csv'))); print(r[0]['lid_open'])")
echo "whatnext sweep (accuracy 1e-8 s, 1 core): lid_open $(error "$t"); $(/usr/bin/python3 -c "print(f'{($end-$start)/10000*1e6:.1f} us per run')")"
for tol in 1e-10 1e-14; do
  start=$(date +%s.%N)
  "$whatnext" sweep --example 1 --spread masses.lid=+-1e-12 --samples 2000 --threads 1 --set run.tolerance=$tol --out w.csv >/dev/null
  end=$(date +%s.%N)
  echo "whatnext sweep (run.tolerance $tol, 1 core): $(/usr/bin/python3 -c "print(f'{($end-$start)/2000*1e6:.1f} us per run')")"
done

for rtol in 1e-6 1e-8 1e-10 1e-12; do
  out=$(/usr/bin/python3 "$here/scipy_example1.py" "$rtol" 20)
  t=$(echo "$out" | sed -n 's/^lid_open //p')
  s=$(echo "$out" | sed -n 's/^seconds_per_run //p')
  echo "SciPy solve_ivp DOP853 rtol $rtol: lid_open $(error "$t"); $(/usr/bin/python3 -c "print(f'{$s*1e3:.2f} ms per run (best of 20)')")"
done

for tc in 0.00002 0.0005 0.001 0.002 0.005 0.02; do
  sed "s/ROPE_TC/$tc/" "$here/example1.xml" > "$work/m.xml"
  out=$("$work/mujoco_example1" "$work/m.xml" 1e-5 2)
  t=$(echo "$out" | sed -n 's/^lid_open //p')
  s=$(echo "$out" | sed -n 's/^seconds_per_run //p')
  if [ "$t" = "nan" ]; then res="the lid does not open by 2 s"; else res="lid_open $(error "$t")"; fi
  echo "MuJoCo dt 1e-5, rope time constant $tc s: $res; $(/usr/bin/python3 -c "print(f'{$s*1e3:.0f} ms per run (best of 2)')")"
done
