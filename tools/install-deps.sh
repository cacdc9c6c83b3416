#!/usr/bin/env bash
# Checks that the Debian packages HELIOS builds and runs with are installed; installs the missing
# ones with apt-get when run as root, otherwise prints the command to run.
# usage: tools/install-deps.sh [--quiet] [--fuzz]   (--fuzz: also clang and libFuzzer, for make fuzz)
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
  "libgtest-dev:/usr/include/gtest/gtest.h"
  "libcpp-httplib-dev:/usr/include/httplib.h"
  "gnuplot-nox:cmd/gnuplot"
  "bubblewrap:cmd/bwrap"
  "bats:cmd/bats"
  "jq:cmd/jq"
  "bc:cmd/bc"
  # make test compiles every report's LaTeX with pdflatex (amsmath: texlive-latex-base, amssymb: texlive-base).
  "texlive-latex-base:cmd/pdflatex"
)
# make fuzz builds its targets with clang++ and links libFuzzer (libclang-rt-dev, only recommended by clang).
for arg in "$@"; do
  if [[ $arg == --fuzz ]]; then
    checks+=("clang:cmd/clang++" "libclang-rt-dev:glob//usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a")
  fi
done
missing=()
for entry in "${checks[@]}"; do
  pkg=${entry%%:*}
  probe=${entry#*:}
  if [[ $probe == cmd/* ]]; then
    command -v "${probe#cmd/}" >/dev/null 2>&1 || missing+=("$pkg")
  elif [[ $probe == glob/* ]]; then
    compgen -G "${probe#glob/}" >/dev/null || missing+=("$pkg")
  else
    [[ -e $probe ]] || missing+=("$pkg")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0
if [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq "${missing[@]}" >/dev/null
else
  echo "install-deps: error: missing Debian packages: ${missing[*]}; run: sudo apt-get install ${missing[*]}" >&2
  exit 1
fi
