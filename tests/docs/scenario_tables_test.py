#!/usr/bin/env python3
"""The key tables of scenarios/README.md are those the code describes.

Every key of a scenario is described once, in a field table in the code (common/scenario_schema.cpp,
each engine's and association's paramTable()). `wsntrack components --markdown` prints those tables,
each between "<!-- table: NAME -->" and "<!-- end table -->". This test fails when a table of the
README differs from the code's, when the README lacks one, or has one the code does not.

    scenario_tables_test.py WSNTRACK README            check
    scenario_tables_test.py WSNTRACK README --update   rewrite the README's tables from the code
"""
import re
import subprocess
import sys

BLOCK = re.compile(r"<!-- table: (.+?) -->\n(.*?)<!-- end table -->\n", re.S)


def blocks(text):
    found = {}
    for match in BLOCK.finditer(text):
        if match.group(1) in found:
            raise SystemExit(f"FAIL: table '{match.group(1)}' appears twice")
        found[match.group(1)] = match.group(2)
    return found


def main():
    wsntrack, readme = sys.argv[1], sys.argv[2]
    update = sys.argv[3:] == ["--update"]
    generated = blocks(subprocess.run([wsntrack, "components", "--markdown"], check=True, capture_output=True,
                                      text=True).stdout)
    if not generated:
        raise SystemExit("FAIL: 'wsntrack components --markdown' printed no table")
    text = open(readme, encoding="utf-8").read()
    documented = blocks(text)
    missing = sorted(set(generated) - set(documented))
    unknown = sorted(set(documented) - set(generated))
    if update:
        if missing:
            raise SystemExit(f"cannot update: the README has no place for {missing}; add their markers first")
        text = BLOCK.sub(lambda m: f"<!-- table: {m.group(1)} -->\n{generated.get(m.group(1), m.group(2))}"
                                   "<!-- end table -->\n", text)
        open(readme, "w", encoding="utf-8").write(text)
        print(f"updated {len(documented)} tables of {readme}")
        return
    failures = [f"the README lacks the table '{name}'" for name in missing]
    failures += [f"the README has a table '{name}' that no component describes" for name in unknown]
    for name in sorted(set(generated) & set(documented)):
        if generated[name] != documented[name]:
            failures.append(f"table '{name}' differs from the code's:\n--- README\n{documented[name]}--- code\n"
                            f"{generated[name]}")
    if failures:
        print("FAIL:\n" + "\n".join(failures))
        print(f"(regenerate with: {sys.argv[0]} {wsntrack} {readme} --update)")
        sys.exit(1)
    print(f"OK: {len(generated)} tables of {readme} match the code")


if __name__ == "__main__":
    main()
