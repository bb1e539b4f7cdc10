#!/usr/bin/env python3
"""Runs the commands that README.md and python/README.md show with their output, and compares the output.

    check_readme.py --rockfit BIN [--python-module-dir DIR [--python EXE] | --without-python]
                    [--source-dir DIR] [--update] [--keep] README.md python/README.md

How to write a README section that this script checks (docs/design.md §12, "The README tests itself"):

* A fenced block whose language is `console` is run. Each line that starts with `$ ` is a command (a line ending
  in `\\` continues it on the next line, as in a shell); the lines after it, up to the next `$ ` line, are its
  output: stdout and stderr together through one pipe, as a log shows them (stdout comes out when the program
  flushes it; on a pipe the program prints progress lines where a terminal shows a progress bar). A command
  followed by no lines must print nothing. `$ echo $?` after a command shows its exit code; any other command
  must exit with 0.
* A line that is only `...` (or `…`) stands for any number of output lines: the lines up to the first one equal
  to the next shown line (or up to the end).
* The commands run in document order, in one scratch copy of the repository's files per README (the files git
  tracks, as they are in the work tree: `git add` a new data file first; no build tree), so a later block may use
  the files an earlier one wrote. The working
  directory is the copy's root. `rockfit` is the built program (on PATH, and as `build/tools/rockfit`),
  `build/python` the built module, and `/usr/bin/python3` in a command is replaced by --python (the interpreter
  given to CMake). --without-python (a build without the module) skips the commands that name build/python.
* Before comparing, each line of both sides is masked where the output legitimately varies from run to run —
  durations ("in 0.76 s", "elapsed 0.7 s", "ETA 11 s", "wall time 105.76 ms", "(3017 of the simulations,
  0.33 s)", "(3.5 s)" after a thread count), speeds ("146.2 simulations/s"), thread counts ("2 thread(s)"),
  dates and the scratch directory's absolute path — and its trailing blanks are dropped. Nothing else is
  masked: paste the real output.
* A block that shows commands with `$ ` but cannot run here (a cluster, a file of the user's) is written with
  another language (e.g. ```sh) and preceded by the line `<!-- readme-check: skip REASON -->`; a block with `$ `
  lines that is neither `console` nor marked so is an error, so that no shown output escapes the check.

A mismatch prints a unified diff whose `---` side is the README (with its line numbers) and whose `+++` side is
the real output. --update writes the real output into the README instead (keeping each `...`), for pasting.
Exit code 0 when every shown output matches, 1 when one does not, 2 for bad use or a malformed README.
"""
import argparse
import difflib
import os
import pathlib
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time

SKIP_MARKER = re.compile(r"^<!--\s*readme-check:\s*skip\b(.*)-->\s*$")
FENCE = re.compile(r"^(`{3,})\s*([\w+-]*)\s*$")
ELLIPSIS = ("...", "…")
SYSTEM_PYTHON = "/usr/bin/python3"
# Separates the outputs of the commands of one block in the shell's combined output (with the exit code).
SEPARATOR = "@@rockfit-readme-check-7f3a@@"
BLOCK_TIMEOUT_S = 600  # the slowest block (a whole fit campaign) takes about 20 s on two busy cores

NUMBER = r"\d+(?:\.\d+)?"
DURATION = NUMBER + r"\s*(?:ms|µs|us|s|min|h)\b"
# (pattern, replacement): only what varies from run to run; each one names the context it needs, so that a
# physical time such as "first impact at 2.7148 s" or "(6 s)" of a recording is never masked.
MASKS = [
    (re.compile(r"\b(in|elapsed|ETA|took) " + DURATION), r"\1 <duration>"),        # wall times of a run
    (re.compile(r"\bwall time(\s+)" + DURATION), r"wall time\1<duration>"),
    (re.compile(r"\bsimulations, " + DURATION + r"\)"), "simulations, <duration>)"),  # fit's interval effort
    (re.compile(NUMBER + r"( simulations/s\b)"), r"<speed>\1"),
    (re.compile(r"\b\d+( thread\(s\))"), r"<threads>\1"),                          # the machine's cores
    (re.compile(r"(thread\(s\)) \(" + DURATION + r"\)"), r"\1 (<duration>)"),
    (re.compile(r"\b\d{4}-\d{2}-\d{2}(?:[ T]\d{2}:\d{2}(?::\d{2}(?:\.\d+)?)?(?:Z|[+-]\d{2}:?\d{2})?)?\b"), "<date>"),
]


class ReadmeError(Exception):
    """A README that breaks the markup (exit code 2)."""


class Command:
    def __init__(self, path, line, text, shown, shown_line):
        self.path = path            # the README
        self.line = line            # README line of the `$ `
        self.text = text            # the command, continuation lines joined with newlines
        self.shown = shown          # the output lines shown
        self.shown_line = shown_line  # README line of the first output line


def parse_readme(path, name):
    """Every checked block of the README `path` (named `name` in messages) as a list of Commands; raises
    ReadmeError for a block that escapes the check."""
    lines = path.read_text(encoding="utf-8").split("\n")
    blocks = []
    i = 0
    previous = ""  # the last non-blank line before the current one
    while i < len(lines):
        match = FENCE.match(lines[i])
        if not match:
            if lines[i].strip():
                previous = lines[i].strip()
            i += 1
            continue
        fence, language = match.group(1), match.group(2)
        start = i
        i += 1
        body = []
        while i < len(lines) and lines[i].rstrip() != fence:
            body.append(lines[i])
            i += 1
        if i == len(lines):
            raise ReadmeError(f"{name}:{start + 1}: the block opened here is never closed")
        i += 1
        skipped = SKIP_MARKER.match(previous) is not None
        previous = ""
        shows_commands = any(line.startswith("$ ") for line in body)
        if language != "console":
            if shows_commands and not skipped:
                raise ReadmeError(
                    f"{name}:{start + 1}: a ```{language} block shows `$ ` commands; write it as ```console so that "
                    "its output is checked, or put `<!-- readme-check: skip REASON -->` on the line before it")
            continue
        if skipped:
            raise ReadmeError(f"{name}:{start + 1}: a ```console block is always checked; to skip it, give it "
                              "another language (```sh) after the skip marker")
        blocks.append(parse_console_block(name, start + 2, body))
    return blocks


def parse_console_block(name, first_line, body):
    commands = []
    k = 0
    while k < len(body):
        line = body[k]
        if not line.startswith("$ "):
            if not line.strip() and not commands:
                k += 1
                continue
            raise ReadmeError(f"{name}:{first_line + k}: output before the first `$ ` command of the block")
        line_number = first_line + k
        text = line[2:]
        while text.endswith("\\") and k + 1 < len(body):
            k += 1
            text += "\n" + body[k]
        k += 1
        shown_line = first_line + k
        shown = []
        while k < len(body) and not body[k].startswith("$ "):
            shown.append(body[k])
            k += 1
        commands.append(Command(name, line_number, text, shown, shown_line))
    return commands


def mask(line, scratch):
    line = line.replace(str(scratch), "<scratch>").rstrip()
    for pattern, replacement in MASKS:
        line = pattern.sub(replacement, line)
    return line


def align(shown, actual, scratch):
    """The real output in the shape of the shown one: each `...` keeps its place and stands for the real lines it
    covers (up to the first one equal to the next shown line). Returns (view of masked lines, view of raw lines)."""
    masked_actual = [mask(a, scratch) for a in actual]
    view, raw = [], []
    i = 0
    for k, line in enumerate(shown):
        if line.strip() in ELLIPSIS:
            following = next((mask(s, scratch) for s in shown[k + 1:] if s.strip() not in ELLIPSIS), None)
            if following is None:
                j = len(actual)
            else:
                j = next((n for n in range(i, len(actual)) if masked_actual[n] == following), i)
            view.append(line.strip())
            raw.append(line)
            i = j
        elif i < len(actual):
            view.append(masked_actual[i])
            raw.append(actual[i])
            i += 1
    view.extend(masked_actual[i:])
    raw.extend(actual[i:])
    return view, raw


def unified_diff(command, shown_masked, view):
    """A unified diff with the README's line numbers on the `---` side."""
    offset = command.shown_line - 1
    out = []
    for line in difflib.unified_diff(shown_masked, view, f"{command.path} (shown, masked)",
                                     "real output (masked)", n=3, lineterm=""):
        hunk = re.match(r"^@@ -(\d+)(,\d+)? \+(\d+)(,\d+)? @@$", line)
        if hunk:
            line = f"@@ -{int(hunk.group(1)) + offset}{hunk.group(2) or ''} +{hunk.group(3)}{hunk.group(4) or ''} @@"
        out.append(line)
    return "\n".join(out)


def repository_files(source):
    """Paths (relative) of the files of the repository: those git tracks (or has staged); without git (a source
    archive), every file outside .git and the build trees."""
    try:
        listed = subprocess.run(["git", "-C", str(source), "ls-files", "-z", "--cached"], capture_output=True,
                                check=True).stdout
        return sorted({p for p in listed.decode().split("\0") if p})
    except (OSError, subprocess.CalledProcessError):
        files = []
        for root, dirs, names in os.walk(source):
            dirs[:] = [d for d in dirs if d != ".git" and not (root == str(source) and d.startswith("build"))]
            files += [os.path.relpath(os.path.join(root, n), source) for n in names]
        return sorted(files)


def make_scratch(source, rockfit, module_dir):
    scratch = pathlib.Path(tempfile.mkdtemp(prefix="rockfit-readme-"))
    for relative in repository_files(source):
        origin = source / relative
        if origin.is_file():
            target = scratch / relative
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(origin, target)
    (scratch / "build" / "tools").mkdir(parents=True)
    (scratch / "build" / "tools" / "rockfit").symlink_to(rockfit)
    if module_dir:
        (scratch / "build" / "python").symlink_to(module_dir, target_is_directory=True)
    return scratch


def needs_module(command):
    return "build/python" in command.text


def run_block(block, scratch, python, with_python):
    """Runs the commands of a block in one shell; returns (output lines, exit code, seconds) per command."""
    script = ["cd " + shlex.quote(str(scratch))]
    for command in block:
        text = command.text if with_python or not needs_module(command) else ":"
        if python != SYSTEM_PYTHON:
            text = re.sub(r"(?<![\w/])" + re.escape(SYSTEM_PYTHON) + r"(?![\w/])", python, text)
        script.append(text)
        script.append(f"__rc=$?; printf '\\n{SEPARATOR} %d %s\\n' \"$__rc\" \"$(date +%s.%N)\"; (exit $__rc)")
    env = dict(os.environ)
    env["PATH"] = str(scratch / "build" / "tools") + os.pathsep + env.get("PATH", "")
    env.update(LC_ALL="C.UTF-8", PYTHONIOENCODING="utf-8", PYTHONDONTWRITEBYTECODE="1",
               MPLCONFIGDIR=str(scratch / ".matplotlib"))
    started = time.time()
    # A session of its own, so that a command that hangs is killed with the shell (the commands after it report
    # no exit code).
    shell = subprocess.Popen(["bash", "-c", "\n".join(script)], stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, env=env, start_new_session=True)
    try:
        output, _ = shell.communicate(timeout=BLOCK_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        os.killpg(shell.pid, signal.SIGKILL)
        output, _ = shell.communicate()
        output += f"\n[killed after {BLOCK_TIMEOUT_S} s]".encode()
    output = output.decode("utf-8", errors="replace")
    parts = re.split(r"\n?" + re.escape(SEPARATOR) + r" (\d+) ([\d.]+)\n", output)
    results = []
    last = started
    for n in range(len(block)):
        if 3 * n + 2 >= len(parts):
            results.append((parts[3 * n].split("\n") if 3 * n < len(parts) else [], None, 0.0))
            continue
        text, code, finished = parts[3 * n], int(parts[3 * n + 1]), float(parts[3 * n + 2])
        text = text[:-1] if text.endswith("\n") else text  # the separator starts a line of its own
        results.append((text.split("\n") if text else [], code, finished - last))
        last = finished
    return results


def first_line(command):
    text = command.text.split("\n")[0]
    return text if len(text) <= 90 else text[:87] + "..."


def check_readme(path, name, blocks, scratch, python, with_python, update):
    """Runs every block of one README (the file `path`, shown as `name`); returns the number of failures."""
    failures = 0
    replacements = {}
    for block in blocks:
        results = run_block(block, scratch, python, with_python)
        for n, (command, (actual, code, seconds)) in enumerate(zip(block, results)):
            where = f"{name}:{command.line}"
            if not with_python and needs_module(command):
                print(f"skip {where} (--without-python) $ {first_line(command)}", flush=True)
                continue
            if code is None:
                print(f"FAIL {where}: no exit code (the block's shell was killed or stopped before it ended) "
                      f"$ {first_line(command)}", flush=True)
                if actual:
                    print("     its output: " + "\n     ".join(actual[-20:]), flush=True)
                failures += 1
                continue
            shows_code = n + 1 < len(block) and block[n + 1].text.strip() == "echo $?"
            shown_masked = [s.strip() if s.strip() in ELLIPSIS else mask(s, scratch) for s in command.shown]
            view, raw = align(command.shown, actual, scratch)
            problems = []
            if code != 0 and not shows_code:
                problems.append(f"exited with code {code} (show `$ echo $?` after it if that is meant)")
            if view != shown_masked:
                problems.append("the shown output differs from the real one:\n"
                                + unified_diff(command, shown_masked, view))
                replacements[(command.shown_line, len(command.shown))] = raw
            status = "FAIL" if problems else "ok  "
            print(f"{status} {where} ({seconds:.1f} s) $ {first_line(command)}", flush=True)
            for problem in problems:
                print("     " + problem.replace("\n", "\n     "), flush=True)
            failures += bool(problems)
    if update and replacements:
        lines = path.read_text(encoding="utf-8").split("\n")
        for (start, count), raw in sorted(replacements.items(), reverse=True):
            lines[start - 1:start - 1 + count] = [r.rstrip() for r in raw]
        path.write_text("\n".join(lines), encoding="utf-8")
        print(f"updated {name}: {len(replacements)} output(s) replaced by the real ones", flush=True)
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("readmes", nargs="+", type=pathlib.Path, help="README files, relative to --source-dir")
    parser.add_argument("--rockfit", required=True, type=pathlib.Path, help="the built program")
    parser.add_argument("--python-module-dir", type=pathlib.Path,
                        help="the directory of the built Python module (build/python); without it, commands that "
                             "use build/python fail")
    parser.add_argument("--python", default=SYSTEM_PYTHON,
                        help=f"the interpreter the module was built for, replacing {SYSTEM_PYTHON} in commands")
    parser.add_argument("--without-python", action="store_true",
                        help="skip the commands that use build/python (a build without the Python module)")
    parser.add_argument("--source-dir", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent.parent,
                        help="the repository (default: this script's)")
    parser.add_argument("--update", action="store_true", help="write the real outputs into the READMEs")
    parser.add_argument("--keep", action="store_true", help="keep the scratch copies (their paths are printed)")
    args = parser.parse_args()

    source = args.source_dir.resolve()
    rockfit = args.rockfit.resolve()
    if not os.access(rockfit, os.X_OK):
        print(f"check_readme.py: {rockfit} is not an executable program; pass the built rockfit with --rockfit",
              file=sys.stderr)
        return 2
    module_dir = args.python_module_dir.resolve() if args.python_module_dir else None
    try:
        parsed = [(source / readme, parse_readme(source / readme, readme)) for readme in args.readmes]
    except (OSError, ReadmeError) as error:
        print(f"check_readme.py: {error}", file=sys.stderr)
        return 2

    failures = 0
    commands = 0
    started = time.time()
    for path, blocks in parsed:
        scratch = make_scratch(source, rockfit, module_dir)
        try:
            failures += check_readme(path, path.relative_to(source), blocks, scratch, args.python,
                                     not args.without_python, args.update)
            commands += sum(len(block) for block in blocks)
        finally:
            if args.keep:
                print(f"scratch copy for {path}: {scratch}")
            else:
                shutil.rmtree(scratch, ignore_errors=True)
    print(f"{commands} command(s) of {len(parsed)} README(s) in {time.time() - started:.0f} s: "
          f"{'all shown outputs match' if not failures else f'{failures} differ'}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
