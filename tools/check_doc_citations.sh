#!/usr/bin/env bash
# Fails when a comment or document in the repository cites something a reader of the repository cannot open:
# the old specification and its section marks, the old x-IMU format note, files outside the checkout (the
# shared data folder beside it, in prose), issue numbers ("issue 4", "issue #4"), source files of other
# projects ("Foo.cs:12"), or a docs/*.md, <lib>/*.md or Markdown link whose file does not exist.
#
#   tools/check_doc_citations.sh [ROOT]      (ROOT: the checkout, default: the one holding this script)
#
# Prints FILE:LINE: what is cited and what to write instead, one line per finding; exits with 1 when there is
# any, 0 when there is none. docs/design.md and docs/file-formats.md keep the old section numbers.
set -euo pipefail

root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root" || { echo "check_doc_citations: cannot enter $root" >&2; exit 2; }

# Files that may name the shared data folder as a path the tests read at run time (not a citation), with a text the line
# must also contain. Keep this list short and explicit.
allowed_shared=(
  "tests/CMakeLists.txt|ROCKFIT_SHARED_DIR"
  "tests/support/test_paths.hpp|"
  "README.md|skip when that directory is absent"
)

# Tracked and untracked (not ignored) text files, without the bundled recordings and these two scripts.
# search [-o] ERE → FILE:LINE:TEXT (with -o: FILE:LINE:MATCH, one line per match)
search() {
  local only=()
  if [[ "$1" == -o ]]; then only=(-o); shift; fi
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git grep -n -I --untracked "${only[@]}" -E -e "$1" -- . ':!data-samples/recordings' \
      ':!tools/check_doc_citations.sh' || true
  else
    grep -rnIE "${only[@]}" --exclude-dir=.git --exclude-dir='build*' --exclude-dir=recordings \
      --exclude=check_doc_citations.sh -e "$1" . | sed 's|^\./||' || true
  fi
}

# FILE:LINE:MATCH → FILE:LINE: MESSAGE, with %s in MESSAGE replaced by the match.
explain() {
  awk -v message="$1" '{
    match($0, /^[^:]*:[0-9]+:/); where = substr($0, 1, RLENGTH - 1); cited = substr($0, RLENGTH + 1)
    text = message; sub(/%s/, cited, text); print where ": " text
  }'
}

findings="$(
  search -o '\bDESIGN(\.md|\b)( §[0-9]+[a-z]?)?' |
    explain "cites the old specification ('%s'), which is not in the repository; cite docs/design.md §n (same section numbers)"

  search -o 'ximu-formats\.md( §[0-9.]+)?' |
    explain "cites '%s', which is not in the repository; cite docs/file-formats.md (same section numbers: §1.1–§1.8, §2)"

  allowed="$(printf '%s\n' "${allowed_shared[@]}")"
  search '\.\./shared|\bshared/(real-imu|reference|ground-motions)' |
    awk -v allowed="$allowed" 'BEGIN { n = split(allowed, entries, "\n") }
      {
        match($0, /^[^:]*:[0-9]+:/); where = substr($0, 1, RLENGTH - 1); split(where, parts, ":")
        for (i = 1; i <= n; ++i) {
          bar = index(entries[i], "|"); file = substr(entries[i], 1, bar - 1); text = substr(entries[i], bar + 1)
          if (parts[1] == file && index($0, text) > 0) next
        }
        print where ": names the shared data folder, which is outside the repository; describe what is meant in docs/ and cite that " \
              "(a path the tests read at run time belongs in tests/support/test_paths.hpp and the allow-list of this check)"
      }'

  search -o "\\b[Ii]ssues? #?[0-9]+\\b|\\b[Tt]he issue's" |
    explain "cites an issue ('%s'); say what it refers to instead (a section of docs/, a test, a named tolerance)"

  search -o '\b[A-Za-z_][A-Za-z0-9_]*\.(cs|rs)(:[0-9-]+)?\b' |
    explain "cites a source file of another project ('%s'); state the fact itself, and cite docs/file-formats.md if needed"

  # docs/<name>.md and <lib>/<name>.md named anywhere must exist (relative to the checkout).
  search -o '\b(docs|core|io|fitting|tools|tests|data-samples)/[A-Za-z0-9_./-]*\.md\b' |
    while IFS= read -r hit; do
      path="${hit#*:*:}"
      [[ -e "$path" ]] || echo "${hit%:"$path"}: cites $path, which does not exist; write it or cite an existing document"
    done

  # Relative Markdown links in *.md files must point to existing files.
  search -o '\]\([^) ]+\)' |
    while IFS= read -r hit; do
      file="${hit%%:*}"
      [[ "$file" == *.md ]] || continue
      target="${hit#*:*:](}"
      target="${target%)}"
      target="${target%%#*}"
      [[ -z "$target" || "$target" =~ ^[a-z]+: ]] && continue
      dir="."
      [[ "$file" == */* ]] && dir="${file%/*}"
      [[ -e "$dir/$target" ]] || echo "${hit%%:](*}: links to $target, which does not exist"
    done
)"

if [[ -n "$findings" ]]; then
  printf '%s\n' "$findings" >&2
  echo "check_doc_citations: $(wc -l <<<"$findings") citation(s) of documents that are not in the repository." >&2
  exit 1
fi
echo "check_doc_citations: every cited document is in the repository"
