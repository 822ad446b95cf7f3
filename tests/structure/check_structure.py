#!/usr/bin/python3
"""Keeps the source tree in the shape STYLE.md asks for: files that fit in a head, functions that
fit on a screen or two, and includes that only point down the layering of the CMake link graph.

Checked, in every non-test source file (C and C++ .cpp/.hpp/.h/.c and Python .py under the
source root's non-hidden top-level folders; tests/ and build trees, i.e. any folder holding a
CMakeCache.txt or named build*, are skipped):

  size       a file has over MAX_FILE_LINES lines;
  function   a C++ or Python function has over MAX_FUNCTION_LINES lines;
  layering   a file in one folder of LAYERS includes ("#include "folder/..."") a folder of the same
             or a higher layer, or either folder is missing from LAYERS. A file that defines main()
             is an executable's entry point, which the link graph puts above every library it links
             (a role's main.cpp links its role library and the scenario loader): it may include any
             folder.

Each problem is printed as "path:line: what (measure, limit)"; the exit status is 1 when there is
any, 0 when there is none, 2 on bad usage.

Python functions are measured with the standard library's ast: end_lineno - lineno + 1 of every
def and async def, nested ones included (decorators are not counted).

C++ functions are measured by a scanner, not a compiler, so it relies on the house style (one
declaration per statement, code that compiles). It works in two passes:

  1. Blanking. Comments (// and /* */), string literals (with escapes and the u8/u/U/L prefixes),
     raw strings (R"delim( ... )delim", with any prefix), character literals and preprocessor
     directives (with their backslash continuations) are replaced by spaces, newlines kept, so no
     brace, parenthesis or semicolon inside them is seen and line numbers stay true. A quote
     inside a number (C++14 digit separator, 1'000'000) is part of the number.
  2. Brace matching. Outside function bodies (at namespace and class scope), the text since the
     last ';', '{' or '}' of that scope is the "head" of the next '{'. The head decides the block:
       - namespace, extern "C", class, struct, union: a scope, scanned the same way inside;
       - enum, an initializer (a head with a top-level '=' not followed by a lambda, or without a
         parameter list) and a brace inside an unclosed '(' (a call's argument): data, skipped to
         its matching '}';
       - a head with a top-level parameter list "( ... )" followed only by qualifiers (const,
         noexcept, override, final, mutable, &, &&, a trailing "-> type"), or by a constructor's
         initializer list (": member(...), member{...}", whose brace initializers belong to the
         head; the body is the brace after a ')' or '}'), or a variable initialized by a lambda
         ("auto f = [...](...) {"): a function.
     A function spans from the first line of its head (template line and attributes included,
     access specifiers and blanked comments not) to the line of its matching '}'. Everything in a
     body, lambdas and local classes included, counts toward the enclosing function.
  Limits: a lambda inside a namespace-scope initializer (a table of field descriptions) is not
  measured on its own, and code under "#if 0" is scanned like any other.

Usage: check_structure.py [--root DIR]     check the tree at DIR (default: the repository root)
       check_structure.py --self-test      check that each kind of problem is caught, and that
                                           the limits themselves pass, on fixture trees
"""

import argparse
import ast
import os
import re
import sys
import tempfile

MAX_FILE_LINES = 700
MAX_FUNCTION_LINES = 120

# The layering of the CMake link graph, bottom first. A folder may include itself and any folder of
# a lower layer; folders of one layer are independent of each other. The deepest listed folder that
# holds a file (or prefixes an include) is the one it belongs to.
#   common            wsn_common_core, wsn_config_yaml: nothing that knows a component
#   idl, common/dds   the generated DDS types; the RAII layer over Cyclone and the role runtime
#   node, network_model  the sensor models and the network model, each over common
#   scenario          the scenario loader, which links the sensor models to read their keys
#   observation_model the statistics behind the engines' derived parameters (links node, network)
#   supernode         the window and the engines
#   aggregator        track association (links the MCMCDA engine) and metrics
#   launcher, bench, examples  the wsntrack command and the programs beside it
LAYERS = [
    ["common"],
    ["idl", "common/dds"],
    ["node", "network_model"],
    ["scenario"],
    ["observation_model"],
    ["supernode"],
    ["aggregator"],
    ["launcher", "bench", "examples", "fuzz"],
]

CPP_SUFFIXES = (".cpp", ".hpp", ".h", ".c")
SKIPPED_TOP_FOLDERS = {"tests"}
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_ROOT = os.path.dirname(os.path.dirname(HERE))


# ----------------------------------------------------------------------------------------------
# Which files


def is_build_tree(path, name):
    return name.startswith("build") or os.path.exists(os.path.join(path, "CMakeCache.txt"))


def source_files(root):
    """Relative paths of the checked files, sorted."""
    found = []
    for top in sorted(os.listdir(root)):
        top_path = os.path.join(root, top)
        if top.startswith(".") or top in SKIPPED_TOP_FOLDERS or not os.path.isdir(top_path):
            continue
        if is_build_tree(top_path, top):
            continue
        for folder, dirs, files in os.walk(top_path):
            dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "__pycache__"
                             and not is_build_tree(os.path.join(folder, d), d))
            for name in files:
                if name.endswith(CPP_SUFFIXES) or name.endswith(".py"):
                    found.append(os.path.relpath(os.path.join(folder, name), root))
    return sorted(found)


def read_text(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


# ----------------------------------------------------------------------------------------------
# C++: blanking


_LITERAL_PREFIXES = {"u8", "u", "U", "L"}
_RAW_PREFIXES = {"R", "u8R", "uR", "UR", "LR"}


def blank_cpp(text):
    """text with comments, literals and preprocessor directives replaced by spaces (newlines kept)."""
    out = list(text)
    n = len(text)

    def blank(begin, end):
        for k in range(begin, min(end, n)):
            if out[k] != "\n":
                out[k] = " "

    def quoted_end(i, quote):
        # i is just past the opening quote; returns the index just past the closing one.
        while i < n and text[i] != quote and text[i] != "\n":
            i += 2 if text[i] == "\\" else 1
        return min(i + 1, n)

    at_line_start = True  # only whitespace so far on this line
    i = 0
    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if c in " \t\r\f\v":
            i += 1
            continue
        if c == "#" and at_line_start:
            end = i
            while end < n and text[end] != "\n":
                end += 2 if text[end] == "\\" and end + 1 < n and text[end + 1] == "\n" else 1
                # A comment inside a directive ends with the directive or runs past it (/* ... */).
                if text.startswith("/*", end):
                    close = text.find("*/", end + 2)
                    end = n if close < 0 else close + 2
            blank(i, end)
            i = end
            continue
        at_line_start = False
        if text.startswith("//", i):
            end = text.find("\n", i)
            end = n if end < 0 else end
            blank(i, end)
            i = end
        elif text.startswith("/*", i):
            close = text.find("*/", i + 2)
            end = n if close < 0 else close + 2
            blank(i, end)
            i = end
        elif c == '"':
            end = quoted_end(i + 1, '"')
            blank(i + 1, end - 1)
            i = end
        elif c == "'":
            end = quoted_end(i + 1, "'")
            blank(i + 1, end - 1)
            i = end
        elif c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
            # A pp-number: digits, letters, '.', digit separators and exponent signs.
            i += 1
            while i < n and (text[i].isalnum() or text[i] in "._'" or
                             (text[i] in "+-" and text[i - 1] in "eEpP")):
                i += 1
        elif c.isalpha() or c == "_":
            start = i
            while i < n and (text[i].isalnum() or text[i] == "_"):
                i += 1
            word = text[start:i]
            if i < n and text[i] == '"' and word in _RAW_PREFIXES:
                open_paren = text.find("(", i + 1)
                delimiter = text[i + 1:open_paren] if open_paren >= 0 else ""
                close = text.find(")" + delimiter + '"', open_paren + 1) if open_paren >= 0 else -1
                end = n if close < 0 else close + len(delimiter) + 2
                blank(i + 1, end - 1)
                i = end
            elif i < n and text[i] in "\"'" and word in _LITERAL_PREFIXES:
                end = quoted_end(i + 1, text[i])
                blank(i + 1, end - 1)
                i = end
        else:
            i += 1
    return "".join(out)


# ----------------------------------------------------------------------------------------------
# C++: functions

_ACCESS = re.compile(r"^\s*(?:(?:public|private|protected)\s*:(?!:)\s*)+")
_SCOPE_HEAD = re.compile(r"^\s*(?:(?:inline\s+)?namespace|extern|class|struct|union)\b")
_ENUM_HEAD = re.compile(r"^\s*(?:typedef\s+)?enum\b")
_QUALIFIERS = re.compile(r"^(?:\s*(?:(?:const|volatile|noexcept|override|final|mutable|try)\b|&&|&))*\s*"
                         r"(?:->.*)?$", re.S)
_TEMPLATE = re.compile(r"^\s*template\s*<")
_OPERATOR_BEFORE = re.compile(r"\boperator\s*[-+*/%^&|<>!=]*$")
_INITIALIZER_LIST = re.compile(r"^[\s\w&]*:(?!:)", re.S)
_NAME_BEFORE_PAREN = re.compile(r"((?:[A-Za-z_~][\w]*\s*::\s*)*(?:operator\s*[^\s(]+|operator\s*\(\s*\)|~?[A-Za-z_]\w*))"
                                r"\s*(?:<[^()]*>)?\s*$")


def top_level_parens(head):
    """(open, close) index pairs of the parenthesis groups of head at depth 0."""
    groups, depth, start = [], 0, -1
    for k, c in enumerate(head):
        if c == "(":
            if depth == 0:
                start = k
            depth += 1
        elif c == ")" and depth > 0:
            depth -= 1
            if depth == 0:
                groups.append((start, k))
    return groups


def top_level_equals(head):
    """Index of the first '=' at parenthesis depth 0 that is an assignment (not ==, <=, >=, !=)."""
    depth = 0
    for k, c in enumerate(head):
        if c in "([":
            depth += 1
        elif c in ")]":
            depth -= 1
        elif c == "=" and depth == 0:
            before = head[k - 1] if k > 0 else ""
            after = head[k + 1] if k + 1 < len(head) else ""
            if before not in "=<>!" and after != "=" and not _OPERATOR_BEFORE.search(head[:k]):
                return k
    return -1


def without_template_parameters(head):
    """head without a leading "template <...>" (its defaults hold '=' and parentheses of their own)."""
    m = _TEMPLATE.match(head)
    if not m:
        return head
    depth, k = 1, m.end()
    while k < len(head) and depth > 0:
        depth += {"<": 1, ">": -1}.get(head[k], 0)
        k += 1
    return head[k:]


def classify_head(head):
    """'scope', 'data', 'function', or 'initializer-list' for a ctor whose body is still to come."""
    head = without_template_parameters(_ACCESS.sub("", head))
    if not head.strip() or _ENUM_HEAD.match(head) or head.count("(") != head.count(")"):
        return "data"  # an unclosed '(' puts the brace inside a call: an argument
    equals = top_level_equals(head)
    if equals >= 0:
        return "function" if head[equals + 1:].lstrip().startswith("[") else "data"
    groups = top_level_parens(head)
    if groups:
        if _INITIALIZER_LIST.match(head[groups[0][1] + 1:]):
            return "initializer-list"
        if _QUALIFIERS.match(head[groups[-1][1] + 1:]):
            return "function"
    return "scope" if _SCOPE_HEAD.match(head) else "data"


def function_name(head):
    head = without_template_parameters(_ACCESS.sub("", head))
    equals = top_level_equals(head)
    if equals >= 0:
        words = re.findall(r"[A-Za-z_]\w*", head[:equals])
        return words[-1] if words else "lambda"
    groups = top_level_parens(head)
    if groups:
        m = _NAME_BEFORE_PAREN.search(head[:groups[0][0]])
        if m:
            return re.sub(r"\s+", "", m.group(1))
    return "function"


def matching_brace(code, open_index):
    depth = 0
    for k in range(open_index, len(code)):
        if code[k] == "{":
            depth += 1
        elif code[k] == "}":
            depth -= 1
            if depth == 0:
                return k
    return len(code) - 1


def cpp_functions(text):
    """(name, first line, last line) of every function defined in C or C++ text."""
    code = blank_cpp(text)
    line_starts = [0] + [k + 1 for k, c in enumerate(code) if c == "\n"]

    def line_of(index):
        lo, hi = 0, len(line_starts) - 1
        while lo < hi:
            mid = (lo + hi + 1) // 2
            if line_starts[mid] <= index:
                lo = mid
            else:
                hi = mid - 1
        return lo + 1

    functions = []

    def scan_scope(begin, end):
        head_start = begin
        k = begin
        while k < end:
            c = code[k]
            if c in ";}":
                head_start = k + 1
            elif c == "{":
                head = code[head_start:k]
                kind = classify_head(head)
                if kind == "initializer-list":
                    before = code[head_start:k].rstrip()
                    if before and before[-1] not in ")}":
                        k = matching_brace(code, k) + 1  # a member's brace initializer
                        continue
                    kind = "function"
                close = matching_brace(code, k)
                if kind == "function":
                    stripped = _ACCESS.sub("", head)
                    first = head_start + (len(head) - len(stripped)) + (len(stripped) - len(stripped.lstrip()))
                    functions.append((function_name(head), line_of(first), line_of(close)))
                elif kind == "scope":
                    scan_scope(k + 1, close)
                k = close + 1
                head_start = k
                continue
            k += 1

    scan_scope(0, len(code))
    return functions


# ----------------------------------------------------------------------------------------------
# Python: functions


def python_functions(text, path):
    tree = ast.parse(text, filename=path)
    return [(node.name, node.lineno, node.end_lineno) for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))]


# ----------------------------------------------------------------------------------------------
# Layering

_INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layer_of_folder():
    return {folder: level for level, folders in enumerate(LAYERS) for folder in folders}


def folder_of(path, layers, root):
    """The deepest folder of LAYERS that holds path; else its top-level folder (a directory of root)."""
    parts = path.split("/")
    for depth in range(len(parts) - 1, 0, -1):
        candidate = "/".join(parts[:depth])
        if candidate in layers:
            return candidate
    if len(parts) > 1 and os.path.isdir(os.path.join(root, parts[0])):
        return parts[0]
    return None


def include_problems(path, text, root, layers, is_executable):
    problems = []
    source = folder_of(path, layers, root)
    for number, line in enumerate(text.splitlines(), start=1):
        m = _INCLUDE.match(line)
        if not m:
            continue
        target = folder_of(m.group(1), layers, root)
        if target is None or target == source:
            continue
        for folder in (source, target):
            if folder not in layers:
                problems.append(f"{path}:{number}: includes \"{m.group(1)}\", but folder {folder}/ is not in "
                                "the layering (LAYERS in tests/structure/check_structure.py)")
        if source in layers and target in layers and layers[target] >= layers[source] and not is_executable:
            where = "above" if layers[target] > layers[source] else "beside"
            problems.append(f"{path}:{number}: {source}/ includes \"{m.group(1)}\" from {target}/, which is "
                            f"{where} it in the layering (layer {layers[target]} >= {layers[source]})")
    return problems


# ----------------------------------------------------------------------------------------------
# The check


def check(root):
    """Every problem of the tree at root, as "path:line: what" strings."""
    problems = []
    layers = layer_of_folder()
    for path in source_files(root):
        text = read_text(os.path.join(root, path))
        lines = len(text.splitlines())
        if lines > MAX_FILE_LINES:
            problems.append(f"{path}:1: file has {lines} lines (limit {MAX_FILE_LINES})")
        if path.endswith(".py"):
            try:
                functions = python_functions(text, path)
            except SyntaxError as e:
                problems.append(f"{path}:{e.lineno}: cannot parse: {e.msg}")
                functions = []
        else:
            functions = cpp_functions(text)
            is_executable = any(name == "main" for name, _, _ in functions)
            problems.extend(include_problems(path, text, root, layers, is_executable))
        for name, first, last in functions:
            length = last - first + 1
            if length > MAX_FUNCTION_LINES:
                problems.append(f"{path}:{first}: function {name} has {length} lines (limit {MAX_FUNCTION_LINES})")
    return problems


# ----------------------------------------------------------------------------------------------
# Self-test: fixture trees with one problem each, and the limits themselves


def cpp_function_of(lines, name="tooLong"):
    """A C++ function of exactly `lines` lines whose body hides braces in every kind of literal."""
    tricky = [
        '  const char* s = "}}} { \\" }";',
        "  const char c = '}';",
        "  const char d = '\\'';",
        '  const char* r = R"x(})}" { )x";',
        "  // } a closing brace in a comment",
        "  /* { an opening one */",
        "  const long big = 1'000'000;",
        "  const auto f = [](int a) {",
        "    return a + 1;",
        "  };",
        "#define BRACE }",
    ]
    body_lines = lines - 2
    assert body_lines >= len(tricky)
    body = tricky + ["  big;"] * (body_lines - len(tricky))
    return [f"int {name}(int x) {{"] + body + ["}"]


def python_function_of(lines, name="too_long"):
    return [f"def {name}(x):"] + ["    x += 1"] * (lines - 2) + ["    return x"]


def write(root, path, lines):
    full = os.path.join(root, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "w") as f:
        f.write("\n".join(lines) + "\n")


def self_test():
    """0 when every fixture gives exactly the problems expected of it."""
    cases = {
        "a 701-line file": ({"common/big.hpp": ["// line"] * 701},
                            ["common/big.hpp:1: file has 701 lines (limit 700)"]),
        "a 700-line file": ({"common/fits.hpp": ["// line"] * 700, "tools/fits.py": ["x = 1"] * 700}, []),
        "a 121-line C++ function with braces in literals and comments":
            ({"node/f.cpp": ["namespace a {", "struct S {", "  int x{1};", "};", ""] + cpp_function_of(121) +
                             ["}  // namespace a"]},
             ["node/f.cpp:6: function tooLong has 121 lines (limit 120)"]),
        "a 120-line C++ function": ({"node/f.cpp": cpp_function_of(120)}, []),
        "a 121-line constructor with an initializer list":
            ({"node/c.cpp": ["S::S(int a)", "    : a_(a), b_{a, 2} {"] + ["  a;"] * 118 + ["}"]},
             ["node/c.cpp:1: function S::S has 121 lines (limit 120)"]),
        "a 121-line member function defined in its class":
            ({"node/m.hpp": ["class M {", " public:"] + ["  " + line for line in cpp_function_of(121, "run")] +
                            ["};"]},
             ["node/m.hpp:3: function run has 121 lines (limit 120)"]),
        "a 121-line lambda at namespace scope":
            ({"node/l.cpp": ["const auto handler = [](int x) {"] + ["  x;"] * 119 + ["};"]},
             ["node/l.cpp:1: function handler has 121 lines (limit 120)"]),
        "a 121-line Python function": ({"tools/f.py": ["import os", ""] + python_function_of(121)},
                                       ["tools/f.py:3: function too_long has 121 lines (limit 120)"]),
        "a 120-line Python function": ({"tools/f.py": python_function_of(120)}, []),
        "common/ including node/": ({"common/up.hpp": ['#include "node/tiling.hpp"'], "node/tiling.hpp": []},
                                    ['common/up.hpp:1: common/ includes "node/tiling.hpp" from node/, which is above '
                                     "it in the layering (layer 2 >= 0)"]),
        "node/ including network_model/ (one layer)":
            ({"node/side.cpp": ["", '#include "network_model/router.hpp"'], "network_model/router.hpp": []},
             ['node/side.cpp:2: node/ includes "network_model/router.hpp" from network_model/, which is beside it '
              "in the layering (layer 2 >= 2)"]),
        "common/ including common/dds/":
            ({"common/x.cpp": ['#include "common/dds/entity.hpp"'], "common/dds/entity.hpp": []},
             ['common/x.cpp:1: common/ includes "common/dds/entity.hpp" from common/dds/, which is above it in the '
              "layering (layer 1 >= 0)"]),
        "a role library including the scenario loader (only its main() may)":
            ({"node/role.cpp": ['#include "scenario/loader.hpp"', "int runRole() { return 0; }"]},
             ['node/role.cpp:1: node/ includes "scenario/loader.hpp" from scenario/, which is above it in the '
              "layering (layer 3 >= 2)"]),
        "a folder missing from the layering":
            ({"newfolder/a.cpp": ['#include "common/rng.hpp"'], "common/rng.hpp": []},
             ['newfolder/a.cpp:1: includes "common/rng.hpp", but folder newfolder/ is not in the layering']),
        "downward includes, tests/ and build trees":
            ({"launcher/main.cpp": ['#include "aggregator/role.hpp"', '#include "common/dds/entity.hpp"',
                                    '#include "wsntrack.h"', "#include <vector>"],
              "node/main.cpp": ['#include "node/role.hpp"', '#include "scenario/loader.hpp"',
                                "int main(int argc, char** argv) { return run(argc, argv); }"],
              "supernode/e.cpp": ['#include "scenario/scenario.hpp"', '#include "common/rng.hpp"'],
              "tests/big_test.cpp": ['#include "launcher/main.hpp"'] + cpp_function_of(300),
              "build/gen.cpp": cpp_function_of(300), "common/out/CMakeCache.txt": [],
              "common/out/gen.cpp": cpp_function_of(300)},
             []),
    }
    failures = 0
    for name, (files, expected) in cases.items():
        with tempfile.TemporaryDirectory(prefix="check_structure.") as root:
            for path, lines in files.items():
                write(root, path, lines)
            found = check(root)
        missing = [e for e in expected if not any(p.startswith(e) for p in found)]
        unexpected = [p for p in found if not any(p.startswith(e) for e in expected)]
        ok = not missing and not unexpected
        failures += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {name}")
        for p in missing:
            print(f"       not caught: {p}")
        for p in unexpected:
            print(f"       wrongly reported: {p}")
    print("self-test passed" if failures == 0 else f"self-test FAILED: {failures} case(s)")
    return 0 if failures == 0 else 1


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--root", default=DEFAULT_ROOT, help="source tree to check (default: %(default)s)")
    parser.add_argument("--self-test", action="store_true", help="check the checker on fixture trees")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    if not os.path.isdir(args.root):
        print(f"no such folder: {args.root}", file=sys.stderr)
        return 2
    problems = check(args.root)
    for problem in problems:
        print(problem)
    checked = len(source_files(args.root))
    print(f"{checked} files checked: {len(problems)} problem(s)" if problems else
          f"{checked} files checked: every file <= {MAX_FILE_LINES} lines, every function <= {MAX_FUNCTION_LINES} "
          f"lines, every include down the layering")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
