#!/usr/bin/env bash
# Checks that the Debian packages HELIOS builds and runs with are installed; installs the missing
# ones with apt-get when run as root (every apt-get waiting for another one's lock; a failed install
# exits 1 with one error line, and make stops), otherwise prints the command to run.
# usage: tools/install-deps.sh [--quiet] [--fuzz] [--slurm]
#   --fuzz:  also clang and libFuzzer, for make fuzz
#   --slurm: also Slurm (slurmctld, slurmd, srun) and munge, for tests/slurm/cluster.sh and slurm.bats;
#            without their recommends (about 30 plugin packages: HDF5, InfluxDB, IPMI, ROCm, ...)
set -euo pipefail

# package:probe, where probe is a command (cmd/NAME) or a file that the package installs.
checks=(
  "g++:cmd/g++"
  "cmake:cmd/cmake"
  "ninja-build:cmd/ninja"
  "pkg-config:cmd/pkg-config"
  "libginac-dev:/usr/include/ginac/ginac.h"
  "libcminpack-dev:/usr/include/cminpack-1/cminpack.h"
  "libeigen3-dev:/usr/include/eigen3/Eigen/Core"
  "nlohmann-json3-dev:/usr/include/nlohmann/json.hpp"
  "libvalijson-dev:/usr/include/valijson/validator.hpp"
  "libcurl4-openssl-dev:/usr/include/x86_64-linux-gnu/curl/curl.h"
  # SHA-256 of the compile cache's keys and programs (OpenSSL's EVP).
  "libssl-dev:/usr/include/openssl/evp.h"
  "libgtest-dev:/usr/include/gtest/gtest.h"
  "libcpp-httplib-dev:/usr/include/httplib.h"
  "gnuplot-nox:cmd/gnuplot"
  "bubblewrap:cmd/bwrap"
  "bats:cmd/bats"
  "jq:cmd/jq"
  "bc:cmd/bc"
  # Bats runs its files two at a time (bats --jobs needs GNU parallel).
  "parallel:cmd/parallel"
  # make test checks the C++ sources' layout against .clang-format (tests/bats/layout.bats).
  "clang-format:cmd/clang-format"
  # make test compiles every report's LaTeX with pdflatex (amsmath: texlive-latex-base, amssymb: texlive-base).
  "texlive-latex-base:cmd/pdflatex"
)
# make fuzz builds its targets with clang++ and links libFuzzer (libclang-rt-dev, only recommended by clang).
# Packages installed without their recommends.
lean_checks=()
for arg in "$@"; do
  if [[ $arg == --fuzz ]]; then
    checks+=("clang:cmd/clang++" "libclang-rt-dev:glob//usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a")
  elif [[ $arg == --slurm ]]; then
    lean_checks+=("slurmctld:/usr/sbin/slurmctld" "slurmd:/usr/sbin/slurmd" "slurm-client:/usr/bin/srun"
                  "munge:/usr/sbin/munged")
  fi
done
# missing_of ENTRY...: the packages whose probe fails.
missing_of() {
  local entry pkg probe
  for entry in "$@"; do
    pkg=${entry%%:*}
    probe=${entry#*:}
    if [[ $probe == cmd/* ]]; then
      command -v "${probe#cmd/}" >/dev/null 2>&1 || echo "$pkg"
    elif [[ $probe == glob/* ]]; then
      compgen -G "${probe#glob/}" >/dev/null || echo "$pkg"
    else
      [[ -e $probe ]] || echo "$pkg"
    fi
  done
}
mapfile -t missing < <(missing_of "${checks[@]}")
mapfile -t lean < <(missing_of ${lean_checks[@]+"${lean_checks[@]}"})
all=(${missing[@]+"${missing[@]}"} ${lean[@]+"${lean[@]}"})
[[ ${#all[@]} -eq 0 ]] && exit 0
if [[ $(id -u) -ne 0 ]] || ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: error: missing Debian packages: ${all[*]}; run: sudo apt-get install ${all[*]}" >&2
  exit 1
fi
echo "install-deps: installing ${all[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
# Every apt-get waits up to 10 minutes for another one's lock (a colleague's, an unattended
# upgrade) rather than failing on it at once.
lock_wait_s=600
apt_get=(apt-get -o "DPkg::Lock::Timeout=$lock_wait_s")
# fail WHAT: the one line that says what failed and what it was to install, and exit 1.
fail() {
  echo "install-deps: error: $1 (to install: ${all[*]}; apt-get's messages above say why)" >&2
  exit 1
}
# apt-get update takes the lock of the package lists, which DPkg::Lock::Timeout does not cover in
# every apt version: a run that fails on a held lock is retried until the same 10 minutes pass.
update_log=$(mktemp)
trap 'rm -f "$update_log"' EXIT
deadline=$((SECONDS + lock_wait_s))
until "${apt_get[@]}" update -qq 2>"$update_log"; do
  if grep -q 'Could not get lock' "$update_log" && ((SECONDS < deadline)); then
    sleep 2
    continue
  fi
  cat "$update_log" >&2
  fail "apt-get update failed"
done
cat "$update_log" >&2
install=("${apt_get[@]}" install -y -qq)
if [[ ${#missing[@]} -gt 0 ]]; then
  "${install[@]}" "${missing[@]}" >/dev/null || fail "apt-get install failed (exit $?)"
fi
if [[ ${#lean[@]} -gt 0 ]]; then
  "${install[@]}" --no-install-recommends "${lean[@]}" >/dev/null ||
    fail "apt-get install --no-install-recommends failed (exit $?)"
fi
# apt-get may exit 0 and leave a probe failing (a package that no longer installs the probed file).
mapfile -t still < <(missing_of ${checks[@]+"${checks[@]}"} ${lean_checks[@]+"${lean_checks[@]}"})
[[ ${#still[@]} -eq 0 ]] || fail "after apt-get, still missing: ${still[*]}"
