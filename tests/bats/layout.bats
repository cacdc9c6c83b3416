#!/usr/bin/env bats
# README.md's "Layout" section against the tree: it names every top-level entry of the repository
# and every library area, and every path it names exists. And every repository path, document and
# section that a source comment or a document cites exists (cited_paths.pl says what it reads).

load test_helper

setup() {
  common_setup
}

# The paths column of the Layout block (what stands before a run of three or more spaces), one
# path per line; a {a,b} group is expanded, a <placeholder> stands for any name (a glob's *).
layout_paths() {
  awk '/^## Layout/ { inside = 1; next } inside && /^```/ { if (fence++) exit; next } inside && fence' "$ROOT/README.md" |
    sed -E 's/ {3,}.*//' | tr ' ' '\n' | sed -e 's/,$//' -e '/^$/d' |
    while read -r path; do
      if [[ $path =~ ^(.*)\{([^}]*)\}(.*)$ ]]; then
        local alt a
        IFS=, read -ra alt <<<"${BASH_REMATCH[2]}"
        for a in "${alt[@]}"; do echo "${BASH_REMATCH[1]}$a${BASH_REMATCH[3]}"; done
      else
        echo "$path"
      fi
    done | sed -E 's#<[^>]*>#*#g'
}

@test "layout: every path README's Layout names exists" {
  local paths path missing=()
  paths="$(layout_paths)"
  [[ $(wc -l <<<"$paths") -ge 10 ]] || { echo "no Layout block found: $paths" >&2; false; }
  while read -r path; do
    compgen -G "$ROOT/$path" >/dev/null || missing+=("$path")
  done <<<"$paths"
  ((${#missing[@]} == 0)) || { echo "named in the Layout but missing: ${missing[*]}" >&2; false; }
}

@test "layout: README's Layout names every top-level entry and every library area" {
  local paths entry unnamed=()
  paths="$(layout_paths)"
  for entry in $(git -C "$ROOT" ls-files | cut -d/ -f1 | sort -u); do
    [[ $entry == .gitignore || $entry == .clang-format ]] && continue
    grep -q -F -x -e "$entry" -e "$entry/" <<<"$(sed -E 's#^([^/]+/?).*#\1#' <<<"$paths")" || unnamed+=("$entry")
  done
  local area areas
  areas="$(awk '/^## Layout/,0' "$ROOT/README.md" | grep -m1 'libhelios:')"
  for area in "$ROOT"/tools/lib/src/*/; do
    area="$(basename "$area")"
    [[ $areas == *" $area"[,\ ]* || $areas == *" $area" ]] || unnamed+=("tools/lib/src/$area")
  done
  ((${#unnamed[@]} == 0)) || { echo "in the tree but not in README's Layout: ${unnamed[*]}" >&2; false; }
}

@test "layout: every path, .md document and section cited in a comment or a document exists" {
  run -0 perl "$ROOT/tests/bats/cited_paths.pl" "$ROOT"
  [[ -z $output ]] || { echo "$output" >&2; false; }
}

@test "layout: the citation check finds a missing path, document and section, and passes patterns" {
  mkdir -p tree/tools/lib tree/tests
  cd tree
  git init -q .
  printf '# T\n\n## Set up\n\n**Limits of input** (exit 3)\n' >README.md
  cat >tools/lib/a.hpp <<'SRC'
// See tools/lib/a.hpp, tools/lib/b.hpp and design.md section 4; tools/helios-<verb>/main.cpp,
// scenarios/S<NN>/problem.txt, scenarios/SNN/settings.json and runs/builtin are not checked.
// README "Set up" and README "Limits" resolve; README "Results" does not.
const char* code_is_not_read = "tools/lib/c.hpp";
SRC
  printf '# Tests\n\nSee `tools/lib/a.hpp` and (`README.md`, "Set up"): the one beside this file.\n' >tests/README.md
  run -1 perl "$ROOT/tests/bats/cited_paths.pl" "$PWD"
  [[ $output == "tests/README.md:3: tests/README.md has no section \"Set up\"
tools/lib/a.hpp:1: no such path: tools/lib/b.hpp
tools/lib/a.hpp:1: no document named design.md in the tree
tools/lib/a.hpp:3: README.md has no section \"Results\"" ]] || { echo "$output" >&2; false; }
}

# The C++ sources as .clang-format lays them out, with Debian 12's clang-format 14 (another
# version breaks some lines elsewhere; tools/install-deps.sh installs this one). Under CI a missing
# clang-format is a failure, elsewhere the test is skipped.
@test "layout: every C++ source is laid out as .clang-format says" {
  if ! command -v clang-format >/dev/null; then
    [[ -z ${CI:-} ]] || { echo "no clang-format under CI: tools/install-deps.sh installs it" >&2; false; }
    skip "no clang-format (tools/install-deps.sh installs it)"
  fi
  [[ $(clang-format --version) == *" version 14."* ]] || skip "the layout is clang-format 14's; this is $(clang-format --version)"
  local files
  mapfile -t files < <(cd "$ROOT" && find tools templates tests \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) | sort)
  ((${#files[@]} >= 200))
  cd "$ROOT"
  run clang-format --dry-run -Werror "${files[@]}"
  [[ $status -eq 0 ]] || { echo "$output" | grep -E '^[^ ].*: error:' | cut -d: -f1 | sort -u | sed 's/^/not laid out: /' >&2; false; }
}
