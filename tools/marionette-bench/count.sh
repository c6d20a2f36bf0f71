#!/bin/sh
# Stable figures for regressions (`make bench-count`): the instruction
# counts of fixed runs under callgrind, counted only inside each run
# (marionette-bench --count starts and stops the instrumentation), so the
# same build gives the same numbers on any machine; then the start-up of
# `marionette sim`, counted whole. The sweep's settings are
# counted too (one callgrind dump per run), and the accuracy-cost front is
# marked on those counts, which no load on the machine can move; the table
# also goes to BUILD_DIR/bench/sweep_count.csv.
#
#   tools/marionette-bench/count.sh [BUILD_DIR]
set -eu
build=${1:-build}
bench=$build/tools/marionette-bench/marionette-bench
[ -x "$bench" ] || { echo "bench-count: no $bench; build first" >&2; exit 2; }
command -v valgrind >/dev/null || { echo "bench-count: valgrind is missing (make deps)" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
echo "machine: $(uname -srm), $(sed -n 's/^model name[^:]*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
echo "commit: $(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo unknown)"
for run in puppet fig10 crowd decode; do
  case $run in
    puppet) what="host/scenes/puppet.yaml, 10 s" ;;
    fig10) what="stick figure, Fig. 10 track, 10 s" ;;
    crowd) what="100 stick puppets (capacity), 1 s" ;;
    decode) what="10 000 SAMPLE frames decoded" ;;
  esac
  valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$scratch/$run.out" \
    "$bench" --count $run >/dev/null 2>"$scratch/$run.log" ||
    { cat "$scratch/$run.log" >&2; exit 1; }
  total=$(sed -n 's/^totals: //p' "$scratch/$run.out" | head -1)
  printf '%-34s %15s instructions\n' "$what" "$total"
done

# One humanoid frame drawn and read back on one llvmpipe thread, at
# 640x360 and at 1280x720, and at 1280x720 without the theater's set (a
# dump each, counted after the shaders are compiled; a particle nudged so
# the shadow map is drawn again).
valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$scratch/render.out" \
  "$bench" --count render >/dev/null 2>"$scratch/render.log" ||
  { cat "$scratch/render.log" >&2; exit 1; }
for d in 1 2 3; do
  total=$(sed -n 's/^totals: //p' "$scratch/render.out.$d" | head -1)
  size=$(sed -n 's/^desc: Trigger: Client Request: render //p' "$scratch/render.out.$d")
  printf '%-34s %15s instructions\n' "humanoid frame drawn, $size" "$total"
done

# Start-up: every instruction of a whole `marionette` process, from the
# dynamic loader's first to exit (callgrind from the start, unlike the runs
# above). `sim --help` is the start-up alone, what every sim run pays before
# its scene; the stick figure for 1 ms adds reading and building a scene.
# sim maps no graphics library (the drawing commands are in the stage
# program), so this is the loader, the C and C++ runtimes and the scene.
marionette=$build/host/app/marionette
[ -x "$marionette" ] || { echo "bench-count: no $marionette; build first" >&2; exit 2; }
for run in help stick; do
  case $run in
    help) what="marionette sim --help, start-up"; set -- sim --help ;;
    stick)
      what="marionette sim, stick.yaml for 1 ms"
      set -- sim --time 0.001 -q "$(dirname "$0")/../../host/scenes/stick.yaml"
      ;;
  esac
  valgrind --tool=callgrind --callgrind-out-file="$scratch/$run.out" "$marionette" "$@" \
    >/dev/null 2>"$scratch/$run.log" || { cat "$scratch/$run.log" >&2; exit 1; }
  total=$(sed -n 's/^totals: //p' "$scratch/$run.out" | head -1)
  printf '%-34s %15s instructions\n' "$what" "$total"
done

# The sweep: instructions per simulated second of each setting, and the
# front on (instructions, end-effector error): a run is on it unless
# another is no worse in both and better in one. Two errors closer than
# what halving the reference's step moves it by are the same error: the
# reference cannot tell them apart.
mkdir -p "$build/bench"
csv=$build/bench/sweep_count.csv
echo "sweep, every setting on every puppet, 3 s of track each (a few minutes):"
valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$scratch/sweep.out" \
  "$bench" --count sweep >"$scratch/sweep.csv" 2>"$scratch/sweep.log" ||
  { cat "$scratch/sweep.log" >&2; exit 1; }
i=0
while IFS= read -r line; do
  i=$((i + 1))
  n=$(sed -n 's/^totals: //p' "$scratch/sweep.out.$i" | head -1)
  echo "$line,$n"
done <"$scratch/sweep.csv" >"$scratch/joined.csv"
awk -F, -v out="$csv" '
  { p[NR] = $1; s[NR] = $2; d[NR] = $3; sim[NR] = $4; ee[NR] = $5; tol[NR] = $6
    ok[NR] = $7; ips[NR] = $8 / $4 }
  END {
    print "puppet,setting,default,sim_s,ee_rms_m,ref_moved_m,ok,instructions_per_sim_s,front" > out
    for (i = 1; i <= NR; i++) {
      f = ok[i]
      for (j = 1; j <= NR && f; j++)
        if (j != i && ok[j] && p[j] == p[i] && ips[j] <= ips[i] && ee[j] <= ee[i] + tol[i] &&
            (ips[j] < ips[i] || ee[j] < ee[i] - tol[i])) f = 0
      front[i] = f
      printf "%s,%s,%d,%g,%g,%g,%d,%.0f,%d\n", p[i], s[i], d[i], sim[i], ee[i], tol[i], ok[i], ips[i], f > out
    }
    for (i = 1; i <= NR; i++) {
      if (p[i] != last) {
        printf "\n%s\n%-42s %16s %10s %5s\n", p[i], "setting", "instr/sim-s", "ee rms", "front"
        last = p[i]
      }
      gsub(/"/, "", s[i])
      printf "%-42s %16.0f %10.2e %5s%s\n", s[i], ips[i], ee[i], front[i] ? "yes" : "",
        ok[i] ? "" : "  not on the front: a reset, not finite, or strings over 1 %"
      if (d[i]) dflt[p[i]] = front[i]
    }
    printf "\ndefault on the front (instructions):"
    for (k in dflt) printf " %s %s;", k, dflt[k] ? "yes" : "NO"
    printf "\n"
  }' "$scratch/joined.csv"
