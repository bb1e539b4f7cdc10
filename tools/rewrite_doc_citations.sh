#!/usr/bin/env bash
# One-shot: rewrites, in place, the citations of documents that are not in the repository into citations of
# docs/ — "DESIGN §n" → "docs/design.md §n", "DESIGN.md" → "docs/design.md", "ximu-formats.md §x" →
# "docs/file-formats.md §x" (the section numbers are kept), and each citation of an issue or of another
# project's source file into the thing it refers to (an explicit replacement per occurrence below).
#
#   tools/rewrite_doc_citations.sh [ROOT]     (ROOT: the checkout, default: the one holding this script)
#
# Runs over core/ io/ fitting/ tools/ tests/, README.md and data-samples/README.md (*.md *.cpp *.hpp *.h *.sh *.txt CMakeLists.txt),
# skipping build directories, .git and this script and tools/check_doc_citations.sh. It is idempotent: a second
# run changes nothing. Prints the number of rewritten citations per file and in total; then run
# tools/check_doc_citations.sh, which lists whatever is left (e.g. new occurrences in other wording).
set -euo pipefail

root="${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}"
cd "$root" || { echo "rewrite_doc_citations: cannot enter $root" >&2; exit 2; }

mapfile -d '' files < <(
  find core io fitting tools tests README.md data-samples/README.md \
    -type d \( -name '.git' -o -name 'build*' \) -prune -o \
    -type f \( -name '*.md' -o -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.sh' -o -name '*.txt' \
    -o -name 'CMakeLists.txt' \) \
    ! -path 'tools/rewrite_doc_citations.sh' ! -path 'tools/check_doc_citations.sh' -print0 2>/dev/null
)
((${#files[@]} > 0)) || { echo "rewrite_doc_citations: no files under $root" >&2; exit 2; }

perl -CSD -Mutf8 -i -pe '
  BEGIN { our %count; our $total = 0; }
  my $n = 0;

  # --- issue numbers, one explicit replacement per occurrence ------------------------------------------------
  $n += s{\QThe crafted bad-file corpus of issue 4 item 2:\E}{The crafted bad-file corpus (docs/design.md §12):}g;
  $n += s{\Q(issue 6, "Done when")\E}{(docs/design.md §12)}g;
  $n += s{\Qthe JSON keys of issue 4\E}{the JSON keys of docs/file-formats.md §9}g;
  $n += s{\Qthe JSON keys of issue 3\E}{the JSON keys of docs/file-formats.md §9}g;
  $n += s{\Qrealistic IMU errors: the issue'"'"'s 1e-2\E}{realistic IMU errors: the 1e-2 of docs/design.md §12}g;
  $n += s{\Q// Issue 4: angles from\E}{// docs/design.md §12: angles from}g;
  $n += s{\QThe issue'"'"'s targets: r_Cha(λ)\E}{The targets of docs/design.md §12: r_Cha(λ)}g;
  $n += s{\Q(issue 3, DESIGN §4)\E}{(docs/design.md §4, §12)}g;
  $n += s{\Qby more than this [m] (issue 3).\E}{by more than this [m] (docs/design.md §12).}g;
  $n += s{\Qresidual, the issue'"'"'s acceptance level\E}{residual, the acceptance level of docs/design.md §12}g;
  $n += s{\Q(the issue'"'"'s acceptance level)\E}{(the acceptance level of docs/design.md §12)}g;
  $n += s{\QDESIGN §4 / issue 3:\E}{docs/design.md §4:}g;
  $n += s{\Qthe acceptance criteria of issue 6.\E}{the acceptance criteria of docs/design.md §12.}g;
  $n += s{\QThe acceptance criterion of issue 6:\E}{The acceptance criterion of docs/design.md §12:}g;
  $n += s{\Q(issue 4: a 45 s, 256 Hz file set\E}{(docs/design.md §12: a 45 s, 256 Hz file set}g;
  $n += s{\Q(DESIGN §9, issue 4)\E}{(docs/design.md §9)}g;

  # --- source files of other projects, and ../shared in prose -------------------------------------------------
  $n += s{\Q// ximu-formats.md §1.6 (QuaternionData.cs:106-109): single-precision\E}{// The x-IMU GUI'"'"'s formulas (docs/file-formats.md §1.6): single-precision}g;
  $n += s{\Q(CSVfileWriter.cs; ximu-formats.md §1.2)\E}{(docs/file-formats.md §1.2)}g;
  $n += s{^// --- the real recordings of \.\./shared/real-imu -+$}{"// --- the real recordings beside the checkout (RealImuDir(), skipped when absent) " . ("-" x 14)}ge;

  # --- wording that does not survive the generic rules -----------------------------------------------------
  $n += s{\Qboth names exist because DESIGN lists them.\E}{both names exist because docs/design.md §4 lists them.}g;
  $n += s{\Q`DESIGN.md` is the contract. This file records what it does not settle\E}{[docs/design.md](../docs/design.md) is the design. This file records what it leaves open}g;

  # --- generic forms ----------------------------------------------------------------------------------------
  $n += s{\(DESIGN §([0-9]+[a-z]?); reference ximu-formats\.md}{(docs/design.md §$1; docs/file-formats.md}g;
  $n += s{\(reference ximu-formats\.md}{(docs/file-formats.md}g;
  $n += s{\breference ximu-formats\.md}{docs/file-formats.md}g;
  $n += s{\bximu-formats\.md}{docs/file-formats.md}g;
  $n += s{\bDESIGN §}{docs/design.md §}g;
  $n += s{\bDESIGN\.md\b}{docs/design.md}g;

  if ($n) { $count{$ARGV} += $n; $total += $n; }
  END {
    for my $file (sort keys %count) { printf STDERR "%4d  %s\n", $count{$file}, $file; }
    printf STDERR "rewrite_doc_citations: %d citation(s) rewritten in %d file(s)\n", $total, scalar(keys %count);
  }
' "${files[@]}"
