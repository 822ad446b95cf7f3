#!/usr/bin/python3
"""Executable documentation: extracts every `wsntrack ...`, `build/bin/...` and `tools/...` command from
the shell code blocks of the docs and runs it, short and into a temporary directory.

Usage (BIN_DIR: the built executables; SOURCE_DIR: the repository):

  doc_commands_test.py BIN_DIR SOURCE_DIR --list             one line per test: ID LABELS (for CMake)
  doc_commands_test.py BIN_DIR SOURCE_DIR --show [DOC...]    the commands, as printed and as run
  doc_commands_test.py BIN_DIR SOURCE_DIR --check-extraction every document yields its commands
  doc_commands_test.py BIN_DIR SOURCE_DIR --run DOC:LINE     runs one test (exit 77: skipped)
  doc_commands_test.py BIN_DIR SOURCE_DIR --all [DOC...]     runs every test of the documents
  doc_commands_test.py BIN_DIR SOURCE_DIR --negative-control proves that a broken command fails

What is extracted. Fenced blocks whose info string is sh, bash, shell or console (in console blocks
only the lines starting with `$ `). Lines ending in `\\` are joined; a trailing `# comment` is
dropped. A logical line is a command when its first word (after VAR=value prefixes, or after
python3) is `wsntrack`, `build/bin/...`, `tools/...` or `./setup.sh`; `./setup.sh` is never run
(it installs packages and builds). Lines that only assign shell variables are run before the later
commands of their block; every other line (cmake, ctest, ...) is left alone.

How a command is run. In a fresh workspace: a copy of SOURCE_DIR without .git, build* and runs, with
build/bin a link to BIN_DIR and BIN_DIR first on PATH (so `wsntrack` is the built one), as
`bash -c` with pipefail. Only these arguments change, and the log shows the command as run:
  wsntrack run       --ticks N (default 20), and --out runs/doc-LINE when it has none;
  tools/sweep.py     --set run.ticks=N, only the first of --seeds, --out when it has none;
  build/bin/*_bench  --benchmark_repetitions=1 and --benchmark_min_time=0.01.
A command that names a path an earlier command of the same document wrote with `--out PATH` gets
that command (and its own such predecessors) run first, in the same workspace.

Exit status. 0 unless the text says otherwise, by a trailing comment on the command line
(`wsntrack validate bad.yaml   # exit 1`) or by a directive: an HTML comment, invisible when the
markdown is rendered, right before the block (only blank lines or other directives between):
  <!-- doc-test: exit N -->            every command of the block must exit N
  <!-- doc-test: skip REASON -->       the block is not run; the test reports REASON as skipped
  <!-- doc-test: timeout S -->         per-command limit (default 300 s)
  <!-- doc-test: ticks N -->           run length of the block's runs and sweeps instead of --ticks
                                       (for output that names a later tick)
  <!-- doc-test: background [wait-for=PATH] -->
        the block's first command (a paced `wsntrack run`, say) runs in the background while the
        block's other commands run -- or, when it is alone in its block, the next shell block's
        (the terminal-1 / terminal-2 pattern). With wait-for they start once PATH exists. The
        background command must end with its own expected status too.
"""

import argparse
import os
import re
import shlex
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

# Documents that must yield at least this many commands: an extractor that silently finds
# nothing (a renamed fence, a changed prompt) must fail, not pass. Any other docs/*.md: 0.
EXPECTED_MIN_COMMANDS = {
    "README.md": 12,
    "scenarios/README.md": 2,
    "examples/README.md": 2,
    "docs/AGGREGATION.md": 2,
    "docs/MCMCDA.md": 3,
    "docs/NETWORK.md": 2,
    "docs/RULEBASED.md": 3,
}
SHELL_LANGUAGES = {"sh", "bash", "shell", "console"}
DEFAULT_TICKS = 20
DEFAULT_TIMEOUT_S = 300.0
SKIP_EXIT = 77  # ctest SKIP_RETURN_CODE
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
# A line that only sets a shell variable (NAME=word, NAME="...", NAME='...' or NAME=$(...)): the
# block's later commands may use it, so it runs before them.
ONLY_ASSIGNMENT = re.compile(r"""^(export\s+)?[A-Za-z_][A-Za-z0-9_]*=(\$\(.*\)|"[^"]*"|'[^']*'|[^\s;&|]*)$""")
DIRECTIVE = re.compile(r"^\s*<!--\s*doc-test:\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([^\s`]*)")
SHELL_SPECIAL = re.compile(r"[$`|;&<>()]")


class DocError(Exception):
    """A document the extractor cannot read unambiguously: reported as file:line."""


@dataclass
class Command:
    doc: str
    line: int
    text: str  # as printed: continuation lines joined, trailing comment dropped
    kind: str  # wsntrack, bin, tool, setup
    expected_exit: int = 0
    prelude: list = field(default_factory=list)  # the block's variable assignments before it
    skip_reason: str = ""
    timeout_s: float = DEFAULT_TIMEOUT_S
    ticks: int = 0  # the block's own run length (doc-test: ticks), 0: the runner's

    @property
    def id(self):
        return f"{self.doc}:{self.line}"


@dataclass
class Block:
    index: int
    line: int
    commands: list
    directives: dict


@dataclass
class Unit:
    """What one ctest test runs: one command, or a background command with the ones that follow it."""
    main: Command
    foreground: list  # commands run in order (for a background unit: while main runs)
    background: bool = False
    wait_for: str = ""

    @property
    def id(self):
        return self.main.id

    @property
    def commands(self):
        return ([self.main] if self.background else []) + self.foreground


# ---------------------------------------------------------------------------------------------
# Extraction


def strip_comment(text):
    """Splits a shell line into (code, comment) at the first unquoted `#` that starts a word."""
    quote = None
    i = 0
    while i < len(text):
        c = text[i]
        if quote:
            if c == "\\" and quote == '"':
                i += 1
            elif c == quote:
                quote = None
        elif c == "\\":
            i += 1
        elif c in "'\"":
            quote = c
        elif c == "#" and (i == 0 or text[i - 1].isspace()):
            return text[:i].rstrip(), text[i + 1:].strip()
        i += 1
    return text.rstrip(), ""


def split_words(text):
    try:
        return shlex.split(text)
    except ValueError:
        return text.split()


def classify(text):
    """The kind of a logical line: wsntrack, bin, tool, setup, assignment or None (not ours)."""
    if ONLY_ASSIGNMENT.match(text):
        return "assignment"
    words = split_words(text)
    i = 0
    while i < len(words) and ASSIGNMENT.match(words[i]):
        i += 1
    if i == len(words):
        return None
    first = words[i]
    if first in ("python3", "python", "/usr/bin/python3") and i + 1 < len(words):
        first = words[i + 1]
    first = first[2:] if first.startswith("./") else first
    if first in ("wsntrack", "build/bin/wsntrack"):
        return "wsntrack"
    if first.startswith("build/bin/"):
        return "bin"
    if first.startswith("tools/"):
        return "tool"
    if first == "setup.sh":
        return "setup"
    return None


def parse_directives(lines):
    result = {}
    for number, text in lines:
        words = text.split(None, 1)
        key, rest = words[0], (words[1] if len(words) > 1 else "")
        if key == "skip":
            if not rest:
                raise DocError(f"{number}: 'doc-test: skip' needs a reason")
            result["skip"] = rest
        elif key == "exit":
            if not rest.isdigit():
                raise DocError(f"{number}: 'doc-test: exit' needs a status, got '{rest}'")
            result["exit"] = int(rest)
        elif key == "ticks":
            if not rest.isdigit() or int(rest) < 1:
                raise DocError(f"{number}: 'doc-test: ticks' needs a number of ticks, got '{rest}'")
            result["ticks"] = int(rest)
        elif key == "timeout":
            try:
                result["timeout"] = float(rest)
            except ValueError:
                raise DocError(f"{number}: 'doc-test: timeout' needs seconds, got '{rest}'") from None
        elif key == "background":
            result["background"] = True
            for option in rest.split():
                if option.startswith("wait-for="):
                    result["wait_for"] = option[len("wait-for="):]
                else:
                    raise DocError(f"{number}: unknown option '{option}' of 'doc-test: background'")
        else:
            raise DocError(f"{number}: unknown directive 'doc-test: {text}' "
                           "(expected skip, exit, ticks, timeout or background)")
    return result


def extract_blocks(doc, text):
    """Every shell block of a document with its commands, in document order."""
    lines = text.splitlines()
    blocks = []
    pending = []  # (line, directive text) waiting for the next block
    i = 0
    while i < len(lines):
        number = i + 1
        directive = DIRECTIVE.match(lines[i])
        fence = FENCE.match(lines[i])
        if directive:
            pending.append((number, directive.group(1)))
            i += 1
            continue
        if not fence:
            if lines[i].strip() and pending:
                raise DocError(f"{doc}:{pending[0][0]}: a doc-test directive must come right before a code block")
            i += 1
            continue
        marker, language = fence.group(2), fence.group(3).lower()
        body = []
        i += 1
        while i < len(lines) and not (lines[i].strip().startswith(marker[0] * len(marker))
                                      and lines[i].strip().strip(marker[0]) == ""):
            body.append((i + 1, lines[i]))
            i += 1
        if i == len(lines):
            raise DocError(f"{doc}:{number}: code block not closed")
        i += 1
        try:
            directives = parse_directives(pending)
        except DocError as error:
            raise DocError(f"{doc}:{error}") from None
        if pending and language not in SHELL_LANGUAGES:
            raise DocError(f"{doc}:{pending[0][0]}: doc-test directive before a '{language or 'plain'}' "
                           "block (only sh, bash, shell and console blocks are run)")
        pending = []
        if language in SHELL_LANGUAGES:
            commands = block_commands(doc, body, language == "console", directives)
            blocks.append(Block(len(blocks), number, commands, directives))
    if pending:
        raise DocError(f"{doc}:{pending[0][0]}: a doc-test directive must come right before a code block")
    return blocks


def block_commands(doc, body, console, directives):
    commands = []
    prelude = []
    logical = []  # (first line, text) after joining continuations
    current, start = None, 0
    for number, raw in body:
        text = raw.rstrip()
        if current is None:
            if console:
                if not text.lstrip().startswith("$ "):
                    continue
                text = text.lstrip()[2:]
            current, start = "", number
        if text.endswith("\\"):
            current += text[:-1].rstrip() + " "
            continue
        logical.append((start, current + text.strip()))
        current = None
    if current is not None:
        raise DocError(f"{doc}:{start}: the command's last line ends with a backslash")
    for number, text in logical:
        code, comment = strip_comment(text.strip())
        if not code:
            continue
        kind = classify(code)
        if kind == "assignment":
            prelude.append(code)
            continue
        if kind is None:
            continue
        expected = directives.get("exit", 0)
        status = re.search(r"\bexit\s+(\d+)\b", comment)
        if status:
            expected = int(status.group(1))
        command = Command(doc, number, code, kind, expected, list(prelude),
                          timeout_s=directives.get("timeout", DEFAULT_TIMEOUT_S), ticks=directives.get("ticks", 0))
        if "skip" in directives:
            command.skip_reason = directives["skip"]
        elif kind == "setup":
            command.skip_reason = ("./setup.sh installs packages with apt-get and builds the tree; "
                                   "the suite runs inside that build")
        commands.append(command)
    return commands


def documents(source, chosen=None):
    """The documents whose commands are tested, relative to the source directory."""
    if chosen:
        return list(chosen)
    docs = ["README.md", "scenarios/README.md"]
    docs += sorted(str(p.relative_to(source)) for p in (source / "docs").glob("*.md"))
    docs.append("examples/README.md")
    return docs


def units_of(doc, blocks):
    """One unit per command, except that a background block takes the commands that follow it."""
    units = []
    taken = set()
    for block in blocks:
        if not block.directives.get("background"):
            continue
        if not block.commands:
            raise DocError(f"{doc}:{block.line}: 'doc-test: background' on a block without a command")
        main, rest = block.commands[0], block.commands[1:]
        if not rest:
            following = [b for b in blocks if b.index > block.index and b.commands]
            if not following:
                raise DocError(f"{doc}:{block.line}: 'doc-test: background' needs commands to run beside it")
            rest = following[0].commands
        units.append(Unit(main, rest, True, block.directives.get("wait_for", "")))
        taken.update(c.id for c in [main] + rest)
    for block in blocks:
        for command in block.commands:
            if command.id not in taken:
                units.append(Unit(command, [command]))
    units.sort(key=lambda u: u.main.line)
    return units


def extract(doc_root, docs):
    """{doc: [Unit]} for the given documents; DocError on anything ambiguous."""
    result = {}
    for doc in docs:
        path = doc_root / doc
        if not path.is_file():
            raise DocError(f"{doc}: no such document")
        blocks = extract_blocks(doc, path.read_text(encoding="utf-8"))
        result[doc] = units_of(doc, blocks)
    return result


# ---------------------------------------------------------------------------------------------
# Rewriting: short runs into the workspace


def option_value(words, name):
    """The value of --name VALUE or --name=VALUE, and the index of the word that holds it."""
    for i, word in enumerate(words):
        if word == name and i + 1 < len(words):
            return words[i + 1], i + 1
        if word.startswith(name + "="):
            return word[len(name) + 1:], i
    return None, -1


def set_option(words, name, value):
    _, index = option_value(words, name)
    if index < 0:
        return words + [name, value]
    words = list(words)
    if words[index].startswith(name + "="):
        words[index] = f"{name}={value}"
    else:
        words[index] = value
    return words


def out_of(command):
    """The directory a command writes with --out, as printed (relative to the repository)."""
    if command.kind not in ("wsntrack", "tool"):
        return None
    value, _ = option_value(split_words(command.text), "--out")
    return value


def rewrite(command, ticks):
    """The command as the test runs it: short, and writing only inside the workspace."""
    ticks = command.ticks or ticks
    words = split_words(command.text)
    prefix_len = 0
    while prefix_len < len(words) and ASSIGNMENT.match(words[prefix_len]):
        prefix_len += 1
    prefix, words = words[:prefix_len], words[prefix_len:]
    program = Path(words[0]).name if words else ""
    if program in ("python3", "python") and len(words) > 1:
        program = Path(words[1]).name
    changed = list(words)
    if command.kind == "wsntrack" and len(words) > 1 and words[1] == "run":
        value, _ = option_value(words, "--ticks")
        changed = set_option(changed, "--ticks", str(min(int(value), ticks) if value and value.isdigit() else ticks))
        changed = with_local_out(changed, f"runs/doc-{command.line}")
    elif command.kind == "tool" and program == "sweep.py":
        seeds, _ = option_value(words, "--seeds")
        if seeds:
            changed = set_option(changed, "--seeds", re.split(r"[-,]", seeds)[0])
        changed = changed + ["--set", f"run.ticks={ticks}"]
        changed = with_local_out(changed, f"runs/doc-sweep-{command.line}")
    elif command.kind == "bin" and program.endswith("_bench"):
        changed = [w for w in changed if not w.startswith(("--benchmark_repetitions", "--benchmark_min_time"))]
        changed += ["--benchmark_repetitions=1", "--benchmark_min_time=0.01"]
    if changed == words:
        return command.text
    if SHELL_SPECIAL.search(command.text):
        raise DocError(f"{command.id}: cannot shorten a command that uses shell syntax ($, |, ;, &, <, >, ()): "
                       "write it as one plain command")
    return shlex.join(prefix + changed)


def with_local_out(words, default):
    value, _ = option_value(words, "--out")
    if value is None:
        return words + ["--out", default]
    if os.path.isabs(value) or value.startswith(".."):
        # Never outside the workspace: an absolute --out keeps its last component only.
        return set_option(words, "--out", "runs/doc-abs-" + Path(value).name)
    return words


def dependencies(unit, units):
    """Units whose --out directory this unit's commands name, nearest first producer each, in order."""
    own_outs = {out_of(c) for c in unit.commands} - {None}
    text = "\n".join("\n".join(c.prelude + [c.text]) for c in unit.commands)
    needed = []
    for out in {o for u in units for o in (out_of(c) for c in u.commands)} - {None} - own_outs:
        pattern = r"(?<![\w./-])" + re.escape(out.rstrip("/")) + r"(?![\w.-])"
        if not re.search(pattern, text):
            continue
        producers = [u for u in units if u.main.line < unit.main.line and u is not unit
                     and any(out_of(c) == out for c in u.commands)]
        if producers:
            needed.append(producers[-1])
    chain = []
    for producer in sorted(needed, key=lambda u: u.main.line):
        for u in dependencies(producer, units) + [producer]:
            if u not in chain:
                chain.append(u)
    return chain


def labels_of(unit, units):
    commands = [c for u in dependencies(unit, units) + [unit] for c in u.commands]
    labels = ["docs"]
    for c in commands:
        words = split_words(c.text)
        # Every wsntrack run, sweep and live viewer starts or joins a cluster on loopback.
        if (c.kind == "wsntrack" and any(w in ("run", "watch") for w in words[:3])) or \
                (c.kind == "tool" and "sweep.py" in c.text) or "watch_tracks" in c.text:
            labels.append("cluster")
            break
    return labels


# ---------------------------------------------------------------------------------------------
# Running


class Workspace:
    """A throw-away copy of the repository: runs write here, never into the source tree."""

    def __init__(self, bin_dir, source, keep):
        self.path = Path(tempfile.mkdtemp(prefix="wsntrack-doc-"))
        self.keep = keep
        for entry in source.iterdir():
            # Build trees and earlier run outputs are large and never what a documented command reads.
            if entry.name in (".git", "runs", "__pycache__") or entry.name.startswith("build"):
                continue
            target = self.path / entry.name
            if entry.is_dir():
                shutil.copytree(entry, target, symlinks=True)
            else:
                shutil.copy2(entry, target)
        (self.path / "build").mkdir()
        (self.path / "build" / "bin").symlink_to(bin_dir)
        self.env = dict(os.environ)
        self.env["PATH"] = f"{bin_dir}{os.pathsep}{self.env.get('PATH', '')}"
        # A run writes its own loopback-only Cyclone configuration; an inherited one must not leak in.
        self.env.pop("CYCLONEDDS_URI", None)

    def close(self, ok):
        if self.keep:
            print(f"    workspace kept: {self.path}")
            return
        shutil.rmtree(self.path, ignore_errors=True)
        if not ok:
            print("    (--keep keeps the workspace with the run directories and each command's log)")


def start(command, script, workspace, log_path):
    log = open(log_path, "wb")
    process = subprocess.Popen(["bash", "-c", "set -o pipefail\n" + "\n".join(command.prelude + [script])],
                               cwd=workspace.path, env=workspace.env, stdout=log, stderr=subprocess.STDOUT,
                               stdin=subprocess.DEVNULL, start_new_session=True)
    log.close()
    return process


def stop(process):
    """Stops a command this test started, and everything it started, by its process group."""
    for sig, grace in ((signal.SIGTERM, 10), (signal.SIGKILL, 5)):
        try:
            os.killpg(process.pid, sig)
        except ProcessLookupError:
            return
        try:
            process.wait(timeout=grace)
            return
        except subprocess.TimeoutExpired:
            continue


def finish(process, timeout_s):
    try:
        return process.wait(timeout=timeout_s), False
    except subprocess.TimeoutExpired:
        stop(process)
        return process.returncode, True


def report(command, script, status, timed_out, elapsed, log_path, role=""):
    ok = not timed_out and status == command.expected_exit
    tag = "ok  " if ok else "FAIL"
    what = f" ({role})" if role else ""
    expected = f", expected {command.expected_exit}" if not ok else ""
    result = "timed out" if timed_out else f"exit {status}{expected}"
    print(f"[{tag}] {command.id}{what}: {result}, {elapsed:.1f} s")
    print(f"    as printed: {command.text}")
    if script != command.text:
        print(f"    as run:     {script}")
    if not ok:
        output = Path(log_path).read_text(errors="replace").splitlines()
        print(f"    output (last {min(len(output), 60)} of {len(output)} lines):")
        for line in output[-60:]:
            print("    | " + line)
    sys.stdout.flush()
    return ok


def run_command(command, workspace, ticks, role=""):
    script = rewrite(command, ticks)
    log_path = workspace.path / f"doc-test-{command.line}.log"
    began = time.monotonic()
    status, timed_out = finish(start(command, script, workspace, log_path), command.timeout_s)
    return report(command, script, status, timed_out, time.monotonic() - began, log_path, role)


def run_unit(unit, workspace, ticks, role=""):
    """Runs one unit in the workspace; True when every command exits as the document says."""
    if not unit.background:
        return run_command(unit.main, workspace, ticks, role)
    main = unit.main
    script = rewrite(main, ticks)
    log_path = workspace.path / f"doc-test-{main.line}.log"
    began = time.monotonic()
    process = start(main, script, workspace, log_path)
    ok = True
    if unit.wait_for:
        deadline = time.monotonic() + 60
        while not (workspace.path / unit.wait_for).exists():
            if process.poll() is not None or time.monotonic() > deadline:
                print(f"[FAIL] {main.id}: {unit.wait_for} did not appear "
                      f"({'the command ended' if process.poll() is not None else 'after 60 s'})")
                ok = False
                break
            time.sleep(0.05)
    if ok:
        for command in unit.foreground:
            ok = run_command(command, workspace, ticks, f"beside {main.id}") and ok
    status, timed_out = finish(process, main.timeout_s)
    return report(main, script, status, timed_out, time.monotonic() - began, log_path,
                  role or "background") and ok


def run_test(unit, units, bin_dir, source, ticks, keep):
    """One test: its --out predecessors, then the unit itself, in one fresh workspace."""
    if unit.main.skip_reason:
        print(f"[skip] {unit.id}: {unit.main.text}\n    reason: {unit.main.skip_reason}")
        return None
    workspace = Workspace(bin_dir, source, keep)
    ok = True
    try:
        for setup in dependencies(unit, units):
            if setup.main.skip_reason:
                print(f"[FAIL] {unit.id} needs {setup.id}, which is skipped: {setup.main.skip_reason}")
                ok = False
                break
            if not run_unit(setup, workspace, ticks, f"setup for {unit.id}"):
                print(f"[FAIL] {unit.id}: its setup {setup.id} failed")
                ok = False
                break
        if ok:
            ok = run_unit(unit, workspace, ticks)
    finally:
        workspace.close(ok)
    return ok


# ---------------------------------------------------------------------------------------------
# Modes


def check_extraction(doc_root, docs, ticks, minimum=None):
    """Every document yields at least its expected number of commands, and each can be rewritten."""
    failures = 0
    try:
        extracted = extract(doc_root, docs)
    except DocError as error:
        print(f"FAIL extraction: {error}")
        return 1
    for doc, units in extracted.items():
        commands = [c for u in units for c in u.commands]
        skipped = [c for c in commands if c.skip_reason]
        want = EXPECTED_MIN_COMMANDS.get(doc, 0) if minimum is None else minimum
        status = "ok  " if len(commands) >= want else "FAIL"
        if len(commands) < want:
            failures += 1
        print(f"[{status}] {doc}: {len(commands)} commands in {len(units)} tests "
              f"({len(skipped)} skipped), expected at least {want}")
        for command in commands:
            try:
                rewrite(command, ticks)
            except DocError as error:
                print(f"[FAIL] {error}")
                failures += 1
    return 1 if failures else 0


def all_units(doc_root, docs):
    extracted = extract(doc_root, docs)
    return [(doc, unit, units) for doc, units in extracted.items() for unit in units]


def run_all(bin_dir, source, doc_root, docs, ticks, keep):
    results = {"passed": [], "failed": [], "skipped": []}
    began = time.monotonic()
    for _, unit, units in all_units(doc_root, docs):
        ok = run_test(unit, units, bin_dir, source, ticks, keep)
        results["skipped" if ok is None else "passed" if ok else "failed"].append(unit.id)
    print(f"\n{len(results['passed'])} passed, {len(results['failed'])} failed, "
          f"{len(results['skipped'])} skipped in {time.monotonic() - began:.0f} s")
    for name in results["failed"]:
        print(f"  failed: {name}")
    return 1 if results["failed"] else 0


def negative_control(bin_dir, source, ticks):
    """Runs the runner on fixture documents that are broken on purpose; passes only if it says so."""
    here = Path(__file__).resolve()
    fixture_dir = here.parent / "fixtures"
    checks = [
        # (what, arguments, expected exit status, lines the output must contain)
        ("a broken command fails the document",
         ["--all", "--source-docs", str(fixture_dir), "broken.md"], 1,
         ["[FAIL] broken.md:9: exit 2, expected 0",  # the README's former gate_chi2 example
          "[FAIL] broken.md:17: exit 0, expected 2",  # a wrong '# exit 2'
          "[ok  ] broken.md:13: exit 2",  # a right '# exit 2'
          "[ok  ] broken.md:21: exit 0",
          "[skip] broken.md:28:",
          "2 passed, 2 failed, 1 skipped"]),
        ("the ctest test of the broken command fails on its own",
         ["--run", "broken.md:9", "--source-docs", str(fixture_dir)], 1,
         ["[FAIL] broken.md:9: exit 2, expected 0"]),
        ("a document without commands fails extraction",
         ["--check-extraction", "--minimum", "1", "--source-docs", str(fixture_dir), "no_commands.md"], 1,
         ["[FAIL] no_commands.md: 0 commands"]),
        ("a directive that is not right before a block fails extraction",
         ["--check-extraction", "--source-docs", str(fixture_dir), "stray_directive.md"], 1,
         ["FAIL extraction: stray_directive.md:4: a doc-test directive must come right before a code block"]),
    ]
    failures = 0
    for what, arguments, want_status, want_lines in checks:
        result = subprocess.run([sys.executable, str(here), str(bin_dir), str(source), "--ticks", str(ticks)]
                                + arguments, capture_output=True, text=True, timeout=600)
        missing = [line for line in want_lines if line not in result.stdout]
        ok = result.returncode == want_status and not missing
        failures += not ok
        print(f"[{'ok  ' if ok else 'FAIL'}] {what}: exit {result.returncode} (expected {want_status})")
        for line in missing:
            print(f"    missing from the output: {line}")
        if not ok:
            print("    output:\n" + "\n".join("    | " + line for line in (result.stdout + result.stderr).splitlines()))
    return 1 if failures else 0


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bin_dir", type=Path)
    parser.add_argument("source_dir", type=Path)
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--list", action="store_true")
    mode.add_argument("--show", action="store_true")
    mode.add_argument("--check-extraction", action="store_true")
    mode.add_argument("--run", metavar="DOC:LINE")
    mode.add_argument("--all", action="store_true")
    mode.add_argument("--negative-control", action="store_true")
    parser.add_argument("docs", nargs="*", help="documents relative to SOURCE_DIR (default: all)")
    parser.add_argument("--ticks", type=int, default=DEFAULT_TICKS)
    parser.add_argument("--minimum", type=int, default=None, help="commands every document must yield")
    parser.add_argument("--source-docs", type=Path, default=None,
                        help="read the documents from here instead of SOURCE_DIR (the fixtures)")
    parser.add_argument("--keep", action="store_true", help="keep every workspace")
    args = parser.parse_intermixed_args(argv)
    bin_dir, source = args.bin_dir.resolve(), args.source_dir.resolve()
    doc_root = args.source_docs.resolve() if args.source_docs else source
    # Fixture documents are read from their own directory, but run in a copy of the repository.
    docs = documents(doc_root, args.docs)

    try:
        if args.list:
            # A document the extractor cannot read loses its tests here and fails docs.extraction;
            # the other documents keep theirs.
            for doc in docs:
                try:
                    for _, unit, units in all_units(doc_root, [doc]):
                        print(unit.id, ",".join(labels_of(unit, units)))
                except DocError as error:
                    print(f"not listed: {error}", file=sys.stderr)
            return 0
        if args.show:
            for doc, unit, units in all_units(doc_root, docs):
                for command in unit.commands:
                    print(f"{command.id} [{'background ' if unit.background and command is unit.main else ''}"
                          f"exit {command.expected_exit}] {command.text}")
                    shown = rewrite(command, args.ticks)
                    if shown != command.text:
                        print(f"    as run: {shown}")
                    if command.skip_reason:
                        print(f"    skipped: {command.skip_reason}")
                for setup in dependencies(unit, units):
                    print(f"    after: {setup.id}")
            return 0
        if args.check_extraction:
            return check_extraction(doc_root, docs, args.ticks, args.minimum)
        if args.run:
            doc = args.run.rsplit(":", 1)[0]
            for _, unit, units in all_units(doc_root, [doc]):
                if unit.id == args.run:
                    ok = run_test(unit, units, bin_dir, source, args.ticks, args.keep)
                    return SKIP_EXIT if ok is None else 0 if ok else 1
            print(f"no command starts at {args.run}; the document changed since CMake listed its tests "
                  "(re-run cmake)")
            return 1
        if args.all:
            return run_all(bin_dir, source, doc_root, docs, args.ticks, args.keep)
        if args.negative_control:
            return negative_control(bin_dir, source, args.ticks)
    except DocError as error:
        print(f"FAIL extraction: {error}")
        return 1
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
