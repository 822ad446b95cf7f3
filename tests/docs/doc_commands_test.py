#!/usr/bin/python3
"""Executable documentation: runs every command of the shell code blocks, and every python block,
of the docs, short and in a temporary copy of the tree, and checks the exit status the text implies.

Usage (BIN_DIR: the built executables; SOURCE_DIR: the repository; --build-dir: the CMake build
directory, by default BIN_DIR's parent):

  doc_commands_test.py BIN_DIR SOURCE_DIR --list             one line per test: ID LABELS LOCKS (for CMake)
  doc_commands_test.py BIN_DIR SOURCE_DIR --show [DOC...]    the commands, as printed and as run
  doc_commands_test.py BIN_DIR SOURCE_DIR --check-extraction every document yields its commands
  doc_commands_test.py BIN_DIR SOURCE_DIR --run DOC:LINE     runs one test (exit 77: skipped)
  doc_commands_test.py BIN_DIR SOURCE_DIR --all [DOC...]     runs every test of the documents
  doc_commands_test.py BIN_DIR SOURCE_DIR --negative-control proves that a broken command fails

What is run. A documented command is a tested command: every logical line of the fenced sh, bash
and shell blocks, and of console blocks the lines starting with `$ `, whatever its first word
(wsntrack, build/bin/..., tools/..., cmake, cpack, dpkg-deb, python3 -c, false, ...). Lines ending
in `\\` are joined; a trailing `# comment` is dropped. Lines that only set shell variables or only
`cd DIR` run before the later commands of their block instead of on their own. A python block
(python, python3 or py) is one command, run whole by /usr/bin/python3 from the workspace root
(traceback line numbers are the document's). Never run, but listed as skipped with the reason:
`./setup.sh` lines (they apt-get and build) and the blocks marked `<!-- doc-test: skip REASON -->`.
Each command is one ctest test, docs.DOC:LINE (its first line), run with the commands it needs.

How a command is run. In a fresh workspace: a copy of SOURCE_DIR without .git, build* and runs, and
BIN_DIR first on PATH (so `wsntrack` is the built one), as `bash -c` with pipefail. The workspace's
`build/` is a directory of links to every entry of the build directory, `build/bin` to BIN_DIR:
`cmake --install build ...` and `(cd build && cpack ...)` use the real build tree, while what a
command writes into `build/` itself (cpack's package and _CPack_Packages) stays in the workspace
and no stale package from the real tree is seen. Only these arguments change, and the log shows
the command as run (`wsntrack`, `sweep.py` and `plot_run.py` by their basename, so an installed
copy such as PREFIX/bin/wsntrack is shortened like the repository's):
  wsntrack run       --ticks N (default 20), and --out runs/doc-LINE when it has none;
  sweep.py, wsntrack sweep   only the first of --seeds, --set run.ticks=N unless it sets fewer ticks
                     already, --out when it has none;
  build/bin/*_bench  --benchmark_repetitions=1 and --benchmark_min_time=0.01.
An --out outside the workspace becomes runs/doc-abs-NAME, except under /tmp. Paths under /tmp that
a test's commands name (/tmp/NAME/...) are used as printed and /tmp/NAME is removed before and
after the test, so a stale one cannot make it pass; tests naming the same /tmp/NAME hold a ctest
RESOURCE_LOCK of that name (and flock /tmp/.NAME.doc-test-lock, against the suite of another build
tree run at the same time), and tests that use the build tree beyond build/bin (`build`,
`build/...`) hold the lock `build_tree` (tests/install's cpack and cmake --install take it too).
A failing test's workspace is kept with --keep-failed (ctest passes it), for its runs' logs.
A command (or python block) that names a path an earlier command of the same document wrote with
`--out PATH` or `--prefix PATH` gets that command (and its own such predecessors) run first, in
the same workspace.

Exit status. 0 unless the text says otherwise, by a trailing comment on the command line
(`wsntrack validate bad.yaml   # exit 1`) or by a directive: an HTML comment, invisible when the
markdown is rendered, right before the block (only blank lines or other directives between):
  <!-- doc-test: exit N -->            every command of the block must exit N
  <!-- doc-test: skip REASON -->       the block is not run; the test reports REASON as skipped
  <!-- doc-test: timeout S -->         per-command limit (default 300 s)
  <!-- doc-test: slow REASON -->       the test takes over a minute even shortened: label `slow`,
                                       with the reason where the label is given
  <!-- doc-test: ticks N -->           run length of the block's runs and sweeps instead of --ticks
                                       (for output that names a later tick)
  <!-- doc-test: sequence -->          the block's commands are one test (the first one's id), run
                                       in order in one workspace, up to the first failure (for
                                       commands that read what an earlier one wrote, other than
                                       by --out/--prefix: cpack, then dpkg-deb on its package)
  <!-- doc-test: background [wait-for=PATH] -->
        the block's first command (a paced `wsntrack run`, say) runs in the background while the
        block's other commands run -- or, when it is alone in its block, the next shell block's
        (the terminal-1 / terminal-2 pattern). With wait-for they start once PATH exists. The
        background command must end with its own expected status too.
"""

import argparse
import fcntl
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

# Documents that must yield at least this many commands (python blocks included): an extractor
# that silently finds nothing (a renamed fence, a changed prompt) must fail, not pass. Any other
# docs/*.md: 0.
EXPECTED_MIN_COMMANDS = {
    "README.md": 24,
    "scenarios/README.md": 2,
    "examples/README.md": 2,
    "docs/AGGREGATION.md": 2,
    "docs/MCMCDA.md": 3,
    "docs/NETWORK.md": 2,
    "docs/RULEBASED.md": 3,
}
# ... and at least this many python blocks.
EXPECTED_MIN_PYTHON_BLOCKS = {"README.md": 1}
SHELL_LANGUAGES = {"sh", "bash", "shell", "console"}
PYTHON_LANGUAGES = {"python", "python3", "py"}
PYTHON = "/usr/bin/python3"  # Debian's, with numpy and matplotlib: what the docs' python needs
# Installed copies of these are shortened like the repository's (an install prefix's bin/, share/.../tools/).
WSNTRACK = "wsntrack"
TOOL_NAMES = {"sweep.py", "plot_run.py"}
DEFAULT_TICKS = 20
DEFAULT_TIMEOUT_S = 300.0
SKIP_EXIT = 77  # ctest SKIP_RETURN_CODE
BUILD_TREE_LOCK = "build_tree"
ASSIGNMENT = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*=")
# A line that only sets a shell variable (NAME=word, NAME="...", NAME='...' or NAME=$(...)): the
# block's later commands may use it, so it runs before them.
ONLY_ASSIGNMENT = re.compile(r"""^(export\s+)?[A-Za-z_][A-Za-z0-9_]*=(\$\(.*\)|"[^"]*"|'[^']*'|[^\s;&|]*)$""")
# Likewise a line that only changes directory: alone it would test nothing.
ONLY_CD = re.compile(r"^cd\s+[^\s;&|()<>]+$")
DIRECTIVE = re.compile(r"^\s*<!--\s*doc-test:\s*(.*?)\s*-->\s*$")
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([^\s`]*)")
SHELL_SPECIAL = re.compile(r"[$`|;&<>()]")
# A top-level entry of /tmp that a command names: written as printed, removed before and after.
TMP_PATH = re.compile(r"(?<![\w./-])/tmp/([A-Za-z0-9_+-][A-Za-z0-9_.+-]*)")


class DocError(Exception):
    """A document the extractor cannot read unambiguously: reported as file:line."""


@dataclass
class Command:
    doc: str
    line: int
    text: str  # as printed: continuation lines joined, trailing comment dropped; a python block whole
    kind: str  # wsntrack, bin, tool, setup, shell or python
    expected_exit: int = 0
    prelude: list = field(default_factory=list)  # the block's assignments and cd lines before it
    skip_reason: str = ""
    slow_reason: str = ""  # doc-test: slow: the test takes over a minute, and why
    timeout_s: float = DEFAULT_TIMEOUT_S
    ticks: int = 0  # the block's own run length (doc-test: ticks), 0: the runner's

    @property
    def id(self):
        return f"{self.doc}:{self.line}"

    @property
    def summary(self):
        """One line for logs: the command, or what a python block is."""
        if self.kind != "python":
            return self.text
        lines = self.text.splitlines()
        return (f"python block of {len(lines)} line{'' if len(lines) == 1 else 's'}, run by {PYTHON}: "
                f"{lines[0].strip()} ...")


@dataclass
class Block:
    index: int
    line: int
    commands: list
    directives: dict


@dataclass
class Unit:
    """What one ctest test runs: one command, a sequence block, or a background command with the
    commands that run beside it."""
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


def program_words(words):
    """The words from the program on: VAR=value prefixes dropped, and `python3 SCRIPT` read as SCRIPT."""
    i = 0
    while i < len(words) and ASSIGNMENT.match(words[i]):
        i += 1
    rest = words[i:]
    if rest and Path(rest[0]).name in ("python3", "python") and len(rest) > 1 and not rest[1].startswith("-"):
        rest = rest[1:]
    return rest


def classify(text):
    """The kind of a logical line: wsntrack, bin, tool, setup, shell, or prelude (assignment, cd)."""
    if ONLY_ASSIGNMENT.match(text) or ONLY_CD.match(text):
        return "prelude"
    words = program_words(split_words(text))
    if not words:
        return "shell"
    first = words[0][2:] if words[0].startswith("./") else words[0]
    name = Path(first).name
    if name == WSNTRACK:
        return "wsntrack"
    if first.startswith("build/bin/"):
        return "bin"
    if first.startswith("tools/") or name in TOOL_NAMES:
        return "tool"
    if first == "setup.sh":
        return "setup"
    return "shell"


def parse_directives(lines):
    result = {}
    for number, text in lines:
        words = text.split(None, 1)
        key, rest = words[0], (words[1] if len(words) > 1 else "")
        if key == "skip":
            if not rest:
                raise DocError(f"{number}: 'doc-test: skip' needs a reason")
            result["skip"] = rest
        elif key == "slow":
            if not rest:
                raise DocError(f"{number}: 'doc-test: slow' needs a reason")
            result["slow"] = rest
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
        elif key == "sequence":
            if rest:
                raise DocError(f"{number}: 'doc-test: sequence' takes no argument, got '{rest}'")
            result["sequence"] = True
        elif key == "background":
            result["background"] = True
            for option in rest.split():
                if option.startswith("wait-for="):
                    result["wait_for"] = option[len("wait-for="):]
                else:
                    raise DocError(f"{number}: unknown option '{option}' of 'doc-test: background'")
        else:
            raise DocError(f"{number}: unknown directive 'doc-test: {text}' "
                           "(expected skip, slow, exit, ticks, timeout, sequence or background)")
    if result.get("sequence") and result.get("background"):
        raise DocError(f"{lines[0][0]}: 'doc-test: sequence' and 'doc-test: background' exclude each other")
    return result


def extract_blocks(doc, text):
    """Every shell and python block of a document with its commands, in document order."""
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
        runnable = language in SHELL_LANGUAGES or language in PYTHON_LANGUAGES
        if pending and not runnable:
            raise DocError(f"{doc}:{pending[0][0]}: doc-test directive before a '{language or 'plain'}' "
                           "block (only sh, bash, shell, console and python blocks are run)")
        if language in PYTHON_LANGUAGES and (directives.get("background") or directives.get("sequence")):
            raise DocError(f"{doc}:{pending[0][0]}: a python block runs whole; 'background' and "
                           "'sequence' are for shell blocks")
        pending = []
        if language in SHELL_LANGUAGES:
            commands = block_commands(doc, body, language == "console", directives)
        elif language in PYTHON_LANGUAGES:
            commands = python_commands(doc, body, directives)
        else:
            continue
        if directives.get("sequence") and any(c.kind == "setup" for c in commands):
            raise DocError(f"{doc}:{number}: a 'doc-test: sequence' block cannot hold ./setup.sh (never run)")
        blocks.append(Block(len(blocks), number, commands, directives))
    if pending:
        raise DocError(f"{doc}:{pending[0][0]}: a doc-test directive must come right before a code block")
    return blocks


def new_command(doc, number, text, kind, expected, prelude, directives):
    command = Command(doc, number, text, kind, expected, list(prelude),
                      timeout_s=directives.get("timeout", DEFAULT_TIMEOUT_S), ticks=directives.get("ticks", 0))
    command.slow_reason = directives.get("slow", "")
    if "skip" in directives:
        command.skip_reason = directives["skip"]
    elif kind == "setup":
        command.skip_reason = ("./setup.sh installs packages with apt-get and builds the tree; "
                               "the suite runs inside that build")
    return command


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
        if kind == "prelude":
            prelude.append(code)
            continue
        expected = directives.get("exit", 0)
        status = re.search(r"\bexit\s+(\d+)\b", comment)
        if status:
            expected = int(status.group(1))
        commands.append(new_command(doc, number, code, kind, expected, prelude, directives))
    return commands


def python_commands(doc, body, directives):
    """A python block is one command: its source, first line numbered as in the document."""
    source = "\n".join(raw for _, raw in body)
    if not source.strip():
        return []
    return [new_command(doc, body[0][0], source + "\n", "python", directives.get("exit", 0), [], directives)]


def documents(source, chosen=None):
    """The documents whose commands are tested, relative to the source directory."""
    if chosen:
        return list(chosen)
    docs = ["README.md", "scenarios/README.md"]
    docs += sorted(str(p.relative_to(source)) for p in (source / "docs").glob("*.md"))
    docs.append("examples/README.md")
    return docs


def units_of(doc, blocks):
    """One unit per command, except that a background block takes the commands that follow it and
    a sequence block is one unit."""
    units = []
    taken = set()
    for block in blocks:
        if block.directives.get("sequence") and block.commands:
            units.append(Unit(block.commands[0], list(block.commands)))
            taken.update(c.id for c in block.commands)
        if not block.directives.get("background"):
            continue
        if not block.commands:
            raise DocError(f"{doc}:{block.line}: 'doc-test: background' on a block without a command")
        main, rest = block.commands[0], block.commands[1:]
        if not rest:
            following = [b for b in blocks if b.index > block.index and b.commands]
            if not following:
                raise DocError(f"{doc}:{block.line}: 'doc-test: background' needs commands to run beside it")
            if following[0].directives.get("sequence"):
                raise DocError(f"{doc}:{following[0].line}: a 'doc-test: sequence' block cannot run beside "
                               f"the background command of {doc}:{block.line}")
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


def outs_of(command):
    """The paths a command writes by --out or --prefix, as printed: what later commands may name."""
    if command.kind == "python":
        return []
    words = split_words(command.text)
    return [value for value in (option_value(words, name)[0] for name in ("--out", "--prefix")) if value]


def set_ticks_of(words):
    """The run lengths a sweep already fixes with --set run.ticks=N."""
    values = []
    for i, word in enumerate(words):
        value = words[i + 1] if word == "--set" and i + 1 < len(words) else \
            word[len("--set="):] if word.startswith("--set=") else None
        if value and value.startswith("run.ticks="):
            number = value[len("run.ticks="):]
            values.append(int(number) if number.isdigit() else None)
    return values


def rewrite(command, ticks):
    """The command as the test runs it: short, and writing only inside the workspace or /tmp."""
    if command.kind == "python":
        return command.text
    ticks = command.ticks or ticks
    words = split_words(command.text)
    prefix_len = 0
    while prefix_len < len(words) and ASSIGNMENT.match(words[prefix_len]):
        prefix_len += 1
    prefix, words = words[:prefix_len], words[prefix_len:]
    program = program_words(words)
    name = Path(program[0]).name if program else ""
    changed = list(words)
    if command.kind == "wsntrack" and len(program) > 1 and program[1] == "run":
        value, _ = option_value(words, "--ticks")
        changed = set_option(changed, "--ticks", str(min(int(value), ticks) if value and value.isdigit() else ticks))
        changed = with_local_out(changed, f"runs/doc-{command.line}")
    elif (command.kind == "tool" and name == "sweep.py") or \
            (command.kind == "wsntrack" and len(program) > 1 and program[1] == "sweep"):
        seeds, _ = option_value(words, "--seeds")
        if seeds:
            changed = set_option(changed, "--seeds", re.split(r"[-,]", seeds)[0])
        fixed = set_ticks_of(words)
        # The last --set wins in sweep.py: a sweep already shorter than N keeps its own length.
        if not fixed or fixed[-1] is None or fixed[-1] > ticks:
            changed = changed + ["--set", f"run.ticks={ticks}"]
        changed = with_local_out(changed, f"runs/doc-sweep-{command.line}")
    elif command.kind == "bin" and name.endswith("_bench"):
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
    if value.startswith("/tmp/") and TMP_PATH.match(value):
        return words  # named /tmp paths are the test's own: removed before and after, locked by name
    if os.path.isabs(value) or value.startswith(".."):
        # Never elsewhere outside the workspace: an absolute --out keeps its last component only.
        return set_option(words, "--out", "runs/doc-abs-" + Path(value).name)
    return words


def command_text(command):
    return "\n".join(command.prelude + [command.text])


def dependencies(unit, units):
    """Units whose --out/--prefix path this unit's commands name, nearest first producer each, in order."""
    own_outs = {o for c in unit.commands for o in outs_of(c)}
    text = "\n".join(command_text(c) for c in unit.commands)
    needed = []
    for out in {o for u in units for c in u.commands for o in outs_of(c)} - own_outs:
        pattern = r"(?<![\w./-])" + re.escape(out.rstrip("/")) + r"(?![\w.-])"
        if not re.search(pattern, text):
            continue
        producers = [u for u in units if u.main.line < unit.main.line and u is not unit
                     and any(out in outs_of(c) for c in u.commands)]
        if producers:
            needed.append(producers[-1])
    chain = []
    for producer in sorted(needed, key=lambda u: u.main.line):
        for u in dependencies(producer, units) + [producer]:
            if u not in chain:
                chain.append(u)
    return chain


def test_commands(unit, units):
    """Every command one test runs: its dependencies' and its own."""
    return [c for u in dependencies(unit, units) + [unit] for c in u.commands]


def labels_of(unit, units):
    labels = ["docs"]
    for c in test_commands(unit, units):
        words = program_words(split_words(c.text)) if c.kind != "python" else []
        # Every wsntrack run, sweep and live viewer starts or joins a cluster on loopback.
        if (c.kind == "wsntrack" and any(w in ("run", "watch", "sweep") for w in words[1:3])) or \
                (c.kind == "tool" and "sweep.py" in c.text) or "watch_tracks" in c.text:
            labels.append("cluster")
            break
    if any(c.slow_reason for c in test_commands(unit, units)):
        labels.append("slow")
    return labels


def uses_build_tree(command):
    """Whether a command reaches into the build tree beyond build/bin (install, cpack, its package)."""
    if command.kind == "python":
        return False
    for line in command.prelude + [command.text]:
        for word in split_words(line):
            word = word.strip("()")
            if word == "build" or (word.startswith("build/") and word != "build/bin"
                                   and not word.startswith("build/bin/")):
                return True
    return False


def tmp_paths(commands):
    """The top-level /tmp entries the commands name: the test owns them while it runs."""
    names = {m.group(1) for c in commands for m in TMP_PATH.finditer(command_text(c))}
    return sorted(Path("/tmp") / name for name in names if name not in (".", ".."))


def locks_of(unit, units):
    """The ctest RESOURCE_LOCKs of a test: what it shares with tests that may run beside it."""
    commands = test_commands(unit, units)
    locks = [str(path) for path in tmp_paths(commands)]
    if any(uses_build_tree(c) for c in commands):
        locks.insert(0, BUILD_TREE_LOCK)
    return locks


# ---------------------------------------------------------------------------------------------
# Running


class Workspace:
    """A throw-away copy of the repository: runs write here, never into the source tree."""

    def __init__(self, bin_dir, build_dir, source, keep):
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
        build = self.path / "build"
        build.mkdir()
        # Links to the real tree's entries rather than one link to the tree: what a command creates
        # in build/ (cpack's package, _CPack_Packages) lands here, beside no stale package of the
        # real tree, and goes with the workspace. The build tree's own files keep absolute paths,
        # so cmake --install and cpack through these links act on the real tree.
        if build_dir and (build_dir / "CMakeCache.txt").is_file():
            for entry in build_dir.iterdir():
                if entry.name in ("bin", "Testing", "_CPack_Packages") or entry.name.endswith((".deb", ".ddeb")):
                    continue
                (build / entry.name).symlink_to(entry)
        (build / "bin").symlink_to(bin_dir)
        self.env = dict(os.environ)
        self.env["PATH"] = f"{bin_dir}{os.pathsep}{self.env.get('PATH', '')}"
        # A run writes its own loopback-only Cyclone configuration; an inherited one must not leak in.
        self.env.pop("CYCLONEDDS_URI", None)

    def close(self, ok, keep_failed=False):
        if self.keep or (keep_failed and not ok):
            print(f"    workspace kept{'' if ok else ' for its logs (remove it when done)'}: {self.path}")
            return
        shutil.rmtree(self.path, ignore_errors=True)
        if not ok:
            print("    (--keep keeps the workspace with the run directories and each command's log)")


def remove_paths(paths):
    for path in paths:
        if path.is_symlink() or path.is_file():
            path.unlink()
        elif path.is_dir():
            shutil.rmtree(path)


def lock_paths(paths):
    """Exclusive locks on the test's /tmp paths, held until the process ends. ctest's RESOURCE_LOCK
    keeps one ctest run from running two such tests at once; this also keeps apart the suites of two
    build trees (build/ and build-asan/, say) run side by side, which name the same paths."""
    held = []
    for path in paths:
        lock = open(path.parent / f".{path.name}.doc-test-lock", "a")
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            print(f"    waiting for {path}: another doc test uses it")
            sys.stdout.flush()
            fcntl.flock(lock, fcntl.LOCK_EX)
        held.append(lock)
    return held


def start(command, script, workspace, log_path):
    log = open(log_path, "wb")
    if command.kind == "python":
        # Blank lines first, so that a traceback's line numbers are the document's.
        source = workspace.path / f"doc-test-{command.line}.py"
        source.write_text("\n" * (command.line - 1) + script, encoding="utf-8")
        argv = [PYTHON, source.name]
    else:
        argv = ["bash", "-c", "set -o pipefail\n" + "\n".join(command.prelude + [script])]
    process = subprocess.Popen(argv, cwd=workspace.path, env=workspace.env, stdout=log, stderr=subprocess.STDOUT,
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
    print(f"    as printed: {command.summary}")
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
        # A sequence stops at its first failure: the commands after it read what it should have made.
        for i, command in enumerate(unit.foreground):
            if not run_command(command, workspace, ticks, role):
                for rest in unit.foreground[i + 1:]:
                    print(f"[FAIL] {rest.id}: not run, {command.id} before it in its sequence failed")
                return False
        return True
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


def run_test(unit, units, paths, ticks, keep, keep_failed=False):
    """One test: its --out/--prefix predecessors, then the unit itself, in one fresh workspace."""
    bin_dir, build_dir, source = paths
    if unit.main.skip_reason:
        print(f"[skip] {unit.id}: {unit.main.summary}\n    reason: {unit.main.skip_reason}")
        return None
    owned = tmp_paths(test_commands(unit, units))
    if owned:
        print(f"    /tmp paths of this test, removed before and after it: {' '.join(map(str, owned))}")
    locks = lock_paths(owned)
    remove_paths(owned)
    workspace = Workspace(bin_dir, build_dir, source, keep)
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
        workspace.close(ok, keep_failed)
        if keep:
            if owned:
                print(f"    kept too: {' '.join(map(str, owned))}")
        else:
            remove_paths(owned)
        for lock in locks:
            lock.close()
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
        python = [c for c in commands if c.kind == "python"]
        want = EXPECTED_MIN_COMMANDS.get(doc, 0) if minimum is None else minimum
        want_python = EXPECTED_MIN_PYTHON_BLOCKS.get(doc, 0) if minimum is None else 0
        good = len(commands) >= want and len(python) >= want_python
        failures += not good
        print(f"[{'ok  ' if good else 'FAIL'}] {doc}: {len(commands)} commands in {len(units)} tests "
              f"({len(skipped)} skipped, {len(python)} python block{'' if len(python) == 1 else 's'}), "
              f"expected at least {want}"
              + (f" ({want_python} python)" if want_python else ""))
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


def run_all(paths, doc_root, docs, ticks, keep):
    results = {"passed": [], "failed": [], "skipped": []}
    began = time.monotonic()
    for _, unit, units in all_units(doc_root, docs):
        ok = run_test(unit, units, paths, ticks, keep)
        results["skipped" if ok is None else "passed" if ok else "failed"].append(unit.id)
    print(f"\n{len(results['passed'])} passed, {len(results['failed'])} failed, "
          f"{len(results['skipped'])} skipped in {time.monotonic() - began:.0f} s")
    for name in results["failed"]:
        print(f"  failed: {name}")
    return 1 if results["failed"] else 0


# broken.md names this path; the negative control leaves a stale copy there first.
STALE_FIXTURE_PATH = Path("/tmp/wsntrack-doc-fixture-stale")


def negative_control(paths, ticks):
    """Runs the runner on fixture documents that are broken on purpose; passes only if it says so."""
    bin_dir, build_dir, source = paths
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
          "[FAIL] broken.md:35: exit 1, expected 0",  # false: not a wsntrack command, run all the same
          "[FAIL] broken.md:36: exit 1, expected 0",  # cmake --install nonexistent-dir
          "[ok  ] broken.md:37: exit 0",
          "[skip] broken.md:38:",  # ./setup.sh, never run
          "[FAIL] broken.md:44: exit 1, expected 0",  # it would pass on a stale /tmp path
          "[FAIL] broken.md:50: exit 1, expected 0",  # a python block is run too
          "line 50, in <module>",  # and its traceback's line numbers are the document's
          "[ok  ] broken.md:54: exit 0",  # from the workspace root
          "[ok  ] broken.md:60: exit 0",  # a sequence: the second command reads what the first wrote
          "[ok  ] broken.md:61: exit 0",
          "5 passed, 6 failed, 2 skipped"]),
        ("the ctest test of the broken command fails on its own",
         ["--run", "broken.md:9", "--source-docs", str(fixture_dir)], 1,
         ["[FAIL] broken.md:9: exit 2, expected 0"]),
        ("the ctest test of a failing non-wsntrack line fails on its own",
         ["--run", "broken.md:36", "--source-docs", str(fixture_dir)], 1,
         ["[FAIL] broken.md:36: exit 1, expected 0"]),
        ("a document without commands fails extraction",
         ["--check-extraction", "--minimum", "1", "--source-docs", str(fixture_dir), "no_commands.md"], 1,
         ["[FAIL] no_commands.md: 0 commands"]),
        ("a directive that is not right before a block fails extraction",
         ["--check-extraction", "--source-docs", str(fixture_dir), "stray_directive.md"], 1,
         ["FAIL extraction: stray_directive.md:4: a doc-test directive must come right before a code block"]),
    ]
    failures = 0
    for what, arguments, want_status, want_lines in checks:
        if "--all" in arguments:
            # A stale result of an earlier run must not make broken.md:44 pass: the runner removes it.
            STALE_FIXTURE_PATH.mkdir(exist_ok=True)
            (STALE_FIXTURE_PATH / "left-by-an-earlier-run").write_text("stale\n")
        result = subprocess.run([sys.executable, str(here), str(bin_dir), str(source), "--build-dir", str(build_dir),
                                 "--ticks", str(ticks)] + arguments, capture_output=True, text=True, timeout=600)
        missing = [line for line in want_lines if line not in result.stdout]
        ok = result.returncode == want_status and not missing
        if "--all" in arguments and STALE_FIXTURE_PATH.exists():
            print(f"    {STALE_FIXTURE_PATH} is still there: the runner must remove a test's /tmp paths after it")
            ok = False
        failures += not ok
        print(f"[{'ok  ' if ok else 'FAIL'}] {what}: exit {result.returncode} (expected {want_status})")
        for line in missing:
            print(f"    missing from the output: {line}")
        if not ok:
            print("    output:\n" + "\n".join("    | " + line for line in (result.stdout + result.stderr).splitlines()))
    remove_paths([STALE_FIXTURE_PATH])
    return 1 if failures else 0


def show(doc_root, docs, ticks):
    for doc, unit, units in all_units(doc_root, docs):
        for command in unit.commands:
            print(f"{command.id} [{'background ' if unit.background and command is unit.main else ''}"
                  f"exit {command.expected_exit}] "
                  + (command.text if command.kind != "python" else command.summary))
            shown = rewrite(command, ticks)
            if shown != command.text:
                print(f"    as run: {shown}")
            if command.skip_reason:
                print(f"    skipped: {command.skip_reason}")
        for setup in dependencies(unit, units):
            print(f"    after: {setup.id}")
        locks = locks_of(unit, units)
        if locks:
            print(f"    locks: {' '.join(locks)}")


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
    parser.add_argument("--build-dir", type=Path, default=None,
                        help="the CMake build directory behind the workspace's build/ (default: BIN_DIR/..)")
    parser.add_argument("--ticks", type=int, default=DEFAULT_TICKS)
    parser.add_argument("--minimum", type=int, default=None, help="commands every document must yield")
    parser.add_argument("--source-docs", type=Path, default=None,
                        help="read the documents from here instead of SOURCE_DIR (the fixtures)")
    parser.add_argument("--keep", action="store_true", help="keep every workspace (and the /tmp paths)")
    parser.add_argument("--keep-failed", action="store_true",
                        help="keep the workspace of a failing test, for the logs of its runs (ctest passes it)")
    args = parser.parse_intermixed_args(argv)
    bin_dir, source = args.bin_dir.resolve(), args.source_dir.resolve()
    build_dir = (args.build_dir or args.bin_dir.parent).resolve()
    paths = (bin_dir, build_dir, source)
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
                        print(unit.id, ",".join(labels_of(unit, units)), ",".join(locks_of(unit, units)) or "-")
                except DocError as error:
                    print(f"not listed: {error}", file=sys.stderr)
            return 0
        if args.show:
            show(doc_root, docs, args.ticks)
            return 0
        if args.check_extraction:
            return check_extraction(doc_root, docs, args.ticks, args.minimum)
        if args.run:
            doc = args.run.rsplit(":", 1)[0]
            for _, unit, units in all_units(doc_root, [doc]):
                if unit.id == args.run:
                    ok = run_test(unit, units, paths, args.ticks, args.keep, args.keep_failed)
                    return SKIP_EXIT if ok is None else 0 if ok else 1
            print(f"no command starts at {args.run}; the document changed since CMake listed its tests "
                  "(re-run cmake)")
            return 1
        if args.all:
            return run_all(paths, doc_root, docs, args.ticks, args.keep)
        if args.negative_control:
            return negative_control(paths, args.ticks)
    except DocError as error:
        print(f"FAIL extraction: {error}")
        return 1
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
