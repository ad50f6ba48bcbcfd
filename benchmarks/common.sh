# common.sh: shell helpers the peer benchmarks share (sourced, not run): the RayDrive
# binary to use, POV-Ray installed on demand, wall-clock timing and medians.
# RAYDRIVE_BUILD=DIR uses an existing build instead of setting up and building build/.
bench_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
raydrive_bin() {
  [ -n "${RAYDRIVE_BUILD:-}" ] || "$bench_root/scripts/setup.sh" >&2
  echo "${RAYDRIVE_BUILD:-$bench_root/build}/bin/raydrive"
}
need_povray() {
  command -v povray >/dev/null ||
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq povray >/dev/null
}
# The SPD scenes, POV-Ray, the RayDrive binary ($bin) and a scratch folder ($work) removed
# on exit: what every peer benchmark starts with.
peer_benchmark_setup() {
  spd="${SPD_DIR:-$bench_root/../shared/scenes/spd}"
  need_povray
  bin="$(raydrive_bin)"
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
}
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# Milliseconds of wall time the command takes (its output discarded).
wall() { local t0 t1; t0=$(date +%s%N); "$@" >/dev/null 2>&1; t1=$(date +%s%N); echo "$(( (t1 - t0) / 1000000 ))"; }
# Peak resident memory of the command in MiB.
peak_mib() { /usr/bin/time -f %M "$@" 2>&1 >/dev/null | tail -1 | awk '{printf "%.0f", $1 / 1024}'; }
ratio() { echo "$1 $2" | awk '{printf "%.2f", $1 / $2}'; }
command -v /usr/bin/time >/dev/null 2>&1 || [ -x /usr/bin/time ] ||
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq time >/dev/null
