#!/bin/sh
# The whole-process figures of docs/performance.md, side by side in one run: the paper's own
# Fortran program and `whatnext run` on the same input (example 3 with the paper's step 0.00025 s,
# 79,777 rows of whatnext.dat), the same run's CSV, and the 10^4-machine sweep of docs/performance.md ("the grid").
#
# The Fortran listing is extracted from the paper's LaTeX source and compiled (gfortran -O2) in a
# temporary directory that is removed afterwards; nothing of it is kept or committed.
# Runs alternate between the programs (A B A B ...) so that a change of load hits both; the
# figures are medians of wall time, with the median CPU time (user + system) beside.
#
# Usage: scripts/time-against-fortran.sh [WHATNEXT] [PAPER_TEX] [RUNS]
#   defaults: build/whatnext, ../shared/seed/whatnext-paper.tex, 11 runs (the sweep: 5)
# Needs gfortran and a C compiler (Debian: gfortran, gcc).
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
whatnext=$(realpath "${1:-$here/build/whatnext}")
paper=$(realpath "${2:-$here/../shared/seed/whatnext-paper.tex}")
runs=${3:-11}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT INT TERM

# The listing is the paper's only verbatim block.
awk '/\\begin\{verbatim\}/{f=1; next} /\\end\{verbatim\}/{f=0} f' "$paper" > "$work/kermit.f"
gfortran -O2 -o "$work/kermit" "$work/kermit.f"
rm "$work/kermit.f"
# Example 3 in the program's input layout (whatnext.inp): hs, xs, phiS, phiL, f, lR, gamma, rL,
# rH, ms, mL, rhoair, rhohe, tmax, dt.
printf '%s\n' 0.0 -0.3 0.0 5.0 0.8 1.0 27.0 0.2 0.6 0.6 0.5 1.29 0.18 20.0 0.00025 > "$work/whatnext.inp"

# runs N A... -- B...: N runs of each, alternating, output to /dev/null (the files they write
# stay in $work); prints median wall and CPU of each. With RUNS_FRESH=FILE1:FILE2..., those files
# are removed before every run, untimed: each run then writes a new file instead of replacing one.
cat > "$work/runs.c" <<'EOF'
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
static int cmp(const void* a, const void* b) { double x = *(const double*)a, y = *(const double*)b; return (x > y) - (x < y); }
static void one(char** argv, double* wall, double* cpu) {
  struct timespec a, b;
  const char* fresh = getenv("RUNS_FRESH");
  if (fresh) {
    char list[4096];
    snprintf(list, sizeof list, "%s", fresh);
    for (char* f = strtok(list, ":"); f; f = strtok(NULL, ":")) unlink(f);
  }
  clock_gettime(CLOCK_MONOTONIC, &a);
  pid_t p = fork();
  if (p == 0) {
    int fd = open("/dev/null", O_WRONLY);
    dup2(fd, 1), dup2(fd, 2);
    execv(argv[0], argv);
    _exit(127);
  }
  int st;
  struct rusage ru;
  wait4(p, &st, 0, &ru);
  clock_gettime(CLOCK_MONOTONIC, &b);
  if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) { fprintf(stderr, "%s failed\n", argv[0]); exit(1); }
  *wall = (b.tv_sec - a.tv_sec) * 1e3 + (b.tv_nsec - a.tv_nsec) / 1e6;
  *cpu = (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1e3 + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e3;
}
int main(int argc, char** argv) {
  int n = atoi(argv[1]), split = 2;
  while (split < argc && strcmp(argv[split], "--") != 0) ++split;
  char** cmd[2] = {argv + 2, split < argc ? argv + split + 1 : NULL};
  if (split < argc) argv[split] = NULL;
  double w[2][n], c[2][n];
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k)
      if (cmd[k]) one(cmd[k], &w[k][i], &c[k][i]);
  for (int k = 0; k < 2 && cmd[k]; ++k) {
    qsort(w[k], n, sizeof(double), cmp), qsort(c[k], n, sizeof(double), cmp);
    printf("%.2f %.2f\n", w[k][n / 2], c[k][n / 2]);
  }
  return 0;
}
EOF
cc -O2 -o "$work/runs" "$work/runs.c"

cd "$work"
echo "machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg)"
echo "whatnext: $whatnext ($("$whatnext" --version))"
"$work/runs" "$runs" "$work/kermit" -- "$whatnext" run --example 3 --set run.output_step=0.00025 --dat "$work/e3.dat" > times
{ read -r fw fc; read -r ww wc; } < times
echo "Fortran (gfortran -O2), example 3, dt 0.00025 s:   $fw ms wall  ($fc ms CPU)  $(wc -l < whatnext.dat) rows"
echo "whatnext run --example 3 ... --dat:              $ww ms wall  ($wc ms CPU)  $(wc -l < e3.dat) rows"
echo "  ratio (target <= 0.1):                         $(echo "$ww $fw" | awk '{printf "%.3f", $1 / $2}')"
# The same, each run writing a new file: replacing one costs whatnext the safe replacement (a
# temporary renamed over the old file; ext4 then writes the new file's blocks out and frees the
# old one's, after waiting for its writes of the run before), which the paper's program, which
# overwrites its file in place, does not pay (docs/performance.md, "The file").
RUNS_FRESH="$work/whatnext.dat:$work/e3.dat" "$work/runs" "$runs" "$work/kermit" -- "$whatnext" run --example 3 \
  --set run.output_step=0.00025 --dat "$work/e3.dat" > times
{ read -r fw fc; read -r ww wc; } < times
echo "  the same, a new file each run: Fortran $fw ms, whatnext $ww ms wall ($wc ms CPU), ratio $(echo "$ww $fw" | awk '{printf "%.3f", $1 / $2}')"
"$work/runs" "$runs" "$whatnext" run --example 3 --set run.output_step=0.00025 --csv "$work/e3.csv" > times
read -r cw cc < times
echo "whatnext run --example 3 ... --csv:              $cw ms wall  ($cc ms CPU)  $(wc -l < e3.csv) rows, ratio $(echo "$cw $fw" | awk '{printf "%.3f", $1 / $2}')"
"$work/runs" 5 "$whatnext" sweep --example 2 --vary geometry.rope_length=0.64:0.80:100 \
  --vary start.sandbag_height=0.3:1.2:100 --out "$work/s.csv" > times
read -r sw sc < times
echo "whatnext sweep, 10^4 machines, all cores:       $sw ms wall  ($sc ms CPU)  $(echo "$sw" | awk '{printf "%.0f", 1e7 / $1}') machines/s (target >= 80000)"
echo "load $(cut -d' ' -f1-3 /proc/loadavg)"
