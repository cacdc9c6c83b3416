#!/usr/bin/env bash
# The house's figures issue 31 tracks, measured from the source (run from the repository's root):
#   - raw JSON reads (.at("…"), .contains("…"), .value("…")) outside the rooms whose job is to read
#     JSON: derivation/ (the derivation artifact), io/ and spec/ (the problem text and spec);
#   - the files that spell the names grammar of the derivation (l_x, x_tf, x_<id>_m, t_<id>_frac,
#     nu_/psi_/jump_ rows...) as string literals, which should be names.hpp alone;
#   - the ten longest functions outside spec/ (the house rule is under 100 lines), by ctags.
set -euo pipefail
cd "$(dirname "$0")/../.."
sources=(tools/lib/src tools/lib/include tools/helios-* templates/runtime)

# Lines holding a read, over the library's sources and the tools' mains (the issue's measure).
reads=$(grep -rhE '\.at\("|\.contains\("|\.value\("' --include='*.cpp' --include='*.hpp' tools/lib/src tools/helios-* \
          --exclude-dir=derivation --exclude-dir=io --exclude-dir=spec | wc -l)
echo "house: lines with raw JSON reads in tools/lib/src and tools/helios-*, outside derivation/, io/, spec/: $reads"
echo "house: by file (over 10), the runtime's templates included:"
grep -rcE '\.at\("|\.contains\("|\.value\("' --include='*.cpp' --include='*.hpp' "${sources[@]}" \
  --exclude-dir=derivation --exclude-dir=io --exclude-dir=spec | awk -F: '$2 > 10 {printf "  %4d %s\n", $2, $1}' |
  sort -rn

grammar='"(l_|_t0|_tf|_m|_p|_frac|t_|nu_|psi_|jump_|time_|stationarity_|transversality_|H_|_rate|_dep)"'
mapfile -t spellers < <(grep -rlE "$grammar" --include='*.cpp' --include='*.hpp' "${sources[@]}")
echo "house: files spelling the names grammar as literals: ${#spellers[@]}"
printf '  %s\n' "${spellers[@]}"

if ! command -v ctags >/dev/null || ! ctags --version 2>/dev/null | grep -q Universal; then
  echo "house: the longest functions need universal-ctags (apt-get install universal-ctags)"
  exit 0
fi
echo "house: the ten longest functions outside spec/ (lines, name, file):"
ctags -R --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat='%{line} %{end} %N %F' "${sources[@]}" |
  awk '$2 > 0 && $4 !~ /\/spec\// {printf "  %4d %s %s\n", $2 - $1 + 1, $3, $4}' | sort -rn | awk "NR <= 10"
